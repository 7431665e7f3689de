#pragma once
/// @file aabb.hpp
/// Aabb: the axis-aligned bounding box, the one bounding volume every layer uses
/// (shape bounds, broad phase, BVH nodes). Closed: boxes that only touch overlap.

#include <proxima/core/math.hpp>
#include <proxima/core/transform.hpp>

namespace proxima {

/// Axis-aligned box [min, max] (closed). An empty box has min > max on some axis.
struct Aabb {
  Vec3 min{kRealMax};   ///< smallest corner
  Vec3 max{-kRealMax};  ///< largest corner

  /// The empty box (min = +max, max = -max): grow() from it.
  static Aabb empty() { return {}; }
  /// The box of one point.
  static Aabb from_point(const Vec3& p) { return {p, p}; }
  /// The box of a centre and half extents (>= 0).
  static Aabb from_center_half_extents(const Vec3& c, const Vec3& h) { return {c - h, c + h}; }

  /// True when min <= max on every axis.
  bool is_valid() const { return min.x <= max.x && min.y <= max.y && min.z <= max.z; }
  /// Centre point.
  Vec3 center() const { return (min + max) * Real(0.5); }
  /// Half extents (>= 0 for a valid box).
  Vec3 half_extents() const { return (max - min) * Real(0.5); }
  /// Edge lengths.
  Vec3 extents() const { return max - min; }
  /// Volume (0 for flat boxes).
  Real volume() const {
    const Vec3 e = extents();
    return e.x * e.y * e.z;
  }
  /// Surface area, the SAH cost measure.
  Real surface_area() const {
    const Vec3 e = extents();
    return Real(2) * (e.x * e.y + e.y * e.z + e.z * e.x);
  }

  /// Grows the box to contain `p`.
  void grow(const Vec3& p) {
    min = glm::min(min, p);
    max = glm::max(max, p);
  }
  /// Grows the box to contain `b`.
  void grow(const Aabb& b) {
    min = glm::min(min, b.min);
    max = glm::max(max, b.max);
  }
  /// The box enlarged by `margin` on every side.
  Aabb inflated(Real margin) const { return {min - Vec3(margin), max + Vec3(margin)}; }

  /// True when `p` lies inside or on the boundary.
  bool contains(const Vec3& p) const {
    return p.x >= min.x && p.x <= max.x && p.y >= min.y && p.y <= max.y && p.z >= min.z && p.z <= max.z;
  }
  /// True when `b` lies entirely inside this box (boundary included).
  bool contains(const Aabb& b) const {
    return glm::all(glm::lessThanEqual(min, b.min)) && glm::all(glm::lessThanEqual(b.max, max));
  }
  /// True when the two closed boxes share at least one point (touching counts).
  bool overlaps(const Aabb& b) const {
    return min.x <= b.max.x && b.min.x <= max.x && min.y <= b.max.y && b.min.y <= max.y && min.z <= b.max.z &&
           b.min.z <= max.z;
  }

  /// The box of this box after a rigid transform (exact box of the 8 transformed corners,
  /// computed with |R| in O(1), Arvo's method).
  Aabb transformed(const Transform& pose) const {
    const Mat3 r = pose.rotation_matrix();
    const Vec3 c = pose.apply(center());
    const Vec3 h = half_extents();
    Vec3 e;
    for (int i = 0; i < 3; ++i) {
      e[i] = std::abs(r[0][i]) * h.x + std::abs(r[1][i]) * h.y + std::abs(r[2][i]) * h.z;
    }
    return {c - e, c + e};
  }
};

/// The smallest box containing both.
inline Aabb merge(const Aabb& a, const Aabb& b) { return {glm::min(a.min, b.min), glm::max(a.max, b.max)}; }

}  // namespace proxima
