#pragma once
/// @file polytope_pair_common.hpp
/// Steps shared by the triangle pair routines: the distance result of the SAT with the
/// witness points of a penetration, and their pair_intersect and pair_collide from the
/// distance (the manifold: clipped supporting faces, else one point).
///
/// Witnesses of a penetration: moving B by the exact depth along the SAT normal leaves the
/// two shapes touching (the origin then lies on the boundary of the Minkowski difference),
/// so the closest points of A and of the moved B coincide, and the pair (p, p + sd * n) is a
/// witness of the penetration for any axis kind (face, edge-edge, in-plane edge normal of a
/// flat shape). Taking the deepest clipped point instead is only right for face axes.

#include <algorithm>
#include <cmath>

#include "pair_support.hpp"
#include "pairs_polyhedral.hpp"
#include "small_polytope_sat.hpp"
#include "supporting_face_manifold.hpp"

namespace proxima::narrow {

/// Fills r.point_a and r.point_b for a penetration (r.signed_distance <= 0, r.normal unit, A
/// to B): `closest(shift)` must return the closest points (on A, on B moved by `shift`) of
/// the pair with B translated by `shift` (world frame). The witnesses are the midpoint of
/// those two points and its image along the normal.
template <class ClosestFn>
void penetration_witness(DistanceResult& r, ClosestFn closest) {
  const Vec3 shift = -r.signed_distance * r.normal;  // moves B out by the depth
  Vec3 on_a;
  Vec3 on_b_moved;
  closest(shift, on_a, on_b_moved);
  const Vec3 mid = (on_a + on_b_moved) * Real(0.5);
  r.point_a = mid;
  r.point_b = mid + r.signed_distance * r.normal;
}

/// Distance result of a SAT pair (world frame, normal A to B) from its small-polytope SAT
/// `s` and tolerance `tol`: overlapping, the SAT depth and normal with the witnesses of
/// penetration_witness; separated, the exact closest points, their distance (at least the
/// SAT's separation) and, above 1e-3 tol, their direction as the normal. `closest(shift,
/// on_a, on_b)` fills the closest points of A and of B translated by `*shift` (nullptr: not
/// translated) and returns their squared distance. The SAT axis is cached in A's frame.
template <class ClosestFn>
DistanceResult sat_distance_result(const SmallSat& s, const Transform& pose_a, Real tol, PairCache* cache,
                                   ClosestFn closest) {
  DistanceResult r;
  r.method = PairMethod::Sat;
  r.normal = s.normal;
  if (cache != nullptr) {
    cache->axis = pose_a.inverse_apply_vector(s.normal);
    cache->valid = true;
  }
  if (s.separation > Real(0)) {
    const Real dist = std::sqrt(closest(nullptr, r.point_a, r.point_b));
    Vec3 unit;
    Real len = Real(0);
    if (dist > tol * Real(1e-3) && unit_and_length(r.point_b - r.point_a, unit, len)) r.normal = unit;
    r.signed_distance = std::max(dist, s.separation);
  } else {
    r.signed_distance = s.separation;
    penetration_witness(
        r, [&](const Vec3& shift, Vec3& on_a, Vec3& on_b) { static_cast<void>(closest(&shift, on_a, on_b)); });
  }
  r.status = status_from_distance(r.signed_distance, tol);
  r.tolerance = tol;
  return r;
}

/// pair_collide of a SAT pair from its SAT `s` (the other arguments as sat_distance_result):
/// manifold_of(sat_distance_result(...)), tagged PairMethod::Sat. A penetration whose clipped
/// supporting faces keep a point as deep as the SAT depth skips the closest features
/// (`closest` is not called): the witness would not enter the manifold.
template <class A, class B, class ClosestFn>
ContactManifold sat_collide_result(const A& a, const Transform& pose_a, const B& b, const Transform& pose_b,
                                   const SmallSat& s, Real tol, const PairRequest& request, PairCache* cache,
                                   ClosestFn closest) {
  if (s.separation <= Real(0) && s.separation <= request.contact_distance && request.max_contacts >= 2) {
    const SupportingFace fa = supporting_face(a, pose_a, s.normal);
    const SupportingFace fb = supporting_face(b, pose_b, -s.normal);
    ContactManifold m;
    if (fa.count >= 2 && fb.count >= 2 &&
        deep_clipped_manifold(fa, fb, s.normal, request_within_reach(request, tol), -s.separation, m)) {
      m.normal = s.normal;
      m.status = status_from_distance(s.separation, tol);
      m.method = PairMethod::Sat;
      if (cache != nullptr) {
        cache->axis = pose_a.inverse_apply_vector(s.normal);
        cache->valid = true;
      }
      return m;
    }
  }
  ContactManifold m = manifold_of(a, pose_a, b, pose_b, sat_distance_result(s, pose_a, tol, cache, closest), request);
  m.method = PairMethod::Sat;
  return m;
}

/// pair_intersect of a SAT pair (contract in pair_support.hpp): the touching rule
/// (in_contact) on its pair_distance.
template <class A, class B>
bool sat_pair_intersect(const A& a, const Transform& pose_a, const B& b, const Transform& pose_b,
                        const PairRequest& request, PairCache* cache) {
  if (!poses_in_range(pose_a, pose_b)) return false;
  return in_contact(pair_distance(a, pose_a, b, pose_b, request, cache), request);
}

/// pair_collide of a SAT pair (contract in pair_support.hpp): manifold_of its pair_distance,
/// tagged PairMethod::Sat.
template <class A, class B>
ContactManifold sat_pair_collide(const A& a, const Transform& pose_a, const B& b, const Transform& pose_b,
                                 const PairRequest& request, PairCache* cache) {
  if (!poses_in_range(pose_a, pose_b)) return invalid_manifold();
  const DistanceResult d = pair_distance(a, pose_a, b, pose_b, request, cache);
  ContactManifold m = manifold_of(a, pose_a, b, pose_b, d, request);
  m.method = PairMethod::Sat;
  return m;
}

}  // namespace proxima::narrow
