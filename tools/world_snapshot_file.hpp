#pragma once
// The state operations the 3D and the 2D world protocols share (docs/world-protocol.md):
// the hash as text, and a world's snapshot written to or read from the request's "file"
// (CollisionWorld and d2::CollisionWorld alike: save / load on binary streams).
#include <cstdint>
#include <fstream>
#include <string>

#include "json_values.hpp"
#include "world_json.hpp"

namespace proxima::tool {

/// A state hash as 16 lowercase hex digits.
std::string hash_text(std::uint64_t hash);

/// The request's "file" member (error "missing" / "wrong_type").
inline std::string member_file(const Json& request) { return read_string(require_member(request, "", "file"), "file"); }

/// Writes `world`'s snapshot to the request's file; errors name "file".
template <class World>
void save_snapshot_file(const World& world, const Json& request) {
  const std::string file = member_file(request);
  std::ofstream out(file, std::ios::binary | std::ios::trunc);
  if (!out) throw FieldError("file", "invalid_argument", "cannot open \"" + file + "\" for writing");
  if (const auto error = world.save(out)) {
    throw FieldError("file", to_string(error->code), "writing \"" + file + "\": " + error->message);
  }
  out.flush();
  if (!out) throw FieldError("file", "invalid_argument", "writing \"" + file + "\" failed");
}

/// The world a snapshot in the request's file holds; errors name "file" with the library's
/// code and reason.
template <class World>
World load_snapshot_file(const Json& request) {
  const std::string file = member_file(request);
  std::ifstream in(file, std::ios::binary);
  if (!in) throw FieldError("file", "invalid_argument", "cannot open \"" + file + "\" for reading");
  Result<World> loaded = World::load(in);
  if (!loaded.ok()) {
    const Error& e = loaded.error();
    throw FieldError("file", to_string(e.code), "in \"" + file + "\": " + e.what());
  }
  return std::move(loaded).value();
}

}  // namespace proxima::tool
