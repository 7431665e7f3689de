#pragma once
/// @file gjk_raycast.hpp
/// Linear cast of one convex set against another by GJK ray casting: the smallest
/// lambda in [0, 1] at which A translated by lambda s comes within `margin` of B.
///
/// Steps (van den Bergen, "Ray casting against general convex objects with application to
/// continuous collision detection", 2004; the margin as in his book, section 4.3.5):
///   1. D(lambda) = (A + lambda s) - B; its distance to the origin is the distance of the
///      translated A to B. Keep a simplex of vertices of D by their support points a_i, b_i,
///      so that w_i = a_i + lambda s - b_i follows lambda.
///   2. v = the point of the simplex nearest the origin; stop with a hit when |v| <= margin
///      + tolerance.
///   3. w = support of D(lambda) along -v. When v.w > margin |v|, the plane of normal v
///      keeps D at more than `margin` from the origin: advance lambda until it does not
///      (v.w(lambda') = margin |v|), or report a miss when s does not close that plane
///      (v.s >= 0, and the plane clears the margin by more than the supports' rounding) or
///      when lambda passes 1. The plane's normal is the hit normal.
///   4. Add w, reduce the simplex (gjk.hpp's signed-volume solver) and repeat.
/// As in gjk.hpp, the simplex arithmetic (w, v, lambda, the plane tests) runs in gjk::Wide
/// on the Real support points, so that near contact v follows the exact points rather than
/// float's rounding of a combination of points as far apart as the pair is large. The
/// rounding of the support points themselves remains: a plane within it of the origin
/// proves nothing (a touching pair moving in was reported as a miss).
/// Header-only, templated on the support functors: no allocation, no exception, never NaN.
#include <proxima/core/math.hpp>
#include <proxima/core/tolerance.hpp>
#include <proxima/geometry/gjk.hpp>

#include <cmath>

namespace proxima::gjk {

/// What cast found. Points are on the sets (before adding the margin), in the common frame,
/// at lambda.
struct CastOutcome {
  bool hit = false;       ///< A + lambda s is within margin (+ tolerance) of B
  bool advanced = false;  ///< lambda moved from 0 (false with a hit: within margin at 0)
  bool capped = false;    ///< the iteration cap stopped it: no answer (hit is false)
  /// No new support point and no advance while |v| is still above margin + tolerance: the
  /// rounding of the supports (float, curved shapes) stops the iteration short of an
  /// answer; hit is false and the caller must decide another way.
  bool stalled = false;
  Real lambda = Real(1);    ///< fraction of s at the hit (1 on a miss)
  Real distance = Real(0);  ///< |v| at lambda: distance of the sets (0 if they overlap)
  Vec3 normal{Real(0)};     ///< unit, from A to B at the hit; zero when never defined
  Vec3 point_a{Real(0)};    ///< nearest point of A + lambda s
  Vec3 point_b{Real(0)};    ///< nearest point of B
  int iterations = 0;       ///< support pairs queried
};

/// Casts A (support `support_a`, at its start placement) along `s` against B (support
/// `support_b`), both in one frame, with `margin` >= 0 (the sum of rounding radii and a
/// target distance) and a length `tolerance` > 0. O(iterations x support cost).
template <class SupportA, class SupportB>
CastOutcome cast(SupportA& support_a, SupportB& support_b, const Vec3& s, Real margin, Real tolerance,
                 int max_iterations) {
  CastOutcome r;
  using W = Wide;
  using WVec3 = WideVec3;
  WideSimplex simplex;
  const WVec3 sw(s);
  W lambda = W(0);
  WVec3 normal(W(0));
  // A first vertex along the motion: the support pair most likely to face each other.
  const Vec3 dir = glm::dot(s, s) > Real(0) ? -s : Vec3(Real(1), Real(0), Real(0));
  WVec3 v = WVec3(support_a(-dir)) - WVec3(support_b(dir));
  W scale2 = glm::dot(v, v);
  const W wmargin = W(margin);
  const W wtolerance = W(tolerance);
  for (int k = 0; k < max_iterations; ++k) {
    r.iterations = k + 1;
    const W vv = glm::dot(v, v);
    const W vn = std::sqrt(vv);
    if (vn <= wmargin + wtolerance) {
      r.hit = true;
      break;
    }
    BasicVertex<W> w;
    const Vec3 vr(v);
    w.a = support_a(-vr);
    w.b = support_b(vr);
    w.w = WVec3(w.a) + lambda * sw - WVec3(w.b);
    scale2 = std::max(scale2, glm::dot(w.w, w.w));
    const W vw = glm::dot(v, w.w);
    bool moved = false;
    const W vs = glm::dot(v, sw);
    // A plane that s does not close proves a miss only when it clears the margin by more
    // than the supports' rounding: touching sets have planes of nearly every direction
    // within rounding of the origin, most of them opening along s. Below that, w joins the
    // simplex without an advance.
    const bool opening = !(vs < W(0));
    if (vw > wmargin * vn && !(opening && vw - wmargin * vn <= W(8) * W(kEpsilon) * std::sqrt(scale2) * vn)) {
      if (opening) return r;  // s does not close the separating plane: miss
      lambda -= (vw - wmargin * vn) / vs;
      if (!(lambda <= W(1))) return r;
      normal = (WVec3(W(0)) - v) / vn;
      r.advanced = moved = true;
      for (int i = 0; i < simplex.size; ++i)
        simplex.v[i].w = WVec3(simplex.v[i].a) + lambda * sw - WVec3(simplex.v[i].b);
      w.w = WVec3(w.a) + lambda * sw - WVec3(w.b);
    }
    bool repeated = false;
    for (int i = 0; i < simplex.size; ++i) repeated = repeated || (simplex.v[i].a == w.a && simplex.v[i].b == w.b);
    if (repeated && !moved) {
      // No new support point and no advance: the distance is |v| within rounding.
      r.hit = vn <= wmargin + wtolerance + W(8) * W(kEpsilon) * std::sqrt(scale2);
      if (!r.hit) {
        r.stalled = true;
        return r;
      }
      break;
    }
    if (!repeated) {
      for (int i = simplex.size; i > 0; --i) simplex.v[i] = simplex.v[i - 1];
      simplex.v[0] = w;
      ++simplex.size;
    }
    detail::reduce(simplex);
    if (simplex.size == 4) {
      v = WVec3(W(0));  // the origin is inside: the sets overlap at lambda
      r.hit = true;
      break;
    }
    v = combine(simplex, 0);
  }
  if (!r.hit) {
    r.capped = true;
    return r;
  }
  r.lambda = Real(lambda);
  r.distance = simplex.size == 4 ? Real(0) : Real(glm::length(v));
  r.point_a = simplex.size > 0 ? Vec3(combine(simplex, 1) + lambda * sw) : Vec3(WVec3(support_a(-dir)) + lambda * sw);
  r.point_b = simplex.size > 0 ? Vec3(combine(simplex, 2)) : support_b(dir);
  // The normal: along -v (the simplex's nearest point, better than a difference of
  // witnesses) when the sets are clearly apart, else the last separating plane's.
  const W distance = simplex.size == 4 ? W(0) : glm::length(v);
  if (distance > wtolerance || (!r.advanced && distance > W(0))) normal = WVec3(W(0)) - v;  // no negative zeros
  const W length = glm::length(normal);
  r.normal = length > W(0) ? Vec3(normal / length) : Vec3(normal);
  return r;
}

}  // namespace proxima::gjk
