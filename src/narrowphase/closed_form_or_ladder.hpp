#pragma once
/// @file closed_form_or_ladder.hpp
/// Private building blocks of the curved pairs whose closed form holds in some poses only
/// (pairs_curved.hpp: parallel cylinders, coaxial cones): the answer of such a closed form
/// from its local solution, and the three queries that take it where it applies and the
/// generic ladder (generic_distance.hpp) elsewhere.

#include <proxima/core/tolerance.hpp>

#include "generic_distance.hpp"
#include "pair_support.hpp"
#include "supporting_face_manifold.hpp"

namespace proxima::narrow::detail {

/// A closed form's answer from its solution in A's frame: signed distance `sd` along the unit
/// normal `n_local` (A to B), A's witness `on_a_local`, B's at A's plus sd along the normal
/// (a point of B where the solution is exact); tolerance resolved at the pair's `scale`.
inline DistanceResult analytic_answer(const Transform& pose_a, Real sd, const Vec3& n_local, const Vec3& on_a_local,
                                      const PairRequest& request, Real scale) {
  DistanceResult r;
  r.signed_distance = sd;
  r.normal = pose_a.apply_vector(n_local);
  r.point_a = pose_a.apply(on_a_local);
  r.point_b = r.point_a + sd * r.normal;
  r.tolerance = resolve_tolerance(request, scale);
  r.status = status_from_distance(sd, r.tolerance);
  r.method = PairMethod::Analytic;
  r.iterations = 0;
  return r;
}

/// pair_distance: `closed(a, pose_a, b, pose_b, request, r)` fills r and returns true where
/// its closed form applies; elsewhere the generic ladder.
template <class A, class B, class ClosedForm>
DistanceResult closed_form_or_ladder_distance(const A& a, const Transform& pose_a, const B& b, const Transform& pose_b,
                                              const PairRequest& request, PairCache* cache, ClosedForm closed) {
  if (!poses_in_range(pose_a, pose_b)) return invalid_distance();
  DistanceResult r;
  if (closed(a, pose_a, b, pose_b, request, r)) return r;
  return generic_distance(a, pose_a, b, pose_b, request, cache);
}

/// pair_intersect: the touching rule on the closed form where it applies, else generic
/// boolean GJK.
template <class A, class B, class ClosedForm>
bool closed_form_or_ladder_intersect(const A& a, const Transform& pose_a, const B& b, const Transform& pose_b,
                                     const PairRequest& request, PairCache* cache, ClosedForm closed) {
  if (!poses_in_range(pose_a, pose_b)) return false;
  DistanceResult r;
  if (closed(a, pose_a, b, pose_b, request, r)) return in_contact(r, request);
  return generic_intersect(a, pose_a, b, pose_b, request, cache);
}

/// pair_collide: the supporting features along the distance's normal, clipped.
template <class A, class B, class ClosedForm>
ContactManifold closed_form_or_ladder_collide(const A& a, const Transform& pose_a, const B& b, const Transform& pose_b,
                                              const PairRequest& request, PairCache* cache, ClosedForm closed) {
  if (!poses_in_range(pose_a, pose_b)) return invalid_manifold();
  return manifold_of(a, pose_a, b, pose_b, closed_form_or_ladder_distance(a, pose_a, b, pose_b, request, cache, closed),
                     request);
}

}  // namespace proxima::narrow::detail

/// Defines pair_distance, pair_intersect and pair_collide of the curved pair (A, A)
/// (pairs_curved.hpp) from its closed form `closed` (a function as closed_form_or_ladder_distance
/// takes), the generic ladder elsewhere.
#define PROXIMA_CLOSED_FORM_OR_LADDER(A, closed)                                                         \
  DistanceResult pair_distance(const A& a, const Transform& pose_a, const A& b, const Transform& pose_b, \
                               const PairRequest& request, PairCache* cache) {                           \
    return detail::closed_form_or_ladder_distance(a, pose_a, b, pose_b, request, cache, closed);         \
  }                                                                                                      \
  bool pair_intersect(const A& a, const Transform& pose_a, const A& b, const Transform& pose_b,          \
                      const PairRequest& request, PairCache* cache) {                                    \
    return detail::closed_form_or_ladder_intersect(a, pose_a, b, pose_b, request, cache, closed);        \
  }                                                                                                      \
  ContactManifold pair_collide(const A& a, const Transform& pose_a, const A& b, const Transform& pose_b, \
                               const PairRequest& request, PairCache* cache) {                           \
    return detail::closed_form_or_ladder_collide(a, pose_a, b, pose_b, request, cache, closed);          \
  }
