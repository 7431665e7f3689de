// Closest points of solid boxes.
//
// Steps (Ericson, Real-Time Collision Detection, 5.1.3 and 5.1.4):
//  1. Axis-aligned box: clamp each coordinate of p into [min, max].
//  2. Oriented box: express p - centre on each unit axis, clamp that coordinate into
//     [-half extent, +half extent], and move p along the axis by the clamped amount only.
//     A point inside is returned unchanged (no round trip through the box frame), and the
//     answer stays accurate for boxes far from the origin.

#include <proxima/geometry/closest_points.hpp>

namespace proxima::geometry {

Vec3 closest_point_aabb(const Vec3& p, const Aabb& box) {
  if (!is_finite(p)) return Vec3(detail::kNaN);
  // max then min, so that an empty box (min > max) still gives a finite answer.
  return glm::min(glm::max(p, box.min), box.max);
}

namespace {

Vec3 closest_point_obb_unscaled(const Vec3& p, const Vec3& center, const Mat3& axes, const Vec3& half_extents) {
  const Vec3 d = p - center;
  Vec3 q = p;
  for (int i = 0; i < 3; ++i) {
    const Real along = glm::dot(d, axes[i]);
    // max then min (not std::clamp) so that a negative half extent is not undefined behaviour.
    const Real clamped = std::min(std::max(along, -half_extents[i]), half_extents[i]);
    if (clamped != along) q += (clamped - along) * axes[i];
  }
  return q;
}

}  // namespace

Vec3 closest_point_obb(const Vec3& p, const Vec3& center, const Mat3& axes, const Vec3& half_extents) {
  const Real m = detail::magnitude({p, center, half_extents, axes[0], axes[1], axes[2]});
  if (!std::isfinite(m)) return Vec3(detail::kNaN);
  const int e = detail::rescale_exponent(detail::magnitude({p, center, half_extents}));
  if (e == 0) return closest_point_obb_unscaled(p, center, axes, half_extents);
  return detail::scaled(closest_point_obb_unscaled(detail::scaled(p, -e), detail::scaled(center, -e), axes,
                                                   detail::scaled(half_extents, -e)),
                        e);
}

}  // namespace proxima::geometry
