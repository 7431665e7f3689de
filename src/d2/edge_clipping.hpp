#pragma once
/// @file edge_clipping.hpp
/// Internal: the reference/incident edge clipping shared by the convex manifold
/// (core_manifold.cpp) and the chain segments' manifold (chain_manifold.cpp).

#include <proxima/d2/contact.hpp>
#include <proxima/d2/convex_shapes.hpp>

namespace proxima::d2::detail {

/// The manifold of reference core `ref` (its edge `edge`, whose separation from `inc` is
/// `separation`) against incident core `inc` (2+ vertices), both in the reference core's
/// frame, normal from ref to inc, points within `contact_distance`. With `allow_corner`,
/// cores apart by more than `tie` whose nearest features are two vertices get one point
/// along the line between them instead.
Manifold clip_manifold(const ConvexCore& ref, int edge, const ConvexCore& inc, Real separation, Real contact_distance,
                       Real tie, bool allow_corner);

/// The manifold moved from A's frame to the world by A's pose.
Manifold to_world(Manifold m, const Pose& pose_a);

}  // namespace proxima::d2::detail
