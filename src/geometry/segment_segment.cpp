// Closest points of two segments.
//
// Steps (the distance |r + s d0 - t d1|^2 is a convex quadratic over the unit square
// (s, t) in [0, 1]^2, r = p0 - q0, d0 = p1 - p0, d1 = q1 - q0; Ericson, Real-Time Collision
// Detection, 5.1.9, with the boundary handled as in Eberly, "Robust Computation of Distance
// Between Line Segments"):
//  1. Huge or tiny coordinates are rescaled by a power of two (no overflow in the degree-4
//     products below).
//  2. Zero-length segments reduce to point-segment.
//  3. Non-parallel segments: the unconstrained minimiser of the two lines, with the
//     numerators written as (d0 x d1).(d1 x r) and (d0 x d1).(d0 x r) so that their error
//     shrinks with the angle. If it lies inside the square it is the answer; it is then
//     polished by one round of exact block minimisation (t from the point of s, then s from
//     the point of t), which removes the error of the 2x2 solve in the flat direction of
//     nearly parallel segments and can only lower the distance.
//  4. Otherwise the minimum lies on the boundary of the square, i.e. it is the nearest of
//     the four end point-segment pairs (p0 and p1 against q0q1, q0 and q1 against p0p1).
//     Each is an exact 1-D clamped projection, so the answer is always a pair of points on
//     the segments, and no decision can go wrong by more than rounding.
//  5. Parallel segments whose projections overlap: every point of the overlap is at the
//     same distance; the midpoint of the overlap on the first segment is returned (a stable
//     choice for contact generation), with its projection on the second.

#include <proxima/core/tolerance.hpp>
#include <proxima/geometry/closest_points.hpp>

namespace proxima::geometry {

namespace {

// Segments whose directions make an angle with sine below this are parallel: along their
// overlap the distance varies by less than this times their length (rounding level).
constexpr Real kParallelSine = Real(16) * kEpsilon;

SegmentPair pair_of(const Vec3& on_a, const Vec3& on_b, Real s, Real t) {
  return {on_a, on_b, s, t, length_squared(on_a - on_b)};
}

}  // namespace

namespace detail {

SegmentPair closest_points_segment_segment_unscaled(const Vec3& p0, const Vec3& p1, const Vec3& q0, const Vec3& q1) {
  const Vec3 d0 = p1 - p0;
  const Vec3 d1 = q1 - q0;
  const Real a = glm::dot(d0, d0);
  const Real e = glm::dot(d1, d1);

  // 2. Degenerate segments.
  if (!(a > Real(0)) && !(e > Real(0))) return pair_of(p0, q0, Real(0), Real(0));
  if (!(a > Real(0))) {
    const SegmentPoint c = closest_point_segment_unscaled(p0, q0, q1);
    return pair_of(p0, c.point, Real(0), c.t);
  }
  if (!(e > Real(0))) {
    const SegmentPoint c = closest_point_segment_unscaled(q0, p0, p1);
    return pair_of(c.point, q0, c.t, Real(0));
  }

  // 3. Interior minimum of the two lines.
  const Vec3 r = p0 - q0;
  const Vec3 n = glm::cross(d0, d1);
  const Real nn = glm::dot(n, n);
  const bool parallel = !(nn > kParallelSine * kParallelSine * a * e);
  if (!parallel) {
    const Real s = glm::dot(n, glm::cross(d1, r)) / nn;
    const Real t = glm::dot(n, glm::cross(d0, r)) / nn;
    if (s >= Real(0) && s <= Real(1) && t >= Real(0) && t <= Real(1)) {
      const SegmentPoint on_b = closest_point_segment_unscaled(p0 + s * d0, q0, q1);
      const SegmentPoint on_a = closest_point_segment_unscaled(on_b.point, p0, p1);
      return pair_of(on_a.point, on_b.point, on_a.t, on_b.t);
    }
  }

  // 4. Boundary of the parameter square: the four end point-segment pairs.
  const SegmentPoint c0 = closest_point_segment_unscaled(p0, q0, q1);
  SegmentPair best = pair_of(p0, c0.point, Real(0), c0.t);
  const SegmentPoint c1 = closest_point_segment_unscaled(p1, q0, q1);
  const SegmentPair b1 = pair_of(p1, c1.point, Real(1), c1.t);
  if (b1.distance_squared < best.distance_squared) best = b1;
  const SegmentPoint c2 = closest_point_segment_unscaled(q0, p0, p1);
  const SegmentPair b2 = pair_of(c2.point, q0, c2.t, Real(0));
  if (b2.distance_squared < best.distance_squared) best = b2;
  const SegmentPoint c3 = closest_point_segment_unscaled(q1, p0, p1);
  const SegmentPair b3 = pair_of(c3.point, q1, c3.t, Real(1));
  if (b3.distance_squared < best.distance_squared) best = b3;

  // 5. Parallel overlap: its midpoint, when it is as near as the best end point pair (up
  // to rounding of the coordinates).
  if (parallel) {
    const Real sq0 = glm::dot(q0 - p0, d0) / a;
    const Real sq1 = glm::dot(q1 - p0, d0) / a;
    const Real lo = std::max(Real(0), std::min(sq0, sq1));
    const Real hi = std::min(Real(1), std::max(sq0, sq1));
    if (lo <= hi) {
      const Real s = Real(0.5) * (lo + hi);
      const Vec3 on_a = p0 + s * d0;
      const SegmentPoint on_b = closest_point_segment_unscaled(on_a, q0, q1);
      const SegmentPair mid = pair_of(on_a, on_b.point, s, on_b.t);
      const Real scale = std::max({max_abs(p0), max_abs(p1), max_abs(q0), max_abs(q1)});
      const Real slack = Real(8) * kEpsilon * scale;
      const Real reach = std::sqrt(best.distance_squared) + slack;
      if (mid.distance_squared <= reach * reach) best = mid;
    }
  }
  return best;
}

}  // namespace detail

SegmentPair closest_points_segment_segment(const Vec3& p0, const Vec3& p1, const Vec3& q0, const Vec3& q1) {
  const Real m = detail::magnitude({p0, p1, q0, q1});
  if (!std::isfinite(m)) return {Vec3(detail::kNaN), Vec3(detail::kNaN), detail::kNaN, detail::kNaN, detail::kNaN};
  const int e = detail::rescale_exponent(m);
  if (e == 0) return detail::closest_points_segment_segment_unscaled(p0, p1, q0, q1);
  SegmentPair r = detail::closest_points_segment_segment_unscaled(detail::scaled(p0, -e), detail::scaled(p1, -e),
                                                                  detail::scaled(q0, -e), detail::scaled(q1, -e));
  r.on_a = detail::scaled(r.on_a, e);
  r.on_b = detail::scaled(r.on_b, e);
  r.distance_squared = std::ldexp(r.distance_squared, 2 * e);
  return r;
}

}  // namespace proxima::geometry
