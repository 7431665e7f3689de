#pragma once
/// @file pairs_rounded.hpp
/// Declarations of the closed-form pair routines of this group (contract in pair_support.hpp):
/// for each pair (A, B), A not after B in ShapeType order, the three functions pair_intersect,
/// pair_distance, pair_collide and the trait kAnalyticPair<A, B> = true.
///
/// Rounded pairs: a sphere (point core) or capsule (segment core) against a sphere, capsule,
/// box or triangle, a sphere against a cylinder, a cone or an ellipsoid, and a segment against a segment (a capsule
/// core without radius). Each routine finds the closest points of the cores with the geometry/closest_points.hpp
/// routines and adds the radii; when the cores touch or overlap, the penetration direction comes from the pair's closed
/// form (deepest box face, separating-axis test of segment against box or triangle, common normal of crossing
/// segments). All O(1), no allocation.
///
/// Degenerate configurations get a deterministic normal, never NaN. Point and segment cores
/// closer than their coordinates' rounding (offset_noise, rounded_common.hpp: 16 ulps of the
/// pair's scale) count as touching, because the direction between their closest points is
/// then noise; farther, the offset's length is the core distance, however far inside the
/// tolerance (which sets the status only):
///  - sphere-sphere with coincident centres: A's local +x axis (in world);
///  - a sphere centre on a capsule's core: the capsule's local +x axis (perpendicular to it);
///  - crossing capsule cores or segments: the common normal of the axes, turned towards B's
///    centre; for parallel or zero-length cores, A's local +x axis with its component along
///    A's core removed (B's core when A has no length; a perpendicular of the core when +x
///    lies along it), turned towards B's centre: always orthogonal to the cores;
///  - a sphere centre on a triangle: the triangle's normal (b - a) x (c - a), turned to the
///    centre's side;
///  - a capsule core touching a box or a triangle: the separating-axis test's axis.
/// Two-point manifolds are used only when their deepest point reproduces the distance query's
/// depth (within tolerance); otherwise the manifold is the exact single closest pair.
/// intersect(...) is true iff in_contact(distance(...), request) (the touching rule of
/// contact.hpp); the sphere, capsule and segment pairs answer it from the squared core
/// distance away from the threshold and from the distance itself near it.

#include <proxima/shapes/shape.hpp>

#include "pair_support.hpp"

namespace proxima::narrow {

// Two segments (no interior): segment-segment closest points, the capsule pair with radii 0.
// Touching or crossing segments get distance 0 along a normal orthogonal to both (the common
// normal, or for parallel segments a perpendicular from A's local +x axis). Manifold: two
// points (the ends of the overlap) for parallel overlapping segments, else one.
PROXIMA_ANALYTIC_PAIR(Segment, Segment)
// Triangle (two-sided, no thickness) against a sphere: closest point of the triangle to the
// centre. Manifold: one point.
PROXIMA_ANALYTIC_PAIR(Triangle, Sphere)
// Triangle against a capsule: segment-triangle closest points; segment-triangle SAT (triangle
// normal, edge x axis, in-plane edge normals) when the core touches the triangle. Manifold: two
// points (the core clipped to the triangle's prism) when the capsule lies along the triangle.
PROXIMA_ANALYTIC_PAIR(Triangle, Capsule)
// Two spheres: centre to centre. Manifold: one point.
PROXIMA_ANALYTIC_PAIR(Sphere, Sphere)
// Sphere against capsule: closest point of the core segment to the centre. Manifold: one point.
PROXIMA_ANALYTIC_PAIR(Sphere, Capsule)
// Two capsules: segment-segment closest points. Manifold: two points (the ends of the overlap
// of the cores) when the axes are parallel and overlap, else one.
PROXIMA_ANALYTIC_PAIR(Capsule, Capsule)
// Sphere against box: closest point of the box to the centre; centre inside: the deepest
// (nearest) face. Manifold: one point.
PROXIMA_ANALYTIC_PAIR(Sphere, Box)
// Sphere against cylinder: closest point of the cylinder's meridian rectangle to the centre;
// normals from the axis and the centre's radial direction. Manifold: one point.
PROXIMA_ANALYTIC_PAIR(Sphere, Cylinder)
// Sphere against cone: closest point of the cone's meridian triangle to the centre; normals
// from the base and slant lines. Manifold: one point.
PROXIMA_ANALYTIC_PAIR(Sphere, Cone)
// Sphere against ellipsoid: the ellipsoid's closest point to the centre (Eberly's robust 1-D
// root finder); the normal is the ellipsoid's gradient there. Manifold: one point.
PROXIMA_ANALYTIC_PAIR(Sphere, Ellipsoid)
// Capsule against box: exact segment-box closest points (piecewise quadratic minimisation);
// segment-box SAT (3 face axes, 3 edge axes) when the core touches the box. Manifold: two
// points (the core clipped to the face) when the contact normal is a face normal and both
// ends of the clipped core lie within the contact distance.
PROXIMA_ANALYTIC_PAIR(Capsule, Box)

}  // namespace proxima::narrow
