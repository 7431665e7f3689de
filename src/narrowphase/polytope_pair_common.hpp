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
#include <array>
#include <cmath>
#include <span>

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

/// Gap of two vertex sets along the unit direction `n` (A to B): the smallest projection of
/// B's vertices less the largest of A's, a lower bound of the polytopes' distance, equal to
/// it along the distance's own normal. Taken as the projection of the two supporting
/// vertices' difference, so that its rounding is the gap's, not the coordinates' (the
/// difference of two large projections had put a float mesh-triangle distance 20 ulps off).
inline Real gap_along(const SmallPolytope& pa, const SmallPolytope& pb, const Vec3& n) {
  int top_a = 0;
  int low_b = 0;
  for (int i = 1; i < pa.vertex_count; ++i) {
    if (glm::dot(pa.vertices[i], n) > glm::dot(pa.vertices[top_a], n)) top_a = i;
  }
  for (int j = 1; j < pb.vertex_count; ++j) {
    if (glm::dot(pb.vertices[j], n) < glm::dot(pb.vertices[low_b], n)) low_b = j;
  }
  return glm::dot(pb.vertices[low_b] - pa.vertices[top_a], n);
}

/// Distance result of a SAT pair (world frame, normal A to B) from its small-polytope SAT
/// `s` over the polytopes `pa`, `pb` and tolerance `tol`: overlapping, the SAT depth and
/// normal with the witnesses of penetration_witness; separated, the exact closest points,
/// and as the normal whichever of the SAT's axis, the closest points' direction and that
/// direction taken across each edge direction the polytopes are farther apart along, the
/// distance being that gap (so the gap along the reported normal is the distance, to
/// rounding; any direction's gap is a lower bound of the distance, so the largest is the
/// best). The SAT axis is exact where a face or two crossing edges are closest, the points'
/// direction across the edge where a vertex meets an edge's inside, the direction itself
/// where two vertices are: the rounding of the points (over their distance) then moves the
/// gap only to second order (widest_gap_direction). `closest(shift, on_a, on_b)` fills the
/// closest points of A and of B translated by `*shift` (nullptr: not translated). The SAT
/// axis is cached in A's frame.
template <class ClosestFn>
DistanceResult sat_distance_result(const SmallSat& s, const SmallPolytope& pa, const SmallPolytope& pb,
                                   const Transform& pose_a, Real tol, PairCache* cache, ClosestFn closest) {
  DistanceResult r;
  r.method = PairMethod::Sat;
  r.normal = s.normal;
  if (cache != nullptr) {
    cache->axis = pose_a.inverse_apply_vector(s.normal);
    cache->valid = true;
  }
  if (s.separation > Real(0)) {
    closest(nullptr, r.point_a, r.point_b);
    r.signed_distance = s.separation;
    const auto gap = [&](const Vec3& n) { return gap_along(pa, pb, n); };
    const Vec3 d = r.point_b - r.point_a;
    std::array<Vec3, 6> edges{};  // A's edge directions, then B's
    std::size_t count = 0;
    for (int k = 0; k < pa.edge_count; ++k) edges[count++] = pa.edges[k];
    for (int k = 0; k < pb.edge_count; ++k) edges[count++] = pb.edges[k];
    widest_gap_direction(d, std::span<const Vec3>(edges.data(), count), gap, r.normal, r.signed_distance);
  } else {
    r.signed_distance = s.separation;
    penetration_witness(r, [&](const Vec3& shift, Vec3& on_a, Vec3& on_b) { closest(&shift, on_a, on_b); });
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
                                   const SmallSat& s, const SmallPolytope& pa, const SmallPolytope& pb, Real tol,
                                   const PairRequest& request, PairCache* cache, ClosestFn closest) {
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
  ContactManifold m =
      manifold_of(a, pose_a, b, pose_b, sat_distance_result(s, pa, pb, pose_a, tol, cache, closest), request);
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
