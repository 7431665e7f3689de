// Ray against a plane n.x = d (two-sided surface) and against the solid half-space
// n.x <= d.
//
// Steps:
//  1. Signed distance of the origin, dist = n.origin - d, and the approach rate
//     n.direction (both scale with |n|, so t does not depend on the normal's length; a
//     zero normal never hits).
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
  const Real len = detail::safe_length(normal);
  if (!(len > Real(0))) return std::nullopt;
  return normal / len;
}

}  // namespace

std::optional<RayHit> ray_plane(const Ray& ray, Real max_t, const Vec3& normal, Real offset) {
  detail::UnitRay r;
  const auto n = plane_normal(ray, max_t, normal, offset, r);
  if (!n) return std::nullopt;
  const Real dist = glm::dot(normal, ray.origin) - offset;
  const Real rate = glm::dot(normal, ray.direction);
  if (dist == Real(0)) return RayHit{Real(0), ray.origin, rate > Real(0) ? -*n : *n};
  if (dist > Real(0) ? !(rate < Real(0)) : !(rate > Real(0))) return std::nullopt;
  return detail::surface_hit(ray, max_t, -dist / rate, dist > Real(0) ? *n : -*n);
}

std::optional<RayHit> ray_halfspace(const Ray& ray, Real max_t, const Vec3& normal, Real offset) {
  detail::UnitRay r;
  const auto n = plane_normal(ray, max_t, normal, offset, r);
  if (!n) return std::nullopt;
  const Real dist = glm::dot(normal, ray.origin) - offset;
  if (dist <= Real(0)) return detail::inside_hit(ray, r);
  const Real rate = glm::dot(normal, ray.direction);
  if (!(rate < Real(0))) return std::nullopt;
  return detail::surface_hit(ray, max_t, dist / -rate, *n);
}

}  // namespace proxima::geometry
