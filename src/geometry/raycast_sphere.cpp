// Ray against a solid sphere.
//
// Steps:
//  1. Check the query; an origin inside the closed ball (|m|^2 <= r^2, m = origin - centre)
//     hits at t = 0.
//  2. Work with the unit direction u: a ray from outside that does not approach the centre
//     (m.u >= 0) misses.
//  3. Discriminant in the geometric form r^2 - |m - (m.u) u|^2 = (r - f)(r + f), f the
//     distance from the centre to the line: no cancellation of the large terms b^2 and
//     |m|^2 when the origin is far away.
//  4. Near root from the stable form s = c / q with q = -b + sqrt(disc) and
//     c = (|m| - r)(|m| + r): no cancellation when the origin is close to the surface.
//  5. t = s / |direction|; the normal is the normalised (hit point - centre).
//
// Sources: Ericson, Real-Time Collision Detection, 5.3.2; Haines, Guenter, Hanika, Keller,
// "Precision Improvements for Ray/Sphere Intersection", Ray Tracing Gems (2019), ch. 7;
// Press et al., Numerical Recipes, 5.6 (quadratic roots without cancellation).

#include <proxima/geometry/raycast.hpp>

#include "geometry/raycast_detail.hpp"

namespace proxima::geometry {

namespace detail {

std::optional<Entry> ball_entry(const Vec3& m, const Vec3& u, Real radius) {
  const Real b = glm::dot(m, u);
  if (b >= Real(0)) return std::nullopt;  // outside and moving away (or tangentially)
  const Vec3 f = m - b * u;               // closest point of the line, relative to the centre
  const Real dist = safe_length(f);
  if (dist > radius) return std::nullopt;
  const Real disc = (radius - dist) * (radius + dist);
  const Real q = -b + std::sqrt(disc);  // > 0: the far root's distance
  const Real lm = safe_length(m);
  const Real c = std::max(Real(0), (lm - radius) * (lm + radius));
  const Real s = c / q;
  if (!std::isfinite(s)) return std::nullopt;  // only beyond the supported coordinate range
  return Entry{s, m + s * u};
}

}  // namespace detail

std::optional<RayHit> ray_sphere(const Ray& ray, Real max_t, const Vec3& center, Real radius) noexcept {
  detail::UnitRay r;
  if (!detail::prepare(ray, max_t, r) || !is_finite(center) || !is_finite(radius) || !(radius > Real(0))) {
    return std::nullopt;
  }
  const Vec3 m = ray.origin - center;
  if (glm::dot(m, m) <= radius * radius) return detail::inside_hit(ray, r);
  if (r.length == Real(0)) return std::nullopt;
  const auto e = detail::ball_entry(m, r.unit, radius);
  if (!e) return std::nullopt;
  return detail::surface_hit(ray, max_t, e->s / r.length, e->normal);
}

}  // namespace proxima::geometry
