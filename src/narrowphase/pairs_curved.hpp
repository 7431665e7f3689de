#pragma once
/// @file pairs_curved.hpp
/// Declarations of the closed-form pair routines of this group (contract in pair_support.hpp):
/// for each pair (A, B), A not after B in ShapeType order, the three functions pair_intersect,
/// pair_distance, pair_collide and the trait kAnalyticPair<A, B> = true.
///
/// Curved pairs with a closed form in the configurations users build most (stacked barrels,
/// wheels side by side, stacked cones and nested ones): two cylinders whose axes are
/// parallel, two cones on one axis. Other poses go to the generic ladder
/// (generic_distance.hpp), whose answer these routines return unchanged.

#include <proxima/shapes/shape.hpp>

#include "pair_support.hpp"

namespace proxima::narrow {

/// Cylinder-cylinder signed distance: parallel axes (within 4 epsilon of sine), the exact
/// distance of B's centre from the Minkowski difference, itself a cylinder (radius R_A + R_B,
/// half length h_A + h_B), normal from A's axis and the radial direction; other poses the
/// generic ladder. O(1) when parallel.
DistanceResult pair_distance(const Cylinder& a, const Transform& pose_a, const Cylinder& b, const Transform& pose_b,
                             const PairRequest& request, PairCache* cache);
/// Cylinder-cylinder overlap: the touching rule on the parallel closed form, else generic
/// boolean GJK.
bool pair_intersect(const Cylinder& a, const Transform& pose_a, const Cylinder& b, const Transform& pose_b,
                    const PairRequest& request, PairCache* cache);
/// Cylinder-cylinder manifold: the supporting features along the distance's normal, clipped
/// (two caps face to face give up to four points, two barrels side by side two).
ContactManifold pair_collide(const Cylinder& a, const Transform& pose_a, const Cylinder& b, const Transform& pose_b,
                             const PairRequest& request, PairCache* cache);
template <>
inline constexpr bool kAnalyticPair<Cylinder, Cylinder> = true;

/// Cone-cone signed distance: coaxial cones (axes parallel or opposite within 4 epsilon of
/// sine, B's centre on A's axis within the coordinates' rounding), the exact distance of the
/// origin from the difference of the two cones' sections through the axis (two triangles),
/// normal an edge normal of a section or a vertex direction of their difference, in A's
/// xz-plane; other poses the generic ladder. O(1) when coaxial.
DistanceResult pair_distance(const Cone& a, const Transform& pose_a, const Cone& b, const Transform& pose_b,
                             const PairRequest& request, PairCache* cache);
/// Cone-cone overlap: the touching rule on the coaxial closed form, else generic boolean GJK.
bool pair_intersect(const Cone& a, const Transform& pose_a, const Cone& b, const Transform& pose_b,
                    const PairRequest& request, PairCache* cache);
/// Cone-cone manifold: the supporting features along the distance's normal, clipped (a base
/// on a base gives up to four points).
ContactManifold pair_collide(const Cone& a, const Transform& pose_a, const Cone& b, const Transform& pose_b,
                             const PairRequest& request, PairCache* cache);
template <>
inline constexpr bool kAnalyticPair<Cone, Cone> = true;

}  // namespace proxima::narrow
