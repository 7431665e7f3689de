#pragma once
/// @file snapshot_stream.hpp
/// Internal: what the 3D and the 2D world snapshots (world/world_snapshot.cpp,
/// d2/world_snapshot.cpp) and state hashes (world/world_hash.cpp, d2/world_hash.cpp) share,
/// none of it depending on the dimension:
///   1. SnapshotWriter / SnapshotReader: little-endian integers, every real as an IEEE
///      double (exact for float), length-prefixed text. The reader keeps its first failure,
///      after which every read returns 0, and checks each count against the bytes the
///      stream still holds, so a truncated or forged stream ends every loop at once;
///   2. the header (magic, version, the writer's sizeof(Real)) and the world settings, and
///      the world they describe;
///   3. handles, and the contact and sensor events;
///   4. StateDigest: the state hashes' running splitmix64 digest.
#include <proxima/core/result.hpp>
#include <proxima/world/world_events.hpp>
#include <proxima/world/world_settings.hpp>

#include <cstdint>
#include <istream>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

namespace proxima {

/// Writes a snapshot's values to a stream.
class SnapshotWriter {
 public:
  /// A writer appending to `out`.
  explicit SnapshotWriter(std::ostream& out) : out_(out) {}
  /// One byte.
  void u8(std::uint8_t v) { out_.put(static_cast<char>(v)); }
  /// Four bytes, little-endian.
  void u32(std::uint32_t v);
  /// Eight bytes, little-endian.
  void u64(std::uint64_t v);
  /// A real as the bits of an IEEE double.
  void real(Real x);
  /// A length (u32), then the characters.
  void text(const std::string& s);
  /// A vector's length (u32): every list of a snapshot starts with it.
  void count(std::size_t n) { u32(static_cast<std::uint32_t>(n)); }

 private:
  std::ostream& out_;
};

/// Reads a snapshot's values; the first failure is kept and every later read returns 0.
class SnapshotReader {
 public:
  /// A reader of `in` from its current position (its length is measured when it can seek).
  explicit SnapshotReader(std::istream& in);
  /// True while no read has failed.
  bool ok() const { return !error_; }
  /// The first failure.
  const std::optional<Error>& error() const { return error_; }
  /// Records a failure naming `field` (the first one is kept).
  void fail(const std::string& field, const std::string& message);
  /// One byte (0 and a failure "snapshot" at the end of the stream).
  std::uint8_t u8();
  /// Four bytes, little-endian.
  std::uint32_t u32();
  /// Eight bytes, little-endian.
  std::uint64_t u64();
  /// A real written by SnapshotWriter::real.
  Real real();
  /// Text written by SnapshotWriter::text.
  std::string text();
  /// A list's length, each element at least `element_bytes` bytes: a failure "snapshot" (and
  /// 0) when the rest of the stream cannot hold that many.
  std::uint32_t count(std::size_t element_bytes = 1);

 private:
  std::istream& in_;
  std::uint64_t remaining_;  ///< bytes left in the stream (the largest value when unknown)
  std::optional<Error> error_;
};

/// Writes the magic (8 characters), the version and sizeof(Real).
void write_snapshot_header(SnapshotWriter& w, const char (&magic)[9], std::uint32_t version);
/// Reads and checks what write_snapshot_header wrote: an Error "snapshot" for another magic
/// (not this kind of snapshot) or another version.
std::optional<Error> read_snapshot_header(SnapshotReader& r, const char (&magic)[9], std::uint32_t version);

/// Writes every field of the settings.
void write_settings(SnapshotWriter& w, const WorldSettings& s);
/// Reads what write_settings wrote (validated by the world's create, not here).
WorldSettings read_settings(SnapshotReader& r);

/// Reads the header and the settings and creates the world they describe (World::create);
/// the Error of either, a settings field prefixed by "snapshot." ("snapshot.settings.x").
template <class World>
Result<World> create_from_snapshot(SnapshotReader& r, const char (&magic)[9], std::uint32_t version) {
  if (auto e = read_snapshot_header(r, magic, version)) return *e;
  const WorldSettings settings = read_settings(r);
  if (!r.ok()) return *r.error();
  Result<World> created = World::create(settings);
  if (!created.ok()) {
    Error e = created.error();
    e.field = "snapshot." + e.field;
    return e;
  }
  return created;
}

/// A handle as its integer.
inline void write_handle(SnapshotWriter& w, ObjectHandle h) { w.u64(h.to_integer()); }
/// A handle written by write_handle.
inline ObjectHandle read_handle(SnapshotReader& r) { return ObjectHandle::from_integer(r.u64()); }

/// A list of contact events (pair, user data).
void write_contact_events(SnapshotWriter& w, const std::vector<ContactEvent>& list);
/// Appends the contact events written by write_contact_events to `list`.
void read_contact_events(SnapshotReader& r, std::vector<ContactEvent>& list);
/// A list of sensor events (sensor, other, user data).
void write_sensor_events(SnapshotWriter& w, const std::vector<SensorEvent>& list);
/// Appends the sensor events written by write_sensor_events to `list`.
void read_sensor_events(SnapshotReader& r, std::vector<SensorEvent>& list);

/// A running 64-bit digest: each value folded in by splitmix64 (the W1 checksum's mixer).
struct StateDigest {
  std::uint64_t h = 0x243F6A8885A308D3ull;  ///< the digest so far

  /// Folds in one 64-bit value.
  void word(std::uint64_t v);
  /// Folds in `n` bytes, 8 at a time.
  void bytes(const void* p, std::size_t n);
  /// Folds in a real's bytes.
  void real(Real x) { bytes(&x, sizeof x); }
};

}  // namespace proxima
