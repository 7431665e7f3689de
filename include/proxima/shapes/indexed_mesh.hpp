#pragma once
/// @file indexed_mesh.hpp
/// IndexedMesh (vertices + triangles by index), the raw data of a triangle mesh, and the
/// analysis and repair that turn user data into a mesh the midphase can trust: welding of
/// near vertices, removal of degenerate and duplicate triangles and of unused vertices,
/// detection of boundary and non-manifold edges, consistent (outward) orientation.
///
/// The mesh shape with its BVH is proxima::TriangleMesh (midphase/triangle_mesh.hpp).

#include <proxima/core/math.hpp>
#include <proxima/core/result.hpp>

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace proxima {

/// Three vertex indices; counter-clockwise seen from outside for a consistently oriented
/// closed mesh (outward normal (b - a) x (c - a)).
using TriangleIndices = std::array<std::uint32_t, 3>;

/// Vertices (local frame, length units) and triangles indexing them.
struct IndexedMesh {
  std::vector<Vec3> vertices;              ///< positions, local frame
  std::vector<TriangleIndices> triangles;  ///< indices into vertices
};

/// What repair_mesh may change. Every step is reported in MeshReport.
struct MeshRepairOptions {
  /// Vertices closer than this (length units) are merged into one. Negative (default):
  /// kRelativeTolerance times the diagonal of the mesh's box. Zero: only exact duplicates.
  Real weld_distance = Real(-1);
  bool remove_degenerate = true;    ///< drop triangles with zero area (after welding): a repeated index,
                                    ///< or twice the area <= kRelativeTolerance * longest edge^2
                                    ///< (the test of Triangle::create)
  bool remove_duplicates = true;    ///< drop triangles using the same three vertices as another
  bool remove_unused = true;        ///< drop vertices no triangle uses (indices are remapped)
  bool orient_consistently = true;  ///< flip triangles so that each edge-connected manifold
                                    ///< component is consistently oriented, outward when closed
                                    ///< (positive volume); an open one keeps the winding most of
                                    ///< its triangles had
};

/// The analysis of a mesh (and what repair changed). Counts refer to the mesh after repair
/// except the input_* fields and the *_removed / welded / flipped counters.
struct MeshReport {
  std::size_t input_vertices = 0;                ///< vertices given
  std::size_t input_triangles = 0;               ///< triangles given
  std::size_t welded_vertices = 0;               ///< vertices merged into another
  std::size_t unused_vertices_removed = 0;       ///< vertices dropped because unused (welded ones count
                                                 ///< in welded_vertices only)
  std::size_t degenerate_triangles_removed = 0;  ///< zero-area triangles dropped
  std::size_t duplicate_triangles_removed = 0;   ///< repeated triangles dropped
  std::size_t flipped_triangles = 0;             ///< triangles whose winding was reversed
  std::size_t degenerate_triangles = 0;          ///< zero-area triangles still present
  std::size_t boundary_edges = 0;                ///< edges used by one triangle (open boundary)
  std::size_t non_manifold_edges = 0;            ///< edges used by more than two triangles
  std::size_t inconsistent_edges = 0;            ///< edges whose two triangles traverse them the same way
  std::size_t components = 0;                    ///< edge-connected components
  bool closed = false;                           ///< every edge shared by exactly two triangles (watertight, manifold)
  bool oriented = false;                         ///< every manifold edge traversed in opposite directions
  Real volume = Real(0);                         ///< signed volume by the divergence theorem (meaningful when closed;
                                                 ///< > 0 when the triangles face outward)
  Real surface_area = Real(0);                   ///< total triangle area
};

/// Analyses `mesh` without changing it. Errors: TooFew for no triangle ("triangles"),
/// OutOfRange for an index past the vertex array ("triangles[4][2]"), NotFinite /
/// OutOfRange for a vertex ("vertices[7].x"). O(n log n).
Result<MeshReport> analyse_mesh(const IndexedMesh& mesh);

/// A repaired copy of `mesh` and its report (same errors as analyse_mesh). The steps run in
/// this order: weld, remove degenerate, remove duplicates, remove unused, orient. O(n log n).
struct RepairedMesh {
  IndexedMesh mesh;   ///< the repaired mesh
  MeshReport report;  ///< what was found and changed
};
/// See RepairedMesh.
Result<RepairedMesh> repair_mesh(const IndexedMesh& mesh, const MeshRepairOptions& options = {});

}  // namespace proxima
