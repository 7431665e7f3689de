#pragma once
/// @file supporting_face_manifold.hpp
/// The contact manifold of a convex pair from its distance result (steps 2 to 4 of
/// generic_collide.hpp): the supporting features of A along the normal and of B against
/// it, clipped when they are aligned with the normal, else the one-point manifold.

#include "face_clipping.hpp"
#include "pair_support.hpp"
#include "supporting_face.hpp"

namespace proxima::narrow {

/// Manifold of A and B (poses in the world frame) from their distance result `d` (normal
/// unit, A to B): clipped supporting faces when aligned with the normal, else one point.
/// O(n m) for features of n and m points (O(F) more for a hull's face search).
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
  if (clipped_manifold(fa, fb, d.normal, request_within_reach(request, d.tolerance), clipped, &witness)) {
    return clipped;
  }
  return m;
}

}  // namespace proxima::narrow
