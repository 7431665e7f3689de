#pragma once
/// @file kdop.hpp
/// Kdop<K>: the discrete-orientation polytope bounded by K/2 slabs of fixed directions
/// (Ericson, Real-Time Collision Detection, 4.6; Klosowski et al., "Efficient Collision
/// Detection Using Bounding Volume Hierarchies of k-DOPs", IEEE TVCG 1998).

#include <proxima/core/math.hpp>
#include <proxima/core/result.hpp>
#include <proxima/geometry/aabb.hpp>

#include <array>
#include <vector>

namespace proxima {

/// Integer direction i of the 13 k-DOP directions, in the order the k-DOPs use them:
/// 0-2 the axes (1,0,0) (0,1,0) (0,0,1); 3-6 the corner diagonals (1,1,1) (1,-1,1)
/// (1,1,-1) (1,-1,-1); 7-12 the edge diagonals (1,1,0) (1,0,1) (0,1,1) (1,-1,0) (1,0,-1)
/// (0,1,-1).
/// Indices outside 0..12 are clamped.
inline Vec3 kdop_base_direction(int i) {
  static constexpr signed char kTable[13][3] = {{1, 0, 0},  {0, 1, 0},   {0, 0, 1}, {1, 1, 1}, {1, -1, 1},
                                                {1, 1, -1}, {1, -1, -1}, {1, 1, 0}, {1, 0, 1}, {0, 1, 1},
                                                {1, -1, 0}, {1, 0, -1},  {0, 1, -1}};
  const int k = i < 0 ? 0 : (i > 12 ? 12 : i);
  return {Real(kTable[k][0]), Real(kTable[k][1]), Real(kTable[k][2])};
}

/// Closed k-DOP for K = 6 (the box), 14 (box + corners), 18 (box + edges) or 26 (all):
/// {x : min[i] <= d_i . x <= max[i], i < K/2}. Kdop<6> and Kdop<14> use base directions
/// 0..K/2-1, Kdop<18> the axes and the edge diagonals (base 0-2 and 7-12), Kdop<26> all 13.
///
/// The directions d_i are the integer vectors of kdop_base_direction (not unit: |d_i| is 1,
/// sqrt(2) or sqrt(3)), so min/max are lengths scaled by |d_i|. The first three directions
/// are always the axes, so slabs 0-2 are the k-DOP's axis-aligned box. The default value
/// is empty (min = +kRealMax, max = -kRealMax): grow() from it.
template <int K>
struct Kdop {
  static_assert(K == 6 || K == 14 || K == 18 || K == 26, "Kdop<K> supports K = 6, 14, 18, 26");
  /// Number of slabs (K/2).
  static constexpr int kSlabCount = K / 2;

  std::array<Real, K / 2> min;  ///< lower bound of d_i . x per slab
  std::array<Real, K / 2> max;  ///< upper bound of d_i . x per slab

  /// The empty k-DOP (every slab inverted).
  Kdop() {
    min.fill(kRealMax);
    max.fill(-kRealMax);
  }

  /// Validated construction: every bound finite ("min[3]", "max[0]" ...), min[i] <= max[i]
  /// ("max[i]", InvalidArgument) and a non-empty intersection of the slabs (a k-DOP whose
  /// slabs are individually consistent can still be empty; "max", Degenerate).
  static Result<Kdop> create(const std::array<Real, K / 2>& min, const std::array<Real, K / 2>& max);

  /// Direction i (< K/2) of this k-DOP family, an integer vector.
  static Vec3 direction(int i) { return kdop_base_direction(K == 18 && i >= 3 ? i + 4 : i); }
  /// d_i . point, the quantity slab i bounds (evaluated the same way everywhere).
  static Real project(int i, const Vec3& point) {
    const Vec3 d = direction(i);
    return d.x * point.x + d.y * point.y + d.z * point.z;
  }

  /// Grows every slab to contain `point`.
  void grow(const Vec3& point) {
    for (int i = 0; i < kSlabCount; ++i) {
      const Real p = project(i, point);
      if (p < min[i]) min[i] = p;
      if (p > max[i]) max[i] = p;
    }
  }
  /// True when `point` lies in every slab (boundary included), exactly as evaluated by project().
  bool contains(const Vec3& point) const {
    for (int i = 0; i < kSlabCount; ++i) {
      const Real p = project(i, point);
      if (!(p >= min[i] && p <= max[i])) return false;
    }
    return true;
  }

  /// True when no point lies in every slab (within tolerance). O(K^4) in the worst case.
  bool is_empty() const;
  /// The polytope's vertices (each within a relative tolerance of its three planes and
  /// inside the others; duplicates merged); empty for an empty k-DOP. O(K^4).
  std::vector<Vec3> vertices() const;
  /// Volume of the polytope (length^3), by summing the pyramids of its face polygons over an
  /// interior point; 0 for flat or empty k-DOPs. O(K^4).
  Real volume() const;
  /// The box of slabs 0-2 (the tight box of the k-DOP when it was fitted to points).
  Aabb aabb() const { return {Vec3(min[0], min[1], min[2]), Vec3(max[0], max[1], max[2])}; }
};

/// The usual k-DOP sizes.
using Kdop6 = Kdop<6>;
/// 14-DOP: box + corner diagonals.
using Kdop14 = Kdop<14>;
/// 18-DOP: box + edge diagonals.
using Kdop18 = Kdop<18>;
/// 26-DOP: box + corner + edge diagonals.
using Kdop26 = Kdop<26>;

extern template struct Kdop<6>;
extern template struct Kdop<14>;
extern template struct Kdop<18>;
extern template struct Kdop<26>;

}  // namespace proxima
