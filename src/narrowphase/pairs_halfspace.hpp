#pragma once
/// @file pairs_halfspace.hpp
/// Declarations of the closed-form pair routines of this group (contract in pair_support.hpp):
/// for each pair (A, B), A not after B in ShapeType order, the three functions pair_intersect,
/// pair_distance, pair_collide and the trait kAnalyticPair<A, B> = true.
///
/// Every convex shape against a half-space (B = {n . x <= d} in B's frame), all through one
/// generic routine (generic_halfspace.hpp, instantiated in shape_halfspace.cpp with the
/// closed-form candidates below); half-space against half-space in halfspace_halfspace.cpp.
/// The signed distance is the plane offset of A's support point in the direction -n (core
/// support plus radius): n_w . x - d_w. The normal (A to B) is -n_w, point_a the support
/// point, point_b its projection on the plane. Manifolds (points sharing the normal -n_w, each
/// with its own depth; a point is kept when its gap is at most contact_distance + tolerance,
/// once the deepest is within contact_distance):
///  - point, sphere, ellipsoid: one point;
///  - segment: its end points; triangle: its vertices; capsule: its two core ends + radius;
///  - box: the up to 4 deepest of its 8 vertices (then reduced to max_contacts);
///  - cylinder: the deepest rim point of each cap, and on the deeper cap the rim points at
///    90, 180 and 270 degrees from it (a cylinder on its side gives 2, standing on a cap 4);
///  - cone: the apex and the same four rim points of the base;
///  - convex hull: its vertices within the contact distance, reduced to max_contacts by
///    select_contacts (area-maximising).
/// Feature ids: (Vertex, index on A, Face, 0), the index being the vertex number (box: bit i
/// set for the + side on axis i; cylinder: 4 * cap + rim point; cone: 0 apex, 1..4 rim);
/// sphere and ellipsoid (Surface, 0, Face, 0).
///
/// Half-space against half-space (both unbounded), documented finite answers:
///  - anti-parallel normals (n_a . n_b <= -(1 - kRelativeTolerance)): the signed gap between
///    the planes, -(d_a + d_b) in world offsets, normal n_a; the witnesses are A's plane
///    point nearest A's origin and that point moved by the signed gap along n_a (on B's plane);
///  - otherwise the solids always overlap without bound: status Penetrating, signed distance
///    -kHalfSpacePairDepth, normal n_a, point_a on A's plane, point_b = point_a +
///    signed_distance * n_a (inside both solids, not on B's surface).

#include <proxima/shapes/shape.hpp>

#include "pair_support.hpp"

namespace proxima::narrow {

/// Depth reported for two half-spaces whose normals are not anti-parallel (their overlap is
/// unbounded): HalfSpace::kSupportExtent (1e5 in float, 1e10 in double), length units.
inline constexpr Real kHalfSpacePairDepth = HalfSpace::kSupportExtent;

PROXIMA_ANALYTIC_PAIR(Point, HalfSpace)
PROXIMA_ANALYTIC_PAIR(Segment, HalfSpace)
PROXIMA_ANALYTIC_PAIR(Triangle, HalfSpace)
PROXIMA_ANALYTIC_PAIR(Sphere, HalfSpace)
PROXIMA_ANALYTIC_PAIR(Capsule, HalfSpace)
PROXIMA_ANALYTIC_PAIR(Box, HalfSpace)
PROXIMA_ANALYTIC_PAIR(Cylinder, HalfSpace)
PROXIMA_ANALYTIC_PAIR(Cone, HalfSpace)
PROXIMA_ANALYTIC_PAIR(Ellipsoid, HalfSpace)
PROXIMA_ANALYTIC_PAIR(ConvexHull, HalfSpace)
PROXIMA_ANALYTIC_PAIR(HalfSpace, HalfSpace)

}  // namespace proxima::narrow
