#pragma once
/// @file generic_halfspace.hpp
/// The generic routine of a convex shape A against a half-space B = {n . x <= d} (B's frame):
/// intersect, distance and collide from what every convex shape offers, its support mapping,
/// core + radius (convex_shape.hpp) and its supporting feature (supporting_face.hpp).
///
/// Steps (van den Bergen, Collision Detection in Interactive 3D Environments, 4.3: the point
/// of A deepest below the plane is A's support point in the direction -n):
///  1. B's plane in the world (unit normal n, offset relative to B's origin); the tolerance
///     from both positions, the plane offset and A's size (halfspace_size);
///  2. A's core support point x in the direction -n (A's frame), the core radius r subtracted
///     along n: signed distance n . x - d - r, normal -n (A to B), point_a = x - r n, point_b
///     its projection on the plane; intersect applies the touching rule (contact.hpp) to it
///     and stops there;
///  3. collide: no point when the pair is not in contact (in_contact); else the
///     candidate points of A's core (plane_contacts: by default A's supporting feature in the
///     direction -n), each kept when its gap is within contact_distance + tolerance, the 4
///     deepest, reduced to max_contacts by reduce_contacts (manifold_reduction.hpp).
///
/// A shape changes a step by an overload below (the longer ones defined in shape_halfspace.cpp):
/// halfspace_size (its size in the tolerance) and plane_contacts (the manifold of step 3).
/// Cost: one support query for intersect and distance; collide adds one pass over the
/// candidates (O(1), a convex hull O(V)).

#include <proxima/core/math.hpp>
#include <proxima/core/transform.hpp>
#include <proxima/shapes/shape.hpp>

#include <algorithm>
#include <cstdint>
#include <span>

#include "pair_support.hpp"
#include "supporting_face.hpp"

namespace proxima::narrow::detail {

/// A half-space's boundary in the world frame: gap(x) = n . (x - origin) - offset, the signed
/// distance of a world point x above the plane (> 0 outside the solid).
struct WorldPlane {
  Vec3 n{Real(0), Real(0), Real(1)};  ///< unit outward normal, world frame
  Vec3 origin{Real(0)};               ///< the half-space's frame origin, world frame
  Real offset = Real(0);              ///< plane offset relative to origin

