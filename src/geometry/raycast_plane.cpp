// Ray against a plane n.x = d (two-sided surface) and against the solid half-space
// n.x <= d.
//
// Steps:
//  1. Signed distance of the origin, dist = n.origin - d, and the approach rate
//     n.direction (both scale with |n|, so t does not depend on the normal's length; a
//     zero normal never hits). Both are accumulated in double: in the float build the
//     products are then exact, so neither a plane far from the origin nor a grazing
//     direction loses digits to the dot products' rounding.
//  2. Plane: an origin on the plane (dist == 0, e.g. a ray lying in it) hits at t = 0;
//     otherwise the ray must move towards the plane and t = -dist / (n.direction). The
//     normal is the unit plane normal turned towards the origin's side.
//  3. Half-space: dist <= 0 is inside (t = 0); otherwise as for the plane, the normal
//     being the outward normal n.
//
// Source: Ericson, Real-Time Collision Detection, 5.3.1.

#include <proxima/geometry/raycast.hpp>

#include "geometry/raycast_detail.hpp"

namespace proxima::geometry {

namespace {

/// Shared checks; returns the unit normal or nothing when the query can never hit.
std::optional<Vec3> plane_normal(const Ray& ray, Real max_t, const Vec3& normal, Real offset, detail::UnitRay& r) {
  if (!detail::prepare(ray, max_t, r) || !is_finite(normal) || !is_finite(offset)) return std::nullopt;
  Real len;
  Vec3 unit;
  if (!detail::length_and_direction(normal, len, unit)) return std::nullopt;
  return unit;
}

/// n.v in double: in the float build the products are exact and the sum is rounded in
/// double, so neither a far origin nor a grazing direction loses digits.
double dot_wide(const Vec3& n, const Vec3& v) {
  return static_cast<double>(n.x) * static_cast<double>(v.x) + static_cast<double>(n.y) * static_cast<double>(v.y) +
         static_cast<double>(n.z) * static_cast<double>(v.z);
}

/// A surface hit at t = -dist / rate (rate != 0, of opposite sign to dist).
std::optional<RayHit> crossing(const Ray& ray, Real max_t, double dist, double rate, const Vec3& normal) {
  const double t = -dist / rate;
  if (!(t <= static_cast<double>(max_t)) || t > static_cast<double>(kRealMax)) return std::nullopt;
  return detail::surface_hit(ray, max_t, static_cast<Real>(t), normal);
}

}  // namespace

std::optional<RayHit> ray_plane(const Ray& ray, Real max_t, const Vec3& normal, Real offset) noexcept {
  detail::UnitRay r;
  const auto n = plane_normal(ray, max_t, normal, offset, r);
  if (!n) return std::nullopt;
  const double dist = dot_wide(normal, ray.origin) - static_cast<double>(offset);
  const double rate = dot_wide(normal, ray.direction);
  if (dist == 0.0) return RayHit{Real(0), ray.origin, rate > 0.0 ? -*n : *n};
  if (dist > 0.0 ? !(rate < 0.0) : !(rate > 0.0)) return std::nullopt;
  return crossing(ray, max_t, dist, rate, dist > 0.0 ? *n : -*n);
}

std::optional<RayHit> ray_halfspace(const Ray& ray, Real max_t, const Vec3& normal, Real offset) noexcept {
  detail::UnitRay r;
  const auto n = plane_normal(ray, max_t, normal, offset, r);
  if (!n) return std::nullopt;
  const double dist = dot_wide(normal, ray.origin) - static_cast<double>(offset);
  if (dist <= 0.0) return detail::inside_hit(ray, r);
  const double rate = dot_wide(normal, ray.direction);
  if (!(rate < 0.0)) return std::nullopt;
  return crossing(ray, max_t, dist, rate, *n);
}

}  // namespace proxima::geometry
