#pragma once
// Internal: a k-DOP's slabs shifted to a local origin in double precision, the form the
// vertex, volume and overlap computations use.

#include <proxima/bounds/kdop.hpp>

#include <glm/vec3.hpp>

#include <array>
#include <vector>

namespace proxima::detail {

/// Slabs lo[i] <= dirs[i] . (x - origin) <= hi[i] in double, with the slack (absolute
/// tolerance) that the precision of the original bounds warrants.
struct KdopPolytope {
  std::array<glm::dvec3, 13> dirs{};  ///< integer slab directions
  std::array<double, 13> lo{};        ///< lower bounds relative to origin
  std::array<double, 13> hi{};        ///< upper bounds relative to origin
  int count = 0;                      ///< number of slabs used
  glm::dvec3 origin{0.0};             ///< local origin (world coordinates)
  double slack = 0.0;                 ///< absolute tolerance of membership tests

  /// Vertices relative to origin (first one only with stop_at_first); empty when the
  /// slabs have no common point.
  std::vector<glm::dvec3> local_vertices(bool stop_at_first) const;
};

/// The polytope of the bounds of a Kdop<K>.
template <int K>
KdopPolytope make_kdop_polytope(const std::array<Real, K / 2>& lo, const std::array<Real, K / 2>& hi);

}  // namespace proxima::detail