  /// Signed height of x above the plane (length units).
  Real gap(const Vec3& x) const { return glm::dot(n, x - origin) - offset; }
};

/// The world plane of half-space h placed at pose.
inline WorldPlane world_plane(const HalfSpace& h, const Transform& pose) {
  return {pose.apply_vector(h.normal()), pose.position, h.offset()};
}

/// Tolerance of a pair with half-space b: both positions, b's offset and the other shape's
/// size (length units).
inline Real halfspace_tolerance(const PairRequest& request, const Transform& pose_a, const Transform& pose_b,
                                const HalfSpace& b, Real size) {
  return resolve_tolerance(request, std::max({max_abs_component(pose_a.position), max_abs_component(pose_b.position),
                                              std::abs(b.offset()), size}));
}

/// Steps 1 and 2 of a query: what collide needs after the distance.
struct PlaneQuery {
  WorldPlane plane;          ///< B's boundary, world frame
  Real tolerance = Real(0);  ///< resolved absolute tolerance (length units)
  DistanceResult distance;   ///< step 2's answer
};

/// A manifold without points, with d's normal, status and method.
inline ContactManifold empty_manifold(const DistanceResult& d) {
  ContactManifold m;
  m.normal = d.normal;
  m.status = d.status;
  m.method = d.method;
  return m;
}

/// Size of A for the tolerance: the largest coordinate of its local box (length units).
template <class S>
Real halfspace_size(const S& a) {
  const Aabb box = a.local_aabb();
  return std::max(max_abs_component(box.min), max_abs_component(box.max));
}

// The same size in closed form, inline (local_aabb is compiled apart); the convex hull keeps a
// measure of its own.
inline Real halfspace_size(const Point& /*a*/) { return Real(0); }
inline Real halfspace_size(const Segment& a) { return std::max(max_abs_component(a.a()), max_abs_component(a.b())); }
inline Real halfspace_size(const Triangle& a) {
  return std::max({max_abs_component(a.a()), max_abs_component(a.b()), max_abs_component(a.c())});
}
inline Real halfspace_size(const Sphere& a) { return a.radius(); }
inline Real halfspace_size(const Capsule& a) { return a.radius() + a.half_length(); }
inline Real halfspace_size(const Box& a) { return max_abs_component(a.half_extents()); }
inline Real halfspace_size(const Cylinder& a) { return std::max(a.radius(), a.half_length()); }
inline Real halfspace_size(const Cone& a) { return std::max(a.radius(), a.half_length()); }
inline Real halfspace_size(const Ellipsoid& a) { return max_abs_component(a.radii()); }
/// Size of a convex hull for the tolerance: its box's largest extent plus its largest
/// coordinates on both sides (length units).
inline Real halfspace_size(const ConvexHull& a) {
  const Aabb box = a.local_aabb();
  return max_abs_component(box.max - box.min) + max_abs_component(box.max) + max_abs_component(box.min);
}

/// The manifold of step 3 from candidate points of A's core (world frame) with their feature
/// indices on A and the core radius r: deepest first, feature ids (Vertex, index, Face, 0);
/// the support point alone when rounding leaves no candidate within the limit.
ContactManifold candidate_manifold(const PlaneQuery& q, std::span<const Vec3> points,
                                   std::span<const std::uint32_t> ids, Real r, const PairRequest& request);

/// Step 3 for any shape: its supporting feature in the direction -n as the candidates.
template <class S>
ContactManifold plane_contacts(const S& a, const Transform& pose_a, const PlaneQuery& q, const PairRequest& request) {
  const SupportingFace f = supporting_face(a, pose_a, -q.plane.n);
  const auto count = static_cast<std::size_t>(f.count);
  return candidate_manifold(q, {f.points.data(), count}, {f.ids.data(), count}, f.radius, request);
}

// Step 3 in closed form, where the supporting feature would give other points or ids, or
// costs more than the answer. The support point alone (its feature the vertex of a point, the
// surface of a sphere or an ellipsoid):
inline ContactManifold plane_contacts(const Point& /*a*/, const Transform& /*pose_a*/, const PlaneQuery& q,
                                      const PairRequest& r) {
  return manifold_from_distance(q.distance, r, make_feature_id(FeatureKind::Vertex, 0, FeatureKind::Face, 0));
}
inline ContactManifold plane_contacts(const Sphere& /*a*/, const Transform& /*pose_a*/, const PlaneQuery& q,
                                      const PairRequest& r) {
  return manifold_from_distance(q.distance, r, make_feature_id(FeatureKind::Surface, 0, FeatureKind::Face, 0));
}
inline ContactManifold plane_contacts(const Ellipsoid& /*a*/, const Transform& /*pose_a*/, const PlaneQuery& q,
                                      const PairRequest& r) {
  return manifold_from_distance(q.distance, r, make_feature_id(FeatureKind::Surface, 0, FeatureKind::Face, 0));
}
// Candidates of their own (shape_halfspace.cpp): the end points without the feature's frame
// (segment), the vertices in their own order (triangle), both core ends even when they
// coincide (capsule), the 8 corners (box), the exact deepest rim points (cylinder, cone), every
// vertex streamed (convex hull).
ContactManifold plane_contacts(const Segment& a, const Transform& pose_a, const PlaneQuery& q, const PairRequest& r);
ContactManifold plane_contacts(const Triangle& a, const Transform& pose_a, const PlaneQuery& q, const PairRequest& r);
ContactManifold plane_contacts(const Capsule& a, const Transform& pose_a, const PlaneQuery& q, const PairRequest& r);
ContactManifold plane_contacts(const Box& a, const Transform& pose_a, const PlaneQuery& q, const PairRequest& r);
ContactManifold plane_contacts(const Cylinder& a, const Transform& pose_a, const PlaneQuery& q, const PairRequest& r);
ContactManifold plane_contacts(const Cone& a, const Transform& pose_a, const PlaneQuery& q, const PairRequest& r);
ContactManifold plane_contacts(const ConvexHull& a, const Transform& pose_a, const PlaneQuery& q, const PairRequest& r);

/// Step 2: the signed distance of A's core support point in the direction -n, with radius r
/// (poses finite).
template <class S>
DistanceResult support_distance(const S& a, const Transform& pose_a, const HalfSpace& b, const Transform& pose_b,
                                Real tolerance) {
  const WorldPlane plane = world_plane(b, pose_b);
  const Real r = a.core_radius();
  const Vec3 x = pose_a.apply(a.core_support(pose_a.inverse_apply_vector(-plane.n)));
  DistanceResult d;
  d.signed_distance = plane.gap(x) - r;
  d.normal = -plane.n;
  d.point_a = x - r * plane.n;
  d.point_b = d.point_a - d.signed_distance * plane.n;
  d.status = status_from_distance(d.signed_distance, tolerance);
  d.method = PairMethod::Analytic;
  d.tolerance = tolerance;
  return d;
}

/// Steps 1 and 2 (poses finite).
template <class S>
PlaneQuery plane_query(const S& a, const Transform& pose_a, const HalfSpace& b, const Transform& pose_b,
                       const PairRequest& request) {
  const Real tolerance = halfspace_tolerance(request, pose_a, pose_b, b, halfspace_size(a));
  return {world_plane(b, pose_b), tolerance, support_distance(a, pose_a, b, pose_b, tolerance)};
}

/// Signed distance of A to the half-space (steps 1, 2); InvalidInput for poses out of range.
template <class S>
DistanceResult halfspace_distance(const S& a, const Transform& pose_a, const HalfSpace& b, const Transform& pose_b,
                                  const PairRequest& request) {
  if (!poses_in_range(pose_a, pose_b)) return invalid_distance();
  return support_distance(a, pose_a, b, pose_b, halfspace_tolerance(request, pose_a, pose_b, b, halfspace_size(a)));
}

/// True when A is in contact with the half-space (step 2 and the touching rule of
/// contact.hpp); false for poses out of range.
template <class S>
bool halfspace_intersect(const S& a, const Transform& pose_a, const HalfSpace& b, const Transform& pose_b,
                         const PairRequest& request) {
  if (!poses_in_range(pose_a, pose_b)) return false;
  return in_contact(halfspace_distance(a, pose_a, b, pose_b, request), request);
}

/// Contact manifold of A and the half-space (steps 1 to 3); InvalidInput for poses out of range.
template <class S>
ContactManifold halfspace_collide(const S& a, const Transform& pose_a, const HalfSpace& b, const Transform& pose_b,
                                  const PairRequest& request) {
  if (!poses_in_range(pose_a, pose_b)) return invalid_manifold();
  const PlaneQuery q = plane_query(a, pose_a, b, pose_b, request);
  if (!in_contact(q.distance, request) || request.max_contacts < 1) {
    return empty_manifold(q.distance);
  }
  return plane_contacts(a, pose_a, q, request);
}

}  // namespace proxima::narrow::detail
