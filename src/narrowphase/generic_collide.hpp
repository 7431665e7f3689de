#pragma once
/// @file generic_collide.hpp
/// The contact manifold of a pair without a closed-form routine, from the pair's distance
/// query.
///
/// Steps (the supporting-face manifold of Jolt's CollideConvexVsConvex / Box2D; Gregorius,
/// "Robust Contact Creation for Physics Simulations", GDC 2015):
///  1. the pair's distance query gives the normal n (A to B) and the signed distance; no
///     contact when the gap exceeds the request's contact distance;
///  2. A's supporting feature along +n and B's along -n (supporting_face.hpp);
///  3. when one of them is a face (or a segment) within acos(kReferenceFaceCosine) of n, the
///     other is clipped against it (face_clipping.hpp): points with a gap above the contact
///     distance are dropped, core radii are added, the distance witness is kept when every
///     clipped point is shallower, and the set is reduced to request.max_contacts by area;
///  4. otherwise (curved or tilted features) the one-point manifold of the distance result.
/// A cylinder resting on a box, or two hulls face to face, thus get up to four points.
/// pair_distance (the closed-form or generic one) must be declared before this header.

#include "face_clipping.hpp"
#include "pair_support.hpp"
#include "supporting_face.hpp"

namespace proxima::narrow {

/// Manifold of any convex pair from its distance query: clipped supporting faces when they
/// are aligned with the normal, else one point. Cost: the distance query plus O(n m) for
/// features of n and m points (O(F) more for a hull's face search).
template <class A, class B>
ContactManifold pair_collide(const A& a, const Transform& pose_a, const B& b, const Transform& pose_b,
                             const PairRequest& request, PairCache* cache) {
  if (!finite_poses(pose_a, pose_b)) return invalid_manifold();
  const DistanceResult d = pair_distance(a, pose_a, b, pose_b, request, cache);
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
