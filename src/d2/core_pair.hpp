#pragma once
/// @file core_pair.hpp
/// Internal: two cores expressed in A's local frame (B's vertices and normals moved by the
/// relative pose), the frame every 2D pair algorithm works in so that large world
/// coordinates cancel once, and the separating-axis helpers on such a pair.

#include <proxima/core/tolerance.hpp>
#include <proxima/d2/convex_shapes.hpp>

#include <cmath>
#include <limits>

namespace proxima::d2::detail {

/// Core B placed in A's frame.
struct CorePair {
  const ConvexCore* a = nullptr;
  ConvexCore b;         ///< B's vertices in A's frame, and its normals once moved (move_normals)
  Rotation rotation{};  ///< B's frame to A's
  /// Largest coordinate magnitude of both cores in A's frame plus the radii: the scale of
  /// the pair's tolerances.
  Real scale = Real(1);
};

/// Rotates B's edge normals into A's frame (a 1-vertex core has none: its normals are
/// unset and must not be read).
inline void move_normals(CorePair& pair, const ConvexCore& b) {
  for (int i = 0; b.count >= 2 && i < b.count; ++i) pair.b.normals[i] = pair.rotation.apply(b.normals[i]);
}

/// Moves B's vertices into A's frame, and its normals with `with_normals` (the
/// separating-axis code needs them, GJK does not).
inline CorePair make_core_pair(const ConvexCore& a, const Pose& pose_a, const ConvexCore& b, const Pose& pose_b,
                               bool with_normals = true) {
  CorePair pair;
  pair.a = &a;
  const Pose rel = relative(pose_a, pose_b);
  pair.rotation = rel.rotation;
  pair.b.count = b.count;
  pair.b.radius = b.radius;
  Real scale = a.radius + b.radius;
  for (int i = 0; i < a.count; ++i) scale = std::max(scale, max_abs_component(a.vertices[i]));
  for (int i = 0; i < b.count; ++i) {
    pair.b.vertices[i] = rel.apply(b.vertices[i]);
    scale = std::max(scale, max_abs_component(pair.b.vertices[i]));
  }
  if (with_normals) move_normals(pair, b);
  pair.scale = std::max(scale, Real(1e-30));
  return pair;
}

/// The separating axis of largest separation among `ref`'s edge normals: separation of edge
/// i = min over `other`'s vertices of n_i . (v - ref_i). Needs ref.count >= 2.
struct AxisSeparation {
  int edge = -1;  ///< edge of `ref`
  Real separation = -std::numeric_limits<Real>::infinity();
};

inline AxisSeparation max_edge_separation(const ConvexCore& ref, const ConvexCore& other) {
  AxisSeparation best;
  for (int i = 0; i < ref.count; ++i) {
    const Vec2 n = ref.normals[i];
    const Vec2 v = ref.vertices[i];
    Real s = std::numeric_limits<Real>::infinity();
    for (int j = 0; j < other.count; ++j) s = std::min(s, glm::dot(n, other.vertices[j] - v));
    if (s > best.separation) best = {i, s};
  }
  return best;
}

/// The tolerance of a pair at `scale`: a few ulps of the coordinates.
inline Real pair_tolerance(Real scale) { return linear_tolerance(scale); }

}  // namespace proxima::d2::detail
