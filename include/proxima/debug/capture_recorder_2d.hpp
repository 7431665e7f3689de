#pragma once
/// @file capture_recorder_2d.hpp
/// CaptureRecorder2D: writes a d2::CollisionWorld's steps to a capture
/// (docs/capture-format.md) with "dimension": 2, so that the web viewer and `proxima render`
/// show a 2D world in the plane z = 0: a header line, a scene line (every object with its
/// fill as a flat mesh, its pose as a turn about +z, and the world's snapshot in base64), then
/// one line per recorded step: the poses of the objects that moved, objects added and
/// removed, the world's events and manifolds (at z = 0), and a draw stream holding every
/// object's outline (a chain, which has no fill, as its segments and normals), the contacts
/// and impacts, and the caller's own primitives.
///
///   std::ofstream file("run.capture.jsonl");
///   debug::CaptureRecorder2D recorder(file);
///   for (...) { world.move(...); world.step(); recorder.record_step(world, dt); }
#include <proxima/core/debug_draw.hpp>
#include <proxima/core/result.hpp>
#include <proxima/d2/collision_world.hpp>
#include <proxima/debug/capture_recorder.hpp>
#include <proxima/debug/draw_world_2d.hpp>

#include <cstdint>
#include <iosfwd>
#include <optional>
#include <string>

namespace proxima::debug {

/// Writes a capture of one 2D world to a stream (see the file comment). The stream must
/// outlive the recorder. Of the options, `tessellation.segments` is the segments per turn of
/// round outlines and `draw_contacts` draws the manifolds and impacts (as `contact` says).
/// Not thread-safe.
class CaptureRecorder2D {
 public:
  /// A recorder writing to `out`; nothing is written before the first record_step.
  explicit CaptureRecorder2D(std::ostream& out, CaptureOptions options = {});

  /// Records the step that `world` has just run (`dt` seconds), then `extra` (may be null)
  /// in its draw stream: writes the header and the scene on the first call, then one step
  /// line; each line is flushed. Error "out" when the stream fails (the recorder then writes
  /// nothing more).
  std::optional<Error> record_step(const d2::CollisionWorld& world, Real dt, const DrawBuffer* extra = nullptr);

  /// Forgets every object written (after the world was replaced, e.g. by load): the next
  /// step removes them all and adds the world's objects anew.
  void reset_objects();

  /// Steps recorded so far.
  std::uint64_t steps_recorded() const { return steps_; }

 private:
  std::string object_record(d2::ObjectHandle handle, const d2::ObjectDesc& desc) const;
  std::string scene_line(const d2::CollisionWorld& world);
  std::string step_line(const d2::CollisionWorld& world, Real dt, const DrawBuffer* extra);
  std::string object_changes(const d2::CollisionWorld& world);

  std::ostream* out_;
  CaptureOptions options_;
  bool started_ = false;
  bool failed_ = false;
  std::uint64_t steps_ = 0;
  detail::CaptureObjectLog written_;  ///< what was written of each object
};

}  // namespace proxima::debug
