#pragma once
/// @file narrowphase.hpp
/// The 2D queries on Shapes, for every pair of kinds: distance, intersect, collide (contact
/// manifolds), ray cast, containment, closest point. Convex pairs go to the core algorithms
/// (convex_queries.hpp); a chain side is taken segment by segment (a rectangle test skips
/// segments out of reach), one-sided for contacts and rays, two-sided for distance.
/// Conventions of contact.hpp; no call allocates except collide_all's output.

#include <proxima/d2/contact.hpp>
#include <proxima/d2/convex_queries.hpp>
#include <proxima/d2/shape.hpp>

#include <optional>
#include <vector>

namespace proxima::d2 {

/// Signed distance between two shapes with witnesses (a chain: its nearest segment, two-sided,
/// reported in part_a / part_b). O(1) for convex pairs, O(segments) with a chain side.
DistanceResult distance(const Shape& a, const Pose& pose_a, const Shape& b, const Pose& pose_b);

/// True when the shapes overlap or touch (signed distance within the pair's tolerance).
bool intersect(const Shape& a, const Pose& pose_a, const Shape& b, const Pose& pose_b);

/// The contact manifold (contact_distance >= 0: speculative points whose gap is at most it).
/// With a chain side, the manifold of the chain segment with the deepest point (use
/// collide_all for every touching segment).
Manifold collide(const Shape& a, const Pose& pose_a, const Shape& b, const Pose& pose_b,
                 Real contact_distance = Real(0));

/// Appends to `out` one manifold per touching part pair: one for a convex pair, one per
/// touching chain segment otherwise (in segment order). Returns the number appended.
int collide_all(const Shape& a, const Pose& pose_a, const Shape& b, const Pose& pose_b, Real contact_distance,
                std::vector<Manifold>& out);

/// First hit of `ray` (world frame) within [0, max_t]; one-sided for chains (see chain.hpp).
std::optional<RayHit> raycast(const Shape& shape, const Pose& pose, const Ray& ray, Real max_t);

/// True when `point` (world frame) is inside or on a convex shape; chains enclose nothing
/// (false).
bool contains(const Shape& shape, const Pose& pose, const Vec2& point);

/// The nearest boundary point of the shape to `point` (world frame), signed distance < 0
/// inside a convex shape; a chain's nearest segment (two-sided, distance >= 0).
SurfacePoint closest_point(const Shape& shape, const Pose& pose, const Vec2& point);

}  // namespace proxima::d2
