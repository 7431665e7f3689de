#pragma once
/// @file polytope_pair_common.hpp
/// Steps shared by the triangle pair routines: the witness points of a penetration found by
/// the SAT, and the manifold of a distance result (clipped supporting faces, else one point).
///
/// Witnesses of a penetration: moving B by the exact depth along the SAT normal leaves the
/// two shapes touching (the origin then lies on the boundary of the Minkowski difference),
/// so the closest points of A and of the moved B coincide, and the pair (p, p + sd * n) is a
/// witness of the penetration for any axis kind (face, edge-edge, in-plane edge normal of a
/// flat shape). Taking the deepest clipped point instead is only right for face axes.

#include "face_clipping.hpp"
#include "pair_support.hpp"
#include "supporting_face.hpp"

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

/// Manifold from a distance result: clipped supporting faces when aligned, else one point.
template <class A, class B>
ContactManifold manifold_of(const A& a, const Transform& pose_a, const B& b, const Transform& pose_b,
                            const DistanceResult& d, const PairRequest& request) {
  ContactManifold m = manifold_from_distance(d, request);
  if (m.count == 0 || request.max_contacts < 2) return m;
  const SupportingFace fa = supporting_face(a, pose_a, d.normal);
  const SupportingFace fb = supporting_face(b, pose_b, -d.normal);
  if (fa.count < 2 || fb.count < 2) return m;
  ContactManifold clipped = m;
  const ContactPoint witness = m.points[0];
  if (clipped_manifold(fa, fb, d.normal, request, clipped, &witness)) return clipped;
  return m;
}

}  // namespace proxima::narrow
