#pragma once
/// @file core_pair.hpp
/// Internal: two cores expressed in A's local frame (B's vertices and normals moved by the
/// relative pose), the frame every 2D pair algorithm works in so that large world
/// coordinates cancel once, the separating-axis helpers on such a pair, the closest points
/// of two segments, and the cores' signed distance before it goes to the world.

#include <proxima/core/tolerance.hpp>
#include <proxima/d2/contact.hpp>
#include <proxima/d2/convex_shapes.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace proxima::d2::detail {

/// True when both poses are finite (the queries answer "invalid input" otherwise).
inline bool valid_poses(const Pose& pose_a, const Pose& pose_b) {
  return is_finite(pose_a.position) && is_finite(pose_b.position) &&
         std::isfinite(pose_a.rotation.c + pose_a.rotation.s) && std::isfinite(pose_b.rotation.c + pose_b.rotation.s);
}

/// Core B placed in A's frame.
struct CorePair {
  const ConvexCore* a = nullptr;
  ConvexCore b;         ///< B's vertices in A's frame, and its normals once completed
  Rotation rotation{};  ///< B's frame to A's
  /// Largest coordinate magnitude of both cores in A's frame plus the radii: the scale of
  /// the pair's tolerances (set by complete_core_pair).
  Real scale = Real(1);
};

/// Moves B's vertices into A's frame (complete_core_pair adds the normals and the scale, so
/// that a pair found apart by A's axes alone need not pay for them).
inline CorePair place_core_b(const ConvexCore& a, const Pose& pose_a, const ConvexCore& b, const Pose& pose_b) {
  CorePair pair;
  pair.a = &a;
  const Pose rel = relative(pose_a, pose_b);
  pair.rotation = rel.rotation;
  pair.b.count = b.count;
  pair.b.radius = b.radius;
  for (int i = 0; i < b.count; ++i) pair.b.vertices[i] = rel.apply(b.vertices[i]);
  return pair;
}

/// Rotates B's edge normals into A's frame (a 1-vertex core has none: its normals are unset
/// and never read) and measures the pair's scale.
inline void complete_core_pair(CorePair& pair, const ConvexCore& b) {
  for (int i = 0; b.count >= 2 && i < b.count; ++i) pair.b.normals[i] = pair.rotation.apply(b.normals[i]);
  Real scale = pair.a->radius + b.radius;
  for (int i = 0; i < pair.a->count; ++i) scale = std::max(scale, max_abs_component(pair.a->vertices[i]));
  for (int i = 0; i < b.count; ++i) scale = std::max(scale, max_abs_component(pair.b.vertices[i]));
  pair.scale = std::max(scale, Real(1e-30));
}

/// Moves B's vertices and edge normals into A's frame, with the pair's scale.
inline CorePair make_core_pair(const ConvexCore& a, const Pose& pose_a, const ConvexCore& b, const Pose& pose_b) {
  CorePair pair = place_core_b(a, pose_a, b, pose_b);
  complete_core_pair(pair, b);
  return pair;
}

/// The separating axis of largest separation among `ref`'s edge normals: separation of edge
/// i = min over `other`'s vertices v of n_i . v, less n_i . ref_i. Needs ref.count >= 2.
struct AxisSeparation {
  int edge = -1;  ///< edge of `ref`
  Real separation = -std::numeric_limits<Real>::infinity();
};

/// The axis of largest separation (above); with `stop`, the first edge whose separation
/// exceeds it instead (the cores are then apart by more than `stop`).
inline AxisSeparation max_edge_separation(const ConvexCore& ref, const ConvexCore& other,
                                          Real stop = std::numeric_limits<Real>::infinity()) {
  AxisSeparation best;
  for (int i = 0; i < ref.count && !(best.separation > stop); ++i) {
    const Vec2 n = ref.normals[i];
    Real s = glm::dot(n, other.vertices[0]);
    for (int j = 1; j < other.count; ++j) s = std::min(s, glm::dot(n, other.vertices[j]));
    s -= glm::dot(n, ref.vertices[i]);
    if (s > best.separation) best = {i, s};
  }
  return best;
}

/// The tolerance of a pair at `scale`: a few ulps of the coordinates.
inline Real pair_tolerance(Real scale) { return linear_tolerance(scale); }

/// Closest points of segments (p1, q1) and (p2, q2) (Ericson §5.1.9): parameters s, t along
/// them (the second segment must not be a point). Defined in core_manifold.cpp.
void closest_segment_parameters(const Vec2& p1, const Vec2& q1, const Vec2& p2, const Vec2& q2, Real& s, Real& t);

/// Signed distance of two cores before the radii, in A's frame or B's (core_distance.cpp).
struct LocalDistance {
  Real distance = Real(0);              ///< of the cores: > 0 apart, <= 0 overlapping
  Vec2 normal{Real(1), Real(0)};        ///< unit, A to B
  Vec2 point_a{Real(0)};                ///< witness on A's core
  Vec2 point_b{Real(0)};                ///< witness on B's core
  PairMethod method = PairMethod::Gjk;  ///< Gjk: the cores are apart; Sat: they overlap
  bool in_b_frame = false;              ///< the vectors are in B's frame (else A's)
  Real scale = Real(1);                 ///< the pair's scale in that frame (CorePair::scale)
};

/// The signed distance of cores a and b before the radii (core_distance.cpp's steps 1-3).
/// A 1-vertex core found apart from the other by more than `stop` may get only that lower
/// bound of the distance (witnesses unset).
LocalDistance local_core_distance(const ConvexCore& a, const Pose& pose_a, const ConvexCore& b, const Pose& pose_b,
                                  Real stop = std::numeric_limits<Real>::infinity());

}  // namespace proxima::d2::detail
