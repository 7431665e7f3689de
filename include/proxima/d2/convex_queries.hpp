#pragma once
/// @file convex_queries.hpp
/// The 2D narrow phase on cores (ConvexCore: a convex polygon of 1–16 vertices plus a
/// radius) and on chain segments. Shape-level calls (narrowphase.hpp) reduce to these.
///
/// Every function takes both operands in their local frames plus their poses and returns a
/// value; none allocates, throws or fails: a pose that is not finite gives "separated,
/// +infinity" (status InvalidInput) and no contact.

#include <proxima/d2/chain.hpp>
#include <proxima/d2/contact.hpp>
#include <proxima/d2/convex_shapes.hpp>

#include <optional>

namespace proxima::d2 {

/// Signed distance between two rounded cores with witness points (contact.hpp convention),
/// in closed form: disjoint cores get their closest points (method Gjk, the cores-apart
/// case), radii subtracted; overlapping cores get the exact penetration of the cores from
/// the separating-axis test over both cores' edge normals (method Sat), radii added. A
/// 1-vertex core takes one pass over the other core's edges; two coincident 1-vertex cores
/// get A's local x axis.
DistanceResult core_distance(const ConvexCore& a, const Pose& pose_a, const ConvexCore& b, const Pose& pose_b);

/// True when the rounded cores overlap or touch: core_distance's signed distance <= the
/// pair's tolerance (a few ulps of the pair's scale).
bool core_intersect(const ConvexCore& a, const Pose& pose_a, const ConvexCore& b, const Pose& pose_b);

/// Contact manifold of two rounded cores: up to two points with one normal, including
/// speculative points whose gap is at most `contact_distance` (>= 0, length units).
/// Cores of 2+ vertices: the separating axis with the largest separation over both cores'
/// edge normals picks the reference edge (A's unless B's separates more by a tie margin of
/// 1e-4 of the pair's scale, so a depth may exceed the exact penetration by that margin),
/// the most anti-parallel edge of the other core is the incident edge, and the incident edge
/// clipped by the reference edge's side lines gives the points; cores apart whose nearest
/// features are two vertices get one point along the line between those vertices. A 1-vertex core
/// (point, circle) gets one point from core_distance.
Manifold core_manifold(const ConvexCore& a, const Pose& pose_a, const ConvexCore& b, const Pose& pose_b,
                       Real contact_distance = Real(0));

/// Contact manifold of a one-sided chain segment (A) with a rounded core (B), the chain's
/// smooth-seam rule applied (chain.hpp): B touches only from the segment's right side (its
/// centre of vertices must be in front of the segment line), and the normal is one the
/// segment may produce — its own normal, or at an end with a convex corner a normal between
/// its own and the neighbour's; at a concave corner, or where the neighbour segment is
/// nearer, only its own normal or nothing. So a body sliding over collinear segments
/// always gets the segments' normal.
Manifold chain_segment_manifold(const ChainSegment& a, const Pose& pose_a, const ConvexCore& b, const Pose& pose_b,
                                Real contact_distance = Real(0));

/// First hit of `ray` (world frame) with the rounded core within [0, max_t]; an origin
/// inside gives t = 0 and normal -direction/|direction|. Nothing for a zero, non-finite
/// direction or a negative max_t. A 1-vertex core of radius 0 (a point) is hit only by a
/// ray through it.
std::optional<RayHit> core_raycast(const ConvexCore& core, const Pose& pose, const Ray& ray, Real max_t);

/// First hit of `ray` (world frame) with a one-sided chain segment: only a ray coming from
/// the segment's right side (against its normal) hits it. Nothing otherwise.
std::optional<RayHit> chain_segment_raycast(const ChainSegment& segment, const Pose& pose, const Ray& ray, Real max_t);

/// True when `point` (world frame) is inside or on the rounded core.
bool core_contains(const ConvexCore& core, const Pose& pose, const Vec2& point);

/// The nearest point of the rounded core's boundary to `point` (world frame), with the
/// signed distance (< 0 inside) and the outward unit normal there.
struct SurfacePoint {
  Vec2 point{Real(0)};             ///< on the boundary, world frame
  Vec2 normal{Real(1), Real(0)};   ///< unit outward normal at `point`
  Real signed_distance = Real(0);  ///< from `point` to the boundary: > 0 outside
};
/// See SurfacePoint.
SurfacePoint core_closest_point(const ConvexCore& core, const Pose& pose, const Vec2& point);

}  // namespace proxima::d2
