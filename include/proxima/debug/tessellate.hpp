#pragma once
/// @file tessellate.hpp
/// Triangle meshes of shapes for drawing: every geometry kind as positions and indices in
/// the shape's local frame (what the capture format stores per object and what draw_shape
/// places at a pose).
#include <proxima/core/math.hpp>
#include <proxima/core/transform.hpp>
#include <proxima/shapes/shape_ref.hpp>

#include <cstdint>
#include <vector>

namespace proxima::debug {

/// How finely to tessellate.
struct TessellationOptions {
  /// Segments around a full turn of the round shapes (sphere, capsule, cylinder, cone,
  /// ellipsoid; half as many from pole to pole). Clamped to [3, 256].
  int segments = 24;
  /// Half the side of the square that stands for a half-space (length units), centred on
  /// the plane's point nearest the local origin.
  Real halfspace_extent = Real(50);
  /// Radius (length units) of the small solid drawn for a point (an octahedron) and around
  /// a segment (a thin hexagonal prism): shapes without area still show.
  Real marker_radius = Real(0.02);
};

/// An indexed triangle mesh (local frame of the shape it was made from): triangle i has the
/// corners positions[indices[3i]], positions[indices[3i+1]], positions[indices[3i+2]],
/// counter-clockwise seen from outside (front faces out). The triangle and the half-space
/// come with both sides (each face twice, once per winding) as they have no inside.
struct DrawMesh {
  std::vector<Vec3> positions;         ///< vertices, local frame, length units
  std::vector<std::uint32_t> indices;  ///< three per triangle

  /// Number of triangles.
  std::size_t triangle_count() const { return indices.size() / 3; }
};

/// The tessellation of `shape` in its local frame. Round shapes: vertices lie on the
/// surface (rings of latitude and longitude), so the mesh is inscribed and its area
/// approaches the surface's as `segments` grows. Box: its 8 corners. Convex hull: its
/// vertices, each face fanned. Triangle mesh: its own vertices and triangles. Compound:
/// each child's tessellation placed at its pose. Half-space: a square of the plane.
/// Point and segment: a marker solid (see TessellationOptions). O(size of the output).
DrawMesh tessellate(ShapeRef shape, const TessellationOptions& options = {});

/// Appends `mesh` placed at `pose` (local -> world) to `out` (indices offset accordingly).
void append_placed(const DrawMesh& mesh, const Transform& pose, DrawMesh& out);

}  // namespace proxima::debug
