#pragma once
// What the 3D and 2D capture recorders share about objects: the members every object record
// starts with, pose members, and the step's "poses" / "added" / "removed" found by comparing
// the live objects with what was last written (docs/capture-format.md). Internal.
#include <proxima/core/debug_draw.hpp>
#include <proxima/debug/capture_recorder.hpp>

#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <sstream>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "debug/json_text.hpp"

namespace proxima::debug::detail {

/// A live object as a step line compares it: its id (the handle's integer) and its state.
struct LiveObject {
  std::uint64_t id = 0;
  CaptureObjectState state;
};

/// Appends "id", "kind", "sensor", "filter", "user_data", "ccd" and "color" (the members an
/// object record starts with, after its opening brace).
void object_members(std::string& out, std::uint64_t id, const CaptureObjectState& state, Rgba color);

/// Appends ,"position":[x,y,z],"rotation":[x,y,z,w].
void pose_members(std::string& out, const Transform& pose);

/// The step line's members ,"poses":[...],"added":[...],"removed":[...]: an object not
/// written before, marked stale, or changed in anything but its pose is added
/// (record(i) writes live[i]'s full record); one only moved gets a pose; one written but no
/// longer live is removed. `written` then holds the live objects' states.
std::string object_changes(CaptureObjectLog& written, std::span<const LiveObject> live,
                           const std::function<std::string(std::size_t)>& record);

/// The scene line of `world` (a CollisionWorld or d2::CollisionWorld): every live object's
/// full record (record(handle, desc)) and, when `snapshot`, the world's snapshot in base64;
/// `written` then holds each object's state (state_of(desc)).
template <class World, class Record, class StateOf>
std::string scene_line(const World& world, bool snapshot, CaptureObjectLog& written, const Record& record,
                       const StateOf& state_of) {
  std::string out = "{\"type\":\"scene\",\"objects\":[";
  bool first = true;
  for (const auto handle : world.objects()) {
    const auto desc = world.object(handle);
    if (!desc) continue;
    if (!first) out += ',';
    first = false;
    out += record(handle, *desc);
    written[handle.to_integer()] = state_of(*desc);
  }
  out += ']';
  if (snapshot) {
    std::ostringstream bytes;
    if (!world.save(bytes)) {
      json::key(out, "snapshot");
      json::string(out, json::base64(bytes.str()));
    }
  }
  out += '}';
  return out;
}

/// object_changes over the live objects of `world` (records by record(handle, desc), states
/// by state_of(desc)).
template <class World, class Record, class StateOf>
std::string object_changes(const World& world, CaptureObjectLog& written, const Record& record,
                           const StateOf& state_of) {
  using Handle = std::decay_t<decltype(world.objects().front())>;
  using Desc = std::decay_t<decltype(*world.object(Handle{}))>;
  std::vector<LiveObject> live;
  std::vector<std::pair<Handle, Desc>> objects;
  for (const Handle handle : world.objects()) {
    std::optional<Desc> desc = world.object(handle);
    if (!desc) continue;
    live.push_back({handle.to_integer(), state_of(*desc)});
    objects.emplace_back(handle, std::move(*desc));
  }
  return object_changes(written, live, [&](std::size_t i) { return record(objects[i].first, objects[i].second); });
}

}  // namespace proxima::debug::detail
