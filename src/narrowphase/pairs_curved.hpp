#pragma once
/// @file pairs_curved.hpp
/// Declarations of the closed-form pair routines of this group (contract in pair_support.hpp):
/// for each pair (A, B), A not after B in ShapeType order, the three functions pair_intersect,
/// pair_distance, pair_collide and the trait kAnalyticPair<A, B> = true.
///
/// Curved pairs with a closed form in the configurations users build most (stacked barrels,
/// wheels side by side, stacked cones and nested ones): two cylinders whose axes are
/// parallel, two cones on one axis. Other poses go to the generic ladder
/// (generic_distance.hpp), whose answer these routines return unchanged (intersect: generic
/// boolean GJK). Where the closed form applies, intersect is the touching rule (contact.hpp)
/// on its distance; manifolds are the supporting features along the distance's normal,
/// clipped (supporting_face_manifold.hpp). The three entry points of each pair come from
/// closed_form_or_ladder.hpp.

#include <proxima/shapes/shape.hpp>

#include "pair_support.hpp"

namespace proxima::narrow {

// Two cylinders with parallel axes (within 4 epsilon of sine): the exact distance of B's
// centre from the Minkowski difference, itself a cylinder (radius R_A + R_B, half length
// h_A + h_B), normal from A's axis and the radial direction. O(1) when parallel. Manifold:
// two caps face to face give up to four points, two barrels side by side two.
PROXIMA_ANALYTIC_PAIR(Cylinder, Cylinder)
// Two coaxial cones (axes parallel or opposite within 4 epsilon of sine, B's centre on A's
// axis within the coordinates' rounding): the exact distance of the origin from the
// difference of the two cones' sections through the axis (two triangles), normal an edge
// normal of a section or a vertex direction of their difference, in A's xz-plane. O(1) when
// coaxial. Manifold: a base on a base gives up to four points.
PROXIMA_ANALYTIC_PAIR(Cone, Cone)

}  // namespace proxima::narrow
