#pragma once
/// @file pairs_polyhedral.hpp
/// Declarations of the closed-form pair routines of this group (contract in pair_support.hpp):
/// for each pair (A, B), A not after B in ShapeType order, the three functions pair_intersect,
/// pair_distance, pair_collide and the trait kAnalyticPair<A, B> = true.
///
/// The polyhedral pairs (box-box, triangle-box, triangle-triangle) decide overlap with the
/// separating-axis test over face normals and edge-pair cross products, whose minimum overlap
/// is the exact penetration depth of two polytopes; separated pairs get exact distances from
/// their closest features; manifolds come from clipping the incident face against the
/// reference face (face_clipping.hpp) or from the closest points of two edges. Triangles are
/// two-sided and have no thickness.

#include <proxima/shapes/shape.hpp>

#include "pair_support.hpp"

namespace proxima::narrow {

/// Box-box overlap (within request.contact_distance): SAT over 15 axes with early exit;
/// `cache->sat_feature` holds the last separating axis, tried first. O(1).
bool pair_intersect(const Box& a, const Transform& pose_a, const Box& b, const Transform& pose_b,
                    const PairRequest& request, PairCache* cache);
/// Box-box signed distance: exact penetration depth by SAT over the 15 axes; when
/// separated, the exact distance from the closest vertex-face and edge-edge feature pairs.
DistanceResult pair_distance(const Box& a, const Transform& pose_a, const Box& b, const Transform& pose_b,
                             const PairRequest& request, PairCache* cache);
/// Box-box manifold: SAT axis (face axes preferred over nearly as shallow edge axes), then
/// reference-face / incident-face clipping or the closest points of two edges; up to 4
/// points reduced by area, stable feature ids.
ContactManifold pair_collide(const Box& a, const Transform& pose_a, const Box& b, const Transform& pose_b,
                             const PairRequest& request, PairCache* cache);
template <>
inline constexpr bool kAnalyticPair<Box, Box> = true;

/// Triangle-box overlap (SAT over 13 axes: the triangle normal, 3 box faces, 9 edge pairs).
bool pair_intersect(const Triangle& a, const Transform& pose_a, const Box& b, const Transform& pose_b,
                    const PairRequest& request, PairCache* cache);
/// Triangle-box signed distance: SAT depth when they overlap, else the exact distance of
/// the closest features (box edges against the triangle, triangle vertices against the box).
DistanceResult pair_distance(const Triangle& a, const Transform& pose_a, const Box& b, const Transform& pose_b,
                             const PairRequest& request, PairCache* cache);
/// Triangle-box manifold by SAT and clipping (up to 4 points).
/// True when the 13 separating axes of triangle a and box b already separate them by more
/// than `beyond` (a lower bound of their distance): no contact within `beyond`. O(1).
bool triangle_box_separated_beyond(const Triangle& a, const Transform& pose_a, const Box& b, const Transform& pose_b,
                                   Real beyond);
/// Signed distance of box b from triangle a along the unit world direction n: for an
/// overlapping or touching pair, minus the smallest t >= 0 such that b moved by t n no longer
/// overlaps a; for a separated pair, the smallest t >= 0 such that b moved by -t n touches a;
/// +infinity when no such t exists. Exact over the 13 separating axes (the translation
/// interval of small_polytope_sat.hpp). O(1).
Real triangle_box_directional_signed_distance(const Triangle& a, const Transform& pose_a, const Box& b,
                                              const Transform& pose_b, const Vec3& n);
ContactManifold pair_collide(const Triangle& a, const Transform& pose_a, const Box& b, const Transform& pose_b,
                             const PairRequest& request, PairCache* cache);
template <>
inline constexpr bool kAnalyticPair<Triangle, Box> = true;

/// Triangle-triangle overlap (geometry::triangles_intersect, or distance within the contact
/// distance).
bool pair_intersect(const Triangle& a, const Transform& pose_a, const Triangle& b, const Transform& pose_b,
                    const PairRequest& request, PairCache* cache);
/// Triangle-triangle signed distance: SAT depth (normals, 9 edge pairs, in-plane edge normals
/// for coplanar pairs) when they overlap, else the exact closest points.
DistanceResult pair_distance(const Triangle& a, const Transform& pose_a, const Triangle& b, const Transform& pose_b,
                             const PairRequest& request, PairCache* cache);
/// Triangle-triangle manifold by SAT and clipping (up to 4 points).
ContactManifold pair_collide(const Triangle& a, const Transform& pose_a, const Triangle& b, const Transform& pose_b,
                             const PairRequest& request, PairCache* cache);
template <>
inline constexpr bool kAnalyticPair<Triangle, Triangle> = true;

}  // namespace proxima::narrow
