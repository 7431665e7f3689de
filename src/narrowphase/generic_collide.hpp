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

#include "pair_support.hpp"
#include "supporting_face_manifold.hpp"

namespace proxima::narrow {

/// Manifold of any convex pair from its distance query: clipped supporting faces when they
/// are aligned with the normal, else one point. Cost: the distance query plus O(n m) for
/// features of n and m points (O(F) more for a hull's face search).
template <class A, class B>
ContactManifold pair_collide(const A& a, const Transform& pose_a, const B& b, const Transform& pose_b,
                             const PairRequest& request, PairCache* cache) {
  if (!poses_in_range(pose_a, pose_b)) return invalid_manifold();
  return manifold_of(a, pose_a, b, pose_b, pair_distance(a, pose_a, b, pose_b, request, cache), request);
}

}  // namespace proxima::narrow
