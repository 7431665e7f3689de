#pragma once
// What the 3D and 2D capture recorders share about objects: the members every object record
// starts with, pose members, and the step's "poses" / "added" / "removed" found by comparing
// the live objects with what was last written (docs/capture-format.md). Internal.
#include <proxima/core/debug_draw.hpp>
#include <proxima/debug/capture_recorder.hpp>

#include <cstdint>
#include <functional>
#include <span>
#include <string>

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

}  // namespace proxima::debug::detail
