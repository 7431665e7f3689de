#pragma once
/// @file pairs_curved.hpp
/// Declarations of the closed-form pair routines of this group (contract in pair_support.hpp):
/// for each pair (A, B), A not after B in ShapeType order, the three functions pair_intersect,
/// pair_distance, pair_collide and the trait kAnalyticPair<A, B> = true.
///
/// Curved pairs with a closed form in the configurations users build most (stacked barrels,
/// wheels side by side): two cylinders whose axes are parallel. Other poses go to the generic
/// ladder (generic_distance.hpp), whose answer these routines return unchanged.

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

}  // namespace proxima::narrow
