// Ray against a solid capsule: the points within `radius` of segment p0p1.
//
// Steps:
//  1. Origin inside (distance to the segment <= radius): t = 0.
//  2. The capsule is the union of three convex pieces: the ball at p0, the ball at p1 and
//     the body (infinite cylinder of the same radius clipped to the slab between the two
//     end planes). With the origin outside the union, the first hit is the earliest entry
//     into any piece.
//  3. Balls: the sphere cast (cancellation-safe quadratic).
//  4. Body: only entries through the lateral surface count, i.e. the entering root of the
//     2-D disc test whose axial coordinate lies in [0, L]. An entry through an end disc
//     is never first, since that disc lies inside the ball at the same end; so a ray along
//     the axis is handled by the balls alone.
//  5. A zero-length segment is a sphere.
//
// Sources: Ericson, Real-Time Collision Detection, 5.3.7 (capsule as cylinder plus
// spheres); Quilez, "Intersectors" (capsule); Press et al., Numerical Recipes, 5.6.

#include <proxima/geometry/raycast.hpp>

#include "geometry/raycast_detail.hpp"

namespace proxima::geometry {

std::optional<RayHit> ray_capsule(const Ray& ray, Real max_t, const Vec3& p0, const Vec3& p1, Real radius) noexcept {
  detail::UnitRay r;
  if (!detail::prepare(ray, max_t, r) || !is_finite(p0) || !is_finite(p1) || !is_finite(radius) ||
      !(radius > Real(0))) {
    return std::nullopt;
  }
  const detail::AxisFrame frame = detail::axis_frame(p0, p1);
  const Real len = frame.length;
  const Vec3 m = frame.local(ray.origin - p0);
  const Real dz = m.z - std::clamp(m.z, Real(0), len);
  if (m.x * m.x + m.y * m.y + dz * dz <= radius * radius) return detail::inside_hit(ray, r);
  if (r.length == Real(0)) return std::nullopt;

  std::optional<detail::Entry> best = detail::ball_entry(ray.origin - p0, r.unit, radius);
  if (len > Real(0)) {
    const auto end = detail::ball_entry(ray.origin - p1, r.unit, radius);
    if (end && (!best || end->s < best->s)) best = end;

    const Vec3 u = frame.local(r.unit);
    const detail::Interval side = detail::disc_interval(Vec2(m.x, m.y), Vec2(u.x, u.y), radius, 0);
    if (side.lo_feature == 0 && !side.empty() && side.hi >= Real(0)) {
      const Real s = std::max(side.lo, Real(0));  // before 0 only by rounding at the surface
      if (std::isfinite(s)) {
        const Real z = m.z + s * u.z;
        if (z >= Real(0) && z <= len && (!best || s < best->s)) {
          best = detail::Entry{s, frame.world(m.x + s * u.x, m.y + s * u.y, Real(0))};
        }
      }
    }
  }
  if (!best) return std::nullopt;
  return detail::surface_hit(ray, max_t, best->s / r.length, best->normal);
}

}  // namespace proxima::geometry
