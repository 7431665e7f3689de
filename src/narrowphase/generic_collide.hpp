#pragma once
/// @file generic_collide.hpp
/// The contact manifold of a pair without a closed-form routine: the pair's distance query,
/// then (for now) the single contact it finds.

#include "pair_support.hpp"

namespace proxima::narrow {

/// Manifold of any convex pair from its distance query (one point).
template <class A, class B>
ContactManifold pair_collide(const A& a, const Transform& pose_a, const B& b, const Transform& pose_b,
                             const PairRequest& request, PairCache* cache) {
  if (!finite_poses(pose_a, pose_b)) return invalid_manifold();
  return manifold_from_distance(pair_distance(a, pose_a, b, pose_b, request, cache), request);
}

}  // namespace proxima::narrow
