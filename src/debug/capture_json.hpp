#pragma once
// The JSON records of the capture format that do not depend on the recorder's state: a
// geometry's short description, a tessellated mesh, a draw stream, a step's events and
// manifolds (docs/capture-format.md). Internal to the library.
#include <proxima/core/debug_draw.hpp>
#include <proxima/d2/collision_world.hpp>
#include <proxima/debug/capture_recorder.hpp>
#include <proxima/debug/tessellate.hpp>
#include <proxima/shapes/shape_ref.hpp>
#include <proxima/world/world_events.hpp>

#include <iosfwd>
#include <span>
#include <string>

namespace proxima::debug::json {

/// Writes `line` and a newline to `out` and flushes it, unless `failed` is already set;
/// sets `failed` when the stream fails. Returns !failed (the recorders stop at a failure).
bool write_line(std::ostream& out, const std::string& line, bool& failed);

/// The header line's object: format, version, `dimension` (2 or 3), units, precision and,
/// when the options have one, the camera.
void header(std::string& out, const CaptureOptions& options, int dimension);
/// {"type": ..., dimensions...}: what a click-to-inspect panel shows of a geometry.
void geometry(std::string& out, ShapeRef shape);
/// {"type": ..., dimensions...} of a 2D shape by the 2D protocol's names, points at z = 0:
/// "point2d" (position), "circle" (center, radius), "segment2d" (a, b), "capsule2d" (a, b,
/// radius), "polygon" (vertices, radius), "chain" (point_count, loop).
void geometry(std::string& out, const d2::Shape& shape);
/// {"positions": [x, y, z, ...], "indices": [...]} (flat arrays, as a WebGL buffer wants).
void mesh(std::string& out, const DrawMesh& mesh);
/// {"lines": [...], "triangles": [...], "points": [...], "boxes": [...], "texts": [...]}.
void draw_stream(std::string& out, const DrawBuffer& draw);
/// {"begin": [[a, b], ...], "persist", "end", "sensor_enter", "sensor_exit", "impacts"}.
void events(std::string& out, const StepEvents& events);
/// [{"a", "b", "normal", "points": [{"a", "b", "depth", "id"}]}, ...].
void manifolds(std::string& out, std::span<const WorldManifold> manifolds);
/// The events of a 2D world's step, as `events`, impacts' points and normals at z = 0.
void events(std::string& out, const d2::StepEvents& events);
/// The manifolds of a 2D world, as `manifolds`, points and normals at z = 0, ids the
/// points' feature ids.
void manifolds(std::string& out, std::span<const d2::WorldManifold> manifolds);

}  // namespace proxima::debug::json
