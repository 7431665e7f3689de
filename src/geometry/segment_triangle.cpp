// Closest points of a segment and a triangle.
//
// Steps (Ericson, Real-Time Collision Detection, 5.1.10 and 5.3.6):
//  1. Huge or tiny coordinates are rescaled by a power of two.
//  2. Crossing: when the end points lie on opposite sides of the triangle's plane (or one
//     on it) and the line pq passes inside the three edges (the signs of the scalar triple
//     products [pq, pc, pb], [pq, pa, pc], [pq, pb, pa] agree), the segment meets the
//     triangle where it crosses the plane. That point is confirmed by its distance to the
//     triangle (a segment nearly in the plane has a noisy crossing): within a few rounding
//     errors it is returned as the common point, distance 0; otherwise it only joins the
//     candidates of step 3. Thin triangles and segments lying in the plane are left to
//     step 3, whose edge candidates find their contacts.
//  3. Otherwise the closest pair involves an end point of the segment or an edge of the
//     triangle (an interior point of each would need the segment parallel to the plane,
//     and then sliding along it reaches one of those): the nearest of the two end
//     point-triangle pairs and the three segment-edge pairs.

#include <proxima/core/tolerance.hpp>
#include <proxima/geometry/closest_points.hpp>

namespace proxima::geometry {

namespace detail {

bool segment_crosses_triangle(const Vec3& p, const Vec3& q, const Vec3& a, const Vec3& b, const Vec3& c, Vec3& point) {
  const Vec3 n = glm::cross(b - a, c - a);
  if (is_thin_triangle(n, a, b, c)) return false;
  return segment_crosses_triangle(p, q, a, b, c, n, point);
}

bool segment_crosses_triangle(const Vec3& p, const Vec3& q, const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& n,
                              Vec3& point) {
  const Real dp = glm::dot(n, p - a);
  const Real dq = glm::dot(n, q - a);
  if ((dp > Real(0) && dq > Real(0)) || (dp < Real(0) && dq < Real(0)) || dp == dq) return false;
  const Vec3 pq = q - p;
  const Vec3 pa = a - p;
  const Vec3 pb = b - p;
  const Vec3 pc = c - p;
  const Real u = glm::dot(pq, glm::cross(pc, pb));
  const Real v = glm::dot(pq, glm::cross(pa, pc));
  const Real w = glm::dot(pq, glm::cross(pb, pa));
  const bool inside = (u >= Real(0) && v >= Real(0) && w >= Real(0)) || (u <= Real(0) && v <= Real(0) && w <= Real(0));
  if (!inside) return false;
  // dp and dq have opposite signs (or one is 0) and differ, so t lies in [0, 1].
  const Real t = std::min(Real(1), std::max(Real(0), dp / (dp - dq)));
  point = p + t * pq;
  return true;
}

Crossing common_point_segment_triangle(const Vec3& p, const Vec3& q, const Vec3& a, const Vec3& b, const Vec3& c,
                                       const Vec3& n, Real accept, ClosestPair& pair) {
  Vec3 x;
  if (!segment_crosses_triangle(p, q, a, b, c, n, x)) return Crossing::None;
  const Vec3 y = closest_point_triangle_unscaled(x, a, b, c).point;
  const Real d2 = length_squared(x - y);
  if (d2 <= accept * accept) {
    pair = {x, x, Real(0)};
    return Crossing::Common;
  }
  pair = {x, y, d2};
  return Crossing::Candidate;
}

ClosestPair closest_points_segment_triangle_unscaled(const Vec3& p, const Vec3& q, const Vec3& a, const Vec3& b,
                                                     const Vec3& c) {
  ClosestPair best{p, a, kRealMax};
  const Vec3 n = glm::cross(b - a, c - a);
  if (!is_thin_triangle(n, a, b, c)) {
    const Real scale = magnitude({p, q, a, b, c});
    const Crossing crossing = common_point_segment_triangle(p, q, a, b, c, n, crossing_acceptance(scale), best);
    if (crossing == Crossing::Common) return best;
  }

  const TrianglePoint tp = closest_point_triangle_unscaled(p, a, b, c);
  const Real dp = length_squared(p - tp.point);
  if (dp < best.distance_squared) best = {p, tp.point, dp};
  const TrianglePoint tq = closest_point_triangle_unscaled(q, a, b, c);
  const Real dq = length_squared(q - tq.point);
  if (dq < best.distance_squared) best = {q, tq.point, dq};
  const Vec3* const edges[3][2] = {{&a, &b}, {&b, &c}, {&c, &a}};
  for (const auto& edge : edges) {
    const SegmentPair s = closest_points_segment_segment_unscaled(p, q, *edge[0], *edge[1]);
    if (s.distance_squared < best.distance_squared) best = {s.on_a, s.on_b, s.distance_squared};
  }
  return best;
}

}  // namespace detail

ClosestPair closest_points_segment_triangle(const Vec3& p, const Vec3& q, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Real m = detail::magnitude({p, q, a, b, c});
  if (!std::isfinite(m)) return {Vec3(detail::kNaN), Vec3(detail::kNaN), detail::kNaN};
  const int e = detail::rescale_exponent(m);
  if (e == 0) return detail::closest_points_segment_triangle_unscaled(p, q, a, b, c);
  ClosestPair r = detail::closest_points_segment_triangle_unscaled(detail::scaled(p, -e), detail::scaled(q, -e),
                                                                   detail::scaled(a, -e), detail::scaled(b, -e),
                                                                   detail::scaled(c, -e));
  r.on_a = detail::scaled(r.on_a, e);
  r.on_b = detail::scaled(r.on_b, e);
  r.distance_squared = std::ldexp(r.distance_squared, 2 * e);
  return r;
}

}  // namespace proxima::geometry
