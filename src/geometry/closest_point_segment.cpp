// Closest points on points, lines and segments.
//
// Steps:
//  1. Inputs whose coordinates are huge or tiny are rescaled by an exact power of two
//     (detail::rescale_exponent) so that no product below overflows or underflows.
//  2. Point-line and point-segment: project p - a on the direction, t = (p - a).d / d.d,
//     clamped to [0, 1] for segments before the division so that t never leaves its range
//     (Ericson, Real-Time Collision Detection, 5.1.2).
//  3. Line-line: the normal equations of |r + s d0 - t d1|^2 solved with the numerators
//     written as (d0 x d1).(d1 x r) and (d0 x d1).(d0 x r) (Binet-Cauchy identity), whose
//     rounding error shrinks with the angle between the lines instead of cancelling
//     catastrophically as b f - c e does (Ericson 5.1.8); parallel lines take s = 0.

#include <proxima/core/tolerance.hpp>
#include <proxima/geometry/closest_points.hpp>

namespace proxima::geometry {

namespace {

// Lines whose directions make an angle with sine below this are parallel.
constexpr Real kParallelSine = Real(16) * kEpsilon;

// x * 2^e clamped to the finite range (a parameter of a nearly degenerate direction).
Real finite_ldexp(Real x, int e) { return std::clamp(std::ldexp(x, e), -kRealMax, kRealMax); }

// Closest point on a line, inputs already in the safe range (d may be zero).
SegmentPoint closest_point_line_unscaled(const Vec3& p, const Vec3& a, const Vec3& d) {
  const Real dd = glm::dot(d, d);
  if (!(dd > Real(0))) return {a, Real(0)};
  const Real t = glm::dot(p - a, d) / dd;
  return {a + t * d, t};
}

SegmentPair line_line_unscaled(const Vec3& p0, const Vec3& d0, const Vec3& p1, const Vec3& d1) {
  const Real a = glm::dot(d0, d0);
  const Real e = glm::dot(d1, d1);
  const Vec3 r = p0 - p1;
  Real s = Real(0);
  Real t = Real(0);
  if (a > Real(0) && e > Real(0)) {
    const Vec3 n = glm::cross(d0, d1);
    const Real nn = glm::dot(n, n);
    if (nn > kParallelSine * kParallelSine * a * e) {
      s = glm::dot(n, glm::cross(d1, r)) / nn;
      t = glm::dot(n, glm::cross(d0, r)) / nn;
    } else {
      t = glm::dot(r, d1) / e;
    }
  } else if (e > Real(0)) {
    t = glm::dot(r, d1) / e;
  } else if (a > Real(0)) {
    s = -glm::dot(r, d0) / a;
  }
  SegmentPair out;
  out.s = s;
  out.t = t;
  out.on_a = p0 + s * d0;
  out.on_b = p1 + t * d1;
  out.distance_squared = length_squared(out.on_a - out.on_b);
  return out;
}

}  // namespace

Real distance_squared_point_point(const Vec3& p, const Vec3& q) {
  const Real m = detail::magnitude({p, q});
  if (!std::isfinite(m)) return detail::kNaN;
  const int e = detail::rescale_exponent(m);
  if (e == 0) return length_squared(p - q);
  return std::ldexp(length_squared(detail::scaled(p, -e) - detail::scaled(q, -e)), 2 * e);
}

SegmentPoint closest_point_line(const Vec3& p, const Vec3& a, const Vec3& d) {
  const Real m = detail::magnitude({p, a});
  const Real dmax = detail::magnitude({d});
  if (!std::isfinite(m) || !std::isfinite(dmax)) return {Vec3(detail::kNaN), detail::kNaN};
  const int ep = detail::rescale_exponent(m);
  if (dmax == Real(0)) return {a, Real(0)};
  const int ed = detail::rescale_exponent(dmax);
  if (ep == 0 && ed == 0) return closest_point_line_unscaled(p, a, d);
  const Vec3 ps = detail::scaled(p, -ep);
  const Vec3 as = detail::scaled(a, -ep);
  const SegmentPoint r = closest_point_line_unscaled(ps, as, detail::scaled(d, -ed));
  return {detail::scaled(r.point, ep), finite_ldexp(r.t, ep - ed)};
}

SegmentPoint closest_point_segment(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Real m = detail::magnitude({p, a, b});
  if (!std::isfinite(m)) return {Vec3(detail::kNaN), detail::kNaN};
  const int e = detail::rescale_exponent(m);
  if (e == 0) return detail::closest_point_segment_unscaled(p, a, b);
  const SegmentPoint r =
      detail::closest_point_segment_unscaled(detail::scaled(p, -e), detail::scaled(a, -e), detail::scaled(b, -e));
  // The end points are returned exactly, not through a round trip of the scaling.
  if (r.t == Real(0)) return {a, Real(0)};
  if (r.t == Real(1)) return {b, Real(1)};
  return {detail::scaled(r.point, e), r.t};
}

SegmentPair closest_points_line_line(const Vec3& p0, const Vec3& d0, const Vec3& p1, const Vec3& d1) {
  const Real mp = detail::magnitude({p0, p1});
  const Real m0 = detail::magnitude({d0});
  const Real m1 = detail::magnitude({d1});
  if (!std::isfinite(mp) || !std::isfinite(m0) || !std::isfinite(m1)) {
    return {Vec3(detail::kNaN), Vec3(detail::kNaN), detail::kNaN, detail::kNaN, detail::kNaN};
  }
  const int ep = detail::rescale_exponent(mp);
  const int e0 = detail::rescale_exponent(m0);
  const int e1 = detail::rescale_exponent(m1);
  if (ep == 0 && e0 == 0 && e1 == 0) return line_line_unscaled(p0, d0, p1, d1);
  SegmentPair r = line_line_unscaled(detail::scaled(p0, -ep), detail::scaled(d0, -e0), detail::scaled(p1, -ep),
                                     detail::scaled(d1, -e1));
  r.s = finite_ldexp(r.s, ep - e0);
  r.t = finite_ldexp(r.t, ep - e1);
  r.on_a = detail::scaled(r.on_a, ep);
  r.on_b = detail::scaled(r.on_b, ep);
  r.distance_squared = std::ldexp(r.distance_squared, 2 * ep);
  return r;
}

}  // namespace proxima::geometry
