// Ray against a solid capped cylinder (axis p0p1, radius r).
//
// Steps:
//  1. Local frame: unit axis a = (p1 - p0) / L and two unit vectors orthogonal to it; the
//     origin (relative to p0) and the unit direction get coordinates (x, y, z).
//  2. Origin inside the closed solid (0 <= z <= L and x^2 + y^2 <= r^2): t = 0.
//  3. Cap slab 0 <= z <= L: 1-D slab interval (whole line or nothing for a direction
//     orthogonal to the axis).
//  4. Lateral surface: the 2-D line (x, y) + s (ux, uy) against the disc of radius r,
//     solved along the unit 2-D direction. The discriminant is taken in the geometric
//     form (r - f)(r + f), f the distance from the axis to the projected line, and the
//     roots from the cancellation-free form; a direction parallel to the axis gives the
//     whole line or nothing.
//  5. Intersect the two intervals; the later entry decides the face: cap (normal -a or
//     +a) or lateral (normal = radial direction of the hit point).
//
// Sources: Ericson, Real-Time Collision Detection, 5.3.7 (segment against cylinder);
// Kay, Kajiya (slabs); Press et al., Numerical Recipes, 5.6 (quadratic roots).

#include <proxima/geometry/raycast.hpp>

#include "geometry/raycast_detail.hpp"

namespace proxima::geometry {

namespace detail {

Interval disc_interval(const Vec2& m, const Vec2& u, Real r, int feature) {
  constexpr Real kInf = std::numeric_limits<Real>::infinity();
  Interval none;
  none.lo = kInf;
  none.hi = -kInf;
  Real speed;
  Vec3 dir3;
  if (!length_and_direction(Vec3(u, Real(0)), speed, dir3)) {
    // Parallel to the axis (or a zero direction): the radius never changes.
    if (glm::dot(m, m) <= r * r) return Interval{};
    return none;
  }
  // Solve along the unit 2-D direction (distance sigma = s * speed), so that nothing is
  // divided by a tiny |u|^2.
  const Vec2 dir(dir3.x, dir3.y);
  const Real b = glm::dot(m, dir);
  const Vec2 f = m - b * dir;  // closest point of the projected line to the axis
  const Real dist = safe_length(Vec3(f, Real(0)));
  if (dist > r) return none;
  const Real disc = (r - dist) * (r + dist);  // = b^2 - c
  const Real lm = safe_length(Vec3(m, Real(0)));
  const Real c = (lm - r) * (lm + r);
  Interval in = quadratic_nonpositive(Real(1), b, c, disc, feature).first;
  in.lo /= speed;
  in.hi /= speed;
  return in;
}

}  // namespace detail

namespace {

enum CylinderFeature : int { CylinderCapStart = 0, CylinderCapEnd = 1, CylinderLateral = 2 };

}  // namespace

std::optional<RayHit> ray_cylinder(const Ray& ray, Real max_t, const Vec3& p0, const Vec3& p1, Real radius) noexcept {
  detail::UnitRay r;
  if (!detail::prepare(ray, max_t, r) || !is_finite(p0) || !is_finite(p1) || !is_finite(radius) ||
      !(radius > Real(0))) {
    return std::nullopt;
  }
  const detail::AxisFrame frame = detail::axis_frame(p0, p1);
  if (!(frame.length > Real(0))) return std::nullopt;
  const Vec3 m = frame.local(ray.origin - p0);
  const Real len = frame.length;
  if (m.z >= Real(0) && m.z <= len && m.x * m.x + m.y * m.y <= radius * radius) return detail::inside_hit(ray, r);
  if (r.length == Real(0)) return std::nullopt;
  const Vec3 u = frame.local(r.unit);

  detail::Interval span = detail::slab_interval(m.z, u.z, Real(0), len, CylinderCapStart, CylinderCapEnd);
  if (span.empty()) return std::nullopt;
  span = span.clipped(detail::disc_interval(Vec2(m.x, m.y), Vec2(u.x, u.y), radius, CylinderLateral));
  if (span.empty() || span.hi < Real(0)) return std::nullopt;
  // The origin tested outside: an entry before 0 is rounding at the surface.
  const Real s = std::max(span.lo, Real(0));
  if (!std::isfinite(s)) return std::nullopt;
  Vec3 normal;
  switch (span.lo_feature) {
    case CylinderCapStart: normal = -frame.axis; break;
    case CylinderCapEnd: normal = frame.axis; break;
    case CylinderLateral: normal = frame.world(m.x + s * u.x, m.y + s * u.y, Real(0)); break;
    default: return detail::inside_hit(ray, r);
  }
  return detail::surface_hit(ray, max_t, s / r.length, normal);
}

}  // namespace proxima::geometry
