#pragma once
/// @file surface_projection.hpp
/// The distance between two separated convex shapes A and B from their closest-point
/// queries alone: the stage of the generic ladder (generic_distance.hpp) that answers where
/// GJK stalled with its duality gap open on a pair with no point, segment, triangle or box
/// core (two curved shapes, or a hull and a curved shape).
///
/// Why: on a rim, a ruled side or a flat face GJK's simplex turns into a sliver whose plane
/// is known only to eps / (its width), and the iteration stops with its gap open, up to
/// 1e-7 of the size in double (docs/validation.md, "GJK near contact"). The closest-point
/// queries compute on each shape's own geometry (closed forms, Eberly's root finder for the
/// ellipsoid), so their points lie on the surfaces to rounding.
///
/// Steps:
///   1. alternating projections (von Neumann; Cheney, Goldstein, Proc. AMS 10, 1959) from
///      GJK's witness on A: q_B = B's closest point to p_A, p_A = A's closest point to q_B,
///      while |p_A - q_B| falls; for convex sets apart this converges to a pair of closest
///      points (linearly, fast from GJK's start in practice: 1 to 5 rounds at gaps of 1e-3
///      to 1e-7 of the size), but slowly where the gap tends to 0 (tangent sets: sublinear)
///      or two ruled sides are nearly parallel. Its distance is an upper bound (two points
///      of the sets);
///   2. the normal from geometry, not from the difference of nearby points: of A's normal at
///      p_A, B's normal at q_B (negated), GJK's direction and the direction q_B - p_A, the
///      one along which the support functions separate the shapes most; that separation
///      is a lower bound of the distance (a separating plane), so the answer carries its own
///      duality gap. At a smooth side a lateral error t of the points tilts its normal by
///      t / R only, where the difference direction tilts by t / distance.
/// Header-only, no allocation; at most 2 kMaxRounds closest-point queries and 8 supports.

#include <proxima/core/math.hpp>

#include <cmath>
#include <limits>

#include "core_closest_point.hpp"

namespace proxima::narrow {

/// What surface_projection found (A's frame).
struct SurfaceProjection {
  Real upper = std::numeric_limits<Real>::infinity();   ///< |point_a - point_b|: two points of the sets (length)
  Real lower = -std::numeric_limits<Real>::infinity();  ///< separation along `normal` (length): a lower bound
  Vec3 point_a{Real(0)};                                ///< on A's surface
  Vec3 point_b{Real(0)};                                ///< on B's surface, B's closest point to point_a
  Vec3 normal{Real(0), Real(0), Real(1)};               ///< unit, A to B: the best separating direction found
  int rounds = 0;                                       ///< rounds of step 1 (two closest-point queries each)
};

namespace surface_projection_detail {

/// Rounds of step 1 at most; slower cases stop there with the gap open, which the answer's
/// bounds show.
inline constexpr int kMaxRounds = 48;

/// Separation of A and B along unit n (A to B): min over B of n.x minus max over A of n.x.
template <class SupportA, class SupportB>
Real separation(SupportA& support_a, SupportB& support_b, const Vec3& n) {
  return glm::dot(n, support_b(-n)) - glm::dot(n, support_a(n));
}

}  // namespace surface_projection_detail

/// Steps 1-2 (see the file comment) for A and B placed in a common frame, from `start_a`
/// (a point on or near A, GJK's witness) and GJK's unit direction `gjk_normal` (A to B).
/// `support_a` and `support_b` are the full shapes' supports in that frame (cores plus
/// radii). The shapes must be apart for `upper` to be their distance.
template <class A, class B, class SupportA, class SupportB>
SurfaceProjection surface_projection(const PlacedShape<A>& a, const PlacedShape<B>& b, SupportA& support_a,
                                     SupportB& support_b, const Vec3& start_a, const Vec3& gjk_normal) {
  namespace sp = surface_projection_detail;
  SurfaceProjection r;
  Vec3 b_normal = gjk_normal;  // B's normal at point_b, negated (A to B)
  Vec3 p = start_a;
  for (int round = 0; round < sp::kMaxRounds; ++round) {  // step 1
    const CoreClosest on_b = b.closest(p);
    const CoreClosest on_a = a.closest(on_b.surface_point);
    ++r.rounds;
    if (!(on_a.signed_distance < r.upper)) break;  // no longer falls (or not finite): converged to rounding
    r.upper = on_a.signed_distance;
    r.point_a = on_a.surface_point;
    r.point_b = on_b.surface_point;
    r.normal = on_a.normal;  // A's outward normal, towards B
    b_normal = -on_b.normal;
    p = on_a.surface_point;
  }
  // Step 2: the direction along which the supports separate the shapes most.
  const Vec3 diff = r.point_b - r.point_a;
  const Real dl = glm::length(diff);
  const Vec3 candidates[4] = {r.normal, b_normal, gjk_normal, dl > Real(0) ? diff / dl : gjk_normal};
  for (const Vec3& n : candidates) {
    const Real s = sp::separation(support_a, support_b, n);
    if (s > r.lower) {
      r.lower = s;
      r.normal = n;
    }
  }
  return r;
}

}  // namespace proxima::narrow
