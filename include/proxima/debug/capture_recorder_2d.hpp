#pragma once
/// @file capture_recorder_2d.hpp
/// CaptureRecorder2D: writes a d2::CollisionWorld's steps to a capture
/// (docs/capture-format.md) with "dimension": 2, so that the web viewer and `proxima render`
/// show a 2D world in the plane z = 0: a header line, a scene line with no objects, then one
/// line per recorded step with the world's events and manifolds (at z = 0) and a draw stream
/// in which the objects themselves are drawn (draw_world_2d: outlines filled at their poses,
/// contacts, impacts), followed by the caller's own primitives.
///
/// The objects travel in the draw stream rather than as scene objects because the 2D world
/// does not list its objects' shapes; its user passes the objects it added.
///
///   std::ofstream file("run.capture.jsonl");
///   debug::CaptureRecorder2D recorder(file);
///   for (...) { world.move(...); world.step(); recorder.record_step(world, objects, dt); }
#include <proxima/core/debug_draw.hpp>
#include <proxima/core/result.hpp>
#include <proxima/d2/collision_world.hpp>
#include <proxima/debug/capture_recorder.hpp>
#include <proxima/debug/draw_world_2d.hpp>

#include <cstdint>
#include <iosfwd>
#include <optional>
#include <span>

namespace proxima::debug {

/// Writes a capture of one 2D world to a stream (see the file comment). The stream must
/// outlive the recorder. Of the options, `snapshot` is not used (no snapshot is written),
/// `tessellation.segments` is the segments per turn of round outlines, and `draw_contacts`
/// draws the manifolds and impacts (as `contact` says). Not thread-safe.
class CaptureRecorder2D {
 public:
  /// A recorder writing to `out`; nothing is written before the first record_step.
  explicit CaptureRecorder2D(std::ostream& out, CaptureOptions options = {});

  /// Records the step that `world` has just run (`dt` seconds), drawing `objects` (those the
  /// world no longer contains are skipped) and then `extra` (may be null): writes the header
  /// and the scene on the first call, then one step line; each line is flushed. Error "out"
  /// when the stream fails (the recorder then writes nothing more).
  std::optional<Error> record_step(const d2::CollisionWorld& world, std::span<const WorldObject2D> objects, Real dt,
                                   const DrawBuffer* extra = nullptr);

  /// Steps recorded so far.
  std::uint64_t steps_recorded() const { return steps_; }

 private:
  std::ostream* out_;
  CaptureOptions options_;
  bool started_ = false;
  bool failed_ = false;
  std::uint64_t steps_ = 0;
};

}  // namespace proxima::debug
