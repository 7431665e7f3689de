#pragma once
// The JSON records of the capture format that do not depend on the recorder's state: a
// geometry's short description, a tessellated mesh, a draw stream, a step's events and
// manifolds (docs/capture-format.md). Internal to the library.
#include <proxima/core/debug_draw.hpp>
#include <proxima/debug/tessellate.hpp>
#include <proxima/shapes/shape_ref.hpp>
#include <proxima/world/world_events.hpp>

#include <span>
#include <string>

namespace proxima::debug::json {

/// {"type": ..., dimensions...}: what a click-to-inspect panel shows of a geometry.
void geometry(std::string& out, ShapeRef shape);
/// {"positions": [x, y, z, ...], "indices": [...]} (flat arrays, as a WebGL buffer wants).
void mesh(std::string& out, const DrawMesh& mesh);
/// {"lines": [...], "triangles": [...], "points": [...], "boxes": [...], "texts": [...]}.
void draw_stream(std::string& out, const DrawBuffer& draw);
/// {"begin": [[a, b], ...], "persist", "end", "sensor_enter", "sensor_exit", "impacts"}.
void events(std::string& out, const StepEvents& events);
/// [{"a", "b", "normal", "points": [{"a", "b", "depth", "id"}]}, ...].
void manifolds(std::string& out, std::span<const WorldManifold> manifolds);

}  // namespace proxima::debug::json
