#pragma once
/// @file bounding_capsule.hpp
/// BoundingCapsule: the points within a radius of a segment, used as a bounding volume.

#include <proxima/core/math.hpp>
#include <proxima/core/result.hpp>
#include <proxima/geometry/aabb.hpp>

namespace proxima {

/// Closed capsule {x : dist(x, segment p0p1) <= radius}. p0 == p1 gives a ball, radius 0 a
/// segment.
struct BoundingCapsule {
  Vec3 p0{Real(0)};       ///< first end of the core segment
  Vec3 p1{Real(0)};       ///< second end of the core segment
  Real radius = Real(0);  ///< radius around the segment (length, >= 0)

  /// Validated construction: p0, p1 finite ("p0.x" ...), radius finite and >= 0 ("radius").
  static Result<BoundingCapsule> create(const Vec3& p0, const Vec3& p1, Real radius);

  /// Volume pi r^2 |p1 - p0| + 4/3 pi r^3 (length^3).
  Real volume() const { return kPi * radius * radius * (glm::length(p1 - p0) + Real(4) / Real(3) * radius); }
  /// Squared distance from `point` to the core segment (the exact expression contains()
  /// compares with radius^2).
  Real distance_squared_to_core(const Vec3& point) const;
  /// True when `point` is inside or on the capsule: distance_squared_to_core(point) <=
  /// radius^2 (the fitters guarantee their points pass this test).
  bool contains(const Vec3& point) const { return distance_squared_to_core(point) <= radius * radius; }
  /// Farthest point in `direction` (any vector).
  Vec3 support(const Vec3& direction) const;
  /// Tight axis-aligned box.
  Aabb aabb() const { return {min(p0, p1) - Vec3(radius), max(p0, p1) + Vec3(radius)}; }
};

}  // namespace proxima
