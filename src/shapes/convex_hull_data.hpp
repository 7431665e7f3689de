#pragma once
/// @file convex_hull_data.hpp
/// Internal: the full data of a ConvexHull, kept out of the public header. The public
/// header holds only ConvexHull::Boundary, what its inline accessors read (vertices, faces,
/// loops, edges, adjacency, box, scale, tolerance); HullData derives from it and adds what
/// the library's own queries use: the relative frame the queries work in, the support
/// scan's blocks, the hill-climbing adjacency and the mass properties.

#include <proxima/shapes/convex_hull.hpp>

#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

namespace proxima::detail {

/// The immutable data of one ConvexHull, shared between its copies (local frame, length units).
struct HullData : ConvexHull::Boundary {
  std::vector<std::uint32_t> climb_offsets;    ///< CSR offsets of climb_neighbors, size vertices + 1
  std::vector<std::uint32_t> climb_neighbors;  ///< vertices sharing a face (hill-climbing moves)
  Vec3 reference{Real(0)};                     ///< centre of the box: queries work relative to it
  std::vector<Vec3> shifted_vertices;          ///< vertices - reference (exact for far hulls)
  /// shifted_vertices in blocks of four, structure of arrays per block (x0 x1 x2 x3,
  /// y0..y3, z0..z3), the last block padded with copies of vertex 0: the scan's layout.
  std::vector<Real> scan_blocks;
  std::vector<Real> shifted_offsets;  ///< face offsets relative to reference
  Real volume = Real(0);              ///< volume (length^3)
  Vec3 centroid{Real(0)};             ///< centre of volume, local frame
  Mat3 unit_inertia{Real(0)};         ///< inertia about the centroid at density 1
};

/// Volume, centroid and unit-density inertia of the closed polyhedron held in `data`
/// (vertices and CCW face loops); false when it has no positive volume
/// (convex_hull_mass.cpp).
bool compute_hull_mass(HullData& data);

}  // namespace proxima::detail

namespace proxima {

inline ConvexHull::ConvexHull(std::shared_ptr<const detail::HullData> data) : data_(std::move(data)) {}

// data_ always holds a detail::HullData (create makes no other), whose only base is Boundary.
inline const detail::HullData& ConvexHull::data() const { return static_cast<const detail::HullData&>(*data_); }

}  // namespace proxima
