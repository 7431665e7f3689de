#pragma once
// Reading and validating a capture (docs/capture-format.md): the header, the scene, every
// step, with errors that name the line and the field ("line 7: poses[2].rotation: ..."),
// and the state of the scene at a given step for `proxima render`.
#include <proxima/core/debug_draw.hpp>
#include <proxima/core/result.hpp>
#include <proxima/core/transform.hpp>
#include <proxima/debug/capture_recorder.hpp>

#include <cstdint>
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

namespace proxima::tool {

/// One object of a capture, as its scene or "added" record gives it.
struct CaptureObject {
  std::uint64_t id = 0;                ///< the world's handle as an integer
  std::string kind;                    ///< "static" or "moving"
  bool sensor = false;                 ///< a sensor
  std::string geometry_type;           ///< the geometry's "type" ("box", "mesh", ...)
  Rgba color;                          ///< the recorder's colour for it
  Transform pose;                      ///< world pose (updated by the steps' "poses")
  std::vector<Vec3> positions;         ///< tessellated mesh, local frame
  std::vector<std::uint32_t> indices;  ///< three per triangle
};

/// One point of a recorded manifold (world frame).
struct CapturePoint {
  Vec3 a{Real(0)};       ///< on object a
  Vec3 b{Real(0)};       ///< on object b
  Real depth = Real(0);  ///< > 0 penetration
};

/// A recorded manifold.
struct CaptureManifold {
  std::uint64_t a = 0;               ///< lower handle
  std::uint64_t b = 0;               ///< higher handle
  Vec3 normal{Real(0)};              ///< from a to b
  std::vector<CapturePoint> points;  ///< 1..4
};

/// One recorded step.
struct CaptureStep {
  std::uint64_t index = 0;                                 ///< 0, 1, 2, ...
  Real dt = Real(0);                                       ///< seconds
  std::vector<std::pair<std::uint64_t, Transform>> poses;  ///< objects that moved
  std::vector<CaptureObject> added;                        ///< objects new or changed
  std::vector<std::uint64_t> removed;                      ///< objects gone
  std::vector<CaptureManifold> contacts;                   ///< touching pairs after the step
  std::size_t query_count = 0;                             ///< queries recorded with the step
  DrawBuffer draw;                                         ///< the step's draw stream
};

/// A whole capture.
struct Capture {
  int version = 0;                             ///< format version (1)
  int dimension = 3;                           ///< 3 (2 for a 2D world drawn in z = 0)
  std::string units;                           ///< name of the length unit
  std::optional<debug::CaptureCamera> camera;  ///< the header's camera, when given
  std::vector<CaptureObject> objects;          ///< the scene's objects
  std::string snapshot;                        ///< the world's snapshot, base64 (may be empty)
  std::vector<CaptureStep> steps;              ///< the steps, in order
};

/// Reads and validates a capture. Errors (field "line N: path", message saying what was
/// expected): not JSON (a truncated last line included), a wrong "format" or unsupported
/// "version", a missing scene, a missing or mistyped member, a mesh index out of range, a
/// step index out of sequence, a pose for an unknown object.
Result<Capture> read_capture(std::istream& in);

/// The scene's objects after step `frame` has been applied (poses moved, objects added and
/// removed), sorted by id. Error "frame" when the capture has no such step.
Result<std::vector<CaptureObject>> objects_at(const Capture& capture, std::size_t frame);

}  // namespace proxima::tool
