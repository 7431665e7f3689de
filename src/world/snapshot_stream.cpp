/// @file snapshot_stream.cpp
/// The snapshot writer and reader the 3D and the 2D worlds share, the header, the settings,
/// the contact and sensor events, and the state digest (snapshot_stream.hpp).
///
/// Steps of the reader: 1. measure the bytes left when the stream can seek (else count them
/// as unlimited: every loop still stops at the stream's end); 2. read byte by byte, counting
/// down, failing once at the end; 3. refuse a count whose elements the rest cannot hold.
#include "world/snapshot_stream.hpp"

#include <algorithm>
#include <cstring>
#include <limits>

namespace proxima {

namespace {
/// The bytes of a contact or a sensor event: two handles, two user data.
constexpr std::size_t kEventBytes = 32;
}  // namespace

void SnapshotWriter::u32(std::uint32_t v) {
  for (int k = 0; k < 4; ++k) u8(static_cast<std::uint8_t>(v >> (8 * k)));
}

void SnapshotWriter::u64(std::uint64_t v) {
  for (int k = 0; k < 8; ++k) u8(static_cast<std::uint8_t>(v >> (8 * k)));
}

void SnapshotWriter::real(Real x) {
  const double d = static_cast<double>(x);
  std::uint64_t bits;
  std::memcpy(&bits, &d, sizeof bits);
  u64(bits);
}

void SnapshotWriter::text(const std::string& s) {
  count(s.size());
  out_.write(s.data(), static_cast<std::streamsize>(s.size()));
}

SnapshotReader::SnapshotReader(std::istream& in) : in_(in), remaining_(std::numeric_limits<std::uint64_t>::max()) {
  const std::istream::pos_type start = in.tellg();
  if (start == std::istream::pos_type(-1)) return;
  in.seekg(0, std::ios::end);
  const std::istream::pos_type end = in.tellg();
  in.seekg(start);
  if (end != std::istream::pos_type(-1) && end >= start) remaining_ = static_cast<std::uint64_t>(end - start);
}

void SnapshotReader::fail(const std::string& field, const std::string& message) {
  if (!error_) error_ = make_error(ErrorCode::InvalidArgument, field, message);
}

std::uint8_t SnapshotReader::u8() {
  if (error_) return 0;
  const int c = in_.get();
  if (c == std::char_traits<char>::eof()) {
    fail("snapshot", "truncated: the stream ended early");
    return 0;
  }
  if (remaining_ != std::numeric_limits<std::uint64_t>::max() && remaining_ > 0) --remaining_;
  return static_cast<std::uint8_t>(c);
}

std::uint32_t SnapshotReader::u32() {
  std::uint32_t v = 0;
  for (int k = 0; k < 4; ++k) v |= std::uint32_t(u8()) << (8 * k);
  return v;
}

std::uint64_t SnapshotReader::u64() {
  std::uint64_t v = 0;
  for (int k = 0; k < 8; ++k) v |= std::uint64_t(u8()) << (8 * k);
  return v;
}

Real SnapshotReader::real() {
  const std::uint64_t bits = u64();
  double d;
  std::memcpy(&d, &bits, sizeof d);
  return static_cast<Real>(d);
}

std::string SnapshotReader::text() {
  const std::uint32_t n = count();
  std::string s;
  for (std::uint32_t k = 0; k < n && ok(); ++k) s.push_back(static_cast<char>(u8()));
  return s;
}

std::uint32_t SnapshotReader::count(std::size_t element_bytes) {
  const std::uint32_t n = u32();
  if (ok() && std::uint64_t(n) * std::max<std::size_t>(element_bytes, 1) > remaining_) {
    fail("snapshot", "truncated: a list of " + std::to_string(n) + " elements is longer than the rest of the stream");
  }
  return ok() ? n : 0;
}

void write_snapshot_header(SnapshotWriter& w, const char (&magic)[9], std::uint32_t version) {
  for (int k = 0; k < 8; ++k) w.u8(static_cast<std::uint8_t>(magic[k]));
  w.u32(version);
  w.u8(sizeof(Real));
}

std::optional<Error> read_snapshot_header(SnapshotReader& r, const char (&magic)[9], std::uint32_t version) {
  bool same = true;
  for (int k = 0; k < 8; ++k) same = r.u8() == static_cast<std::uint8_t>(magic[k]) && same;
  if (!r.ok() || !same) {
    return make_error(ErrorCode::InvalidArgument, "snapshot",
                      std::string("not a snapshot of this kind (magic ") + magic + ")");
  }
  const std::uint32_t saved = r.u32();
  if (r.ok() && saved != version) {
    return make_error(ErrorCode::InvalidArgument, "snapshot",
                      "unsupported version " + std::to_string(saved) + " (this library reads version " +
                          std::to_string(version) + ")");
  }
  r.u8();  // the writer's sizeof(Real): reals are doubles either way
  return r.error();
}

void write_settings(SnapshotWriter& w, const WorldSettings& s) {
  w.text(s.broadphase);
  w.real(s.contact_distance);
  w.u32(static_cast<std::uint32_t>(s.max_contacts));
  w.u8(static_cast<std::uint8_t>((s.sensors_sense_sensors ? 1 : 0) | (s.continuous ? 2 : 0)));
  w.real(s.ccd_safety_factor);
  w.real(s.ccd_tolerance);
}

WorldSettings read_settings(SnapshotReader& r) {
  WorldSettings s;
  s.broadphase = r.text();
  s.contact_distance = r.real();
  s.max_contacts = static_cast<int>(r.u32());
  const std::uint8_t flags = r.u8();
  s.sensors_sense_sensors = (flags & 1) != 0;
  s.continuous = (flags & 2) != 0;
  s.ccd_safety_factor = r.real();
  s.ccd_tolerance = r.real();
  return s;
}

void write_contact_events(SnapshotWriter& w, const std::vector<ContactEvent>& list) {
  w.count(list.size());
  for (const ContactEvent& e : list) {
    write_handle(w, e.pair.a);
    write_handle(w, e.pair.b);
    w.u64(e.user_data_a);
    w.u64(e.user_data_b);
  }
}

void read_contact_events(SnapshotReader& r, std::vector<ContactEvent>& list) {
  for (std::uint32_t n = r.count(kEventBytes), k = 0; k < n && r.ok(); ++k) {
    ContactEvent e;
    e.pair.a = read_handle(r);
    e.pair.b = read_handle(r);
    e.user_data_a = r.u64();
    e.user_data_b = r.u64();
    list.push_back(e);
  }
}

void write_sensor_events(SnapshotWriter& w, const std::vector<SensorEvent>& list) {
  w.count(list.size());
  for (const SensorEvent& e : list) {
    write_handle(w, e.sensor);
    write_handle(w, e.other);
    w.u64(e.user_data_sensor);
    w.u64(e.user_data_other);
  }
}

void read_sensor_events(SnapshotReader& r, std::vector<SensorEvent>& list) {
  for (std::uint32_t n = r.count(kEventBytes), k = 0; k < n && r.ok(); ++k) {
    SensorEvent e;
    e.sensor = read_handle(r);
    e.other = read_handle(r);
    e.user_data_sensor = r.u64();
    e.user_data_other = r.u64();
    list.push_back(e);
  }
}

void StateDigest::word(std::uint64_t v) {
  std::uint64_t z = (h ^ v) + 0x9E3779B97F4A7C15ull;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  h = z ^ (z >> 31);
}

void StateDigest::bytes(const void* p, std::size_t n) {
  const auto* c = static_cast<const unsigned char*>(p);
  for (std::size_t k = 0; k < n; k += 8) {
    std::uint64_t v = 0;
    std::memcpy(&v, c + k, std::min<std::size_t>(8, n - k));
    word(v);
  }
}

}  // namespace proxima
