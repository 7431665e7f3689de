#pragma once
// `proxima mesh-info FILE`: loads a mesh file, analyses and repairs it, builds the mesh shape
// and prints the validation and repair report, bounds, volume, surface area and BVH
// statistics (text, or one JSON object with --json).
#include <cstddef>
#include <iosfwd>
#include <string>

#include "json_values.hpp"

namespace proxima::tool {

/// What mesh-info does.
struct MeshInfoOptions {
  std::string path;             ///< the mesh file (OBJ, STL, PLY, glTF, ...)
  bool repair = true;           ///< run repair_mesh (else only analyse; the shape is built as given)
  double weld_distance = -1.0;  ///< MeshRepairOptions::weld_distance (negative: relative default)
  bool json = false;            ///< print one JSON object instead of text
  /// Draw a progress bar over the stages (analysis, repair, hierarchy) on the error stream
  /// for a mesh of at least progress_triangles triangles (the CLI: when standard error is a
  /// terminal).
  bool progress = false;
  std::size_t progress_triangles = 200000;  ///< from this size the stages take long enough for a bar
};

/// The report as JSON: "file", "input" (analysis of the file's mesh), "repair" (what changed;
/// absent without repair), "mesh" (analysis after repair), "bounds", "bvh". Throws
/// FieldError("file", ...) when the file cannot be loaded or holds no triangle. The
/// progress bar (options.progress) goes to `progress_out` (may be null: none).
Json mesh_info(const MeshInfoOptions& options, std::ostream* progress_out = nullptr);

/// Runs mesh-info: prints to `out`, errors to `err`. Returns the exit status (0, or 1 when
/// the file cannot be used).
int run_mesh_info(const MeshInfoOptions& options, std::ostream& out, std::ostream& err);

}  // namespace proxima::tool
