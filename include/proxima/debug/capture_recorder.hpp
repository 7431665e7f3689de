#pragma once
/// @file capture_recorder.hpp
/// CaptureRecorder: writes a CollisionWorld's steps to a capture (docs/capture-format.md), a
/// JSON-Lines text that a browser and Python read with their own JSON parsers: a header
/// line, a scene line (every object with its tessellated local-frame mesh, and the world's
/// binary snapshot in base64), then one line per recorded step (poses of the objects that
/// moved, objects added and removed, events, manifolds, recorded queries, the draw stream).
///
/// The world knows nothing of files: its user attaches a recorder and calls record_step
/// after each step (`proxima world --record FILE` does so for every "step" request).
///
///   std::ofstream file("run.capture.jsonl");
///   debug::CaptureRecorder recorder(file);
///   for (...) { world.move(...); world.step(dt); recorder.record_step(world, dt); }
#include <proxima/core/debug_draw.hpp>
#include <proxima/core/result.hpp>
#include <proxima/debug/draw_contacts.hpp>
#include <proxima/debug/tessellate.hpp>
#include <proxima/geometry/ray.hpp>
#include <proxima/world/collision_world.hpp>

#include <cstdint>
#include <iosfwd>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace proxima::debug {

/// Version of the capture format that CaptureRecorder writes.
inline constexpr int kCaptureVersion = 1;

/// A camera for viewers and `proxima render` (world frame, length units).
struct CaptureCamera {
  Vec3 position{Real(10), Real(-10), Real(10)};  ///< eye
  Vec3 target{Real(0)};                          ///< point looked at
  Vec3 up{Real(0), Real(0), Real(1)};            ///< up direction (need not be unit)
  Real fov_degrees = Real(0);                    ///< vertical field of view; 0: orthographic
  Real ortho_height = Real(10);                  ///< orthographic: height of the view (length units)
};

/// What a recorder writes.
struct CaptureOptions {
  std::string units = "m";              ///< name of the length unit (the header's "units")
  std::optional<CaptureCamera> camera;  ///< written in the header when given
  TessellationOptions tessellation;     ///< how objects' meshes are tessellated
  bool snapshot = true;                 ///< the scene line carries the world's snapshot (base64)
  bool draw_contacts = true;            ///< each step's draw stream includes its manifolds
  ContactDrawOptions contact;           ///< how they are drawn (draw_manifold)
};

namespace detail {
/// What a recorder last wrote of an object, to find what changed by the next step.
struct CaptureObjectState {
  Transform pose;  ///< world frame (a 2D object's pose in the plane z = 0)
  ObjectKind kind = ObjectKind::Moving;
  bool sensor = false;
  CollisionFilter filter;
  std::uint64_t user_data = 0;
  CcdMode ccd = CcdMode::Auto;
  bool stale = false;  ///< to be written again in full (geometry changed, world replaced)
};
/// What was written of each object, by handle integer.
using CaptureObjectLog = std::map<std::uint64_t, CaptureObjectState>;
}  // namespace detail

/// Writes a capture of one world to a stream (see the file comment). The stream must
/// outlive the recorder. Not thread-safe.
class CaptureRecorder {
 public:
  /// A recorder writing to `out`; nothing is written before the first record_step.
  explicit CaptureRecorder(std::ostream& out, CaptureOptions options = {});

  /// Records the step that `world` has just run (`dt` seconds): writes the header and the
  /// scene on the first call, then one step line; `extra` (may be null) is appended to the
  /// step's draw stream. Each line is flushed. Error "out" when the stream fails (the
  /// recorder then writes nothing more).
  std::optional<Error> record_step(const CollisionWorld& world, Real dt, const DrawBuffer* extra = nullptr);

  /// Records a ray query (world frame) and its hits, written with the next step.
  void record_ray(const Ray& ray, Real max_t, std::span<const WorldHit> hits);

  /// The object's geometry changed (set_geometry): the next step writes it again among the
  /// "added" objects (a reader replaces the object of the same id).
  void invalidate(ObjectHandle object);

  /// Forgets every object written (after the world was replaced, e.g. by load): the next
  /// step removes them all and adds the world's objects anew.
  void reset_objects();

  /// Steps recorded so far.
  std::uint64_t steps_recorded() const { return steps_; }

 private:
  std::string object_record(ObjectHandle handle, const ObjectDesc& desc) const;
  std::string scene_line(const CollisionWorld& world);
  std::string step_line(const CollisionWorld& world, Real dt, const DrawBuffer* extra);
  std::string object_changes(const CollisionWorld& world);

  std::ostream* out_;
  CaptureOptions options_;
  bool started_ = false;
  bool failed_ = false;
  std::uint64_t steps_ = 0;
  detail::CaptureObjectLog written_;  ///< what was written of each object
  std::vector<std::string> queries_;  ///< JSON of the queries for the next step
};

}  // namespace proxima::debug
