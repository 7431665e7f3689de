#pragma once
/// @file bounding_sphere.hpp
/// BoundingSphere: a closed ball used as a bounding volume (world frame, or whatever frame
/// its points were given in).

#include <proxima/core/math.hpp>
#include <proxima/core/result.hpp>
#include <proxima/geometry/aabb.hpp>

namespace proxima {

/// Closed ball {x : |x - center| <= radius}. A radius of 0 is allowed (the bounding sphere
/// of a single point).
struct BoundingSphere {
  Vec3 center{Real(0)};   ///< centre, in the frame of the bounded geometry
  Real radius = Real(0);  ///< radius (length, >= 0)

  /// Validated construction: center finite ("center.x" ...), radius finite and >= 0
  /// ("radius").
  static Result<BoundingSphere> create(const Vec3& center, Real radius);

  /// Volume 4/3 pi r^3 (length^3).
  Real volume() const { return Real(4) / Real(3) * kPi * radius * radius * radius; }
  /// True when `point` is inside or on the sphere: |point - center|^2 <= radius^2, evaluated
  /// exactly so in floating point (the fitters guarantee their points pass this test).
  bool contains(const Vec3& point) const {
    const Vec3 d = point - center;
    return glm::dot(d, d) <= radius * radius;
  }
  /// Farthest point in `direction` (any vector; zero gives the centre + radius along z).
  Vec3 support(const Vec3& direction) const;
  /// Tight axis-aligned box of the ball.
  Aabb aabb() const { return {center - Vec3(radius), center + Vec3(radius)}; }
};

}  // namespace proxima
