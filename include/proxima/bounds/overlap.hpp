#pragma once
/// @file overlap.hpp
/// Overlap tests between every pair of bounding volumes: Aabb, BoundingSphere, Obb,
/// BoundingCapsule, Kdop<K> (same K) and ConvexHull, all given in one common frame.
///
/// All volumes are closed: touching counts as overlapping. Every test is exact, with
/// touching decided within a tolerance of about 16 ulps (of Real) of the coordinates'
/// magnitude (exactly in Real arithmetic for the sphere and box closed forms): no test is
/// conservative.
///   - closed forms: Aabb-Aabb, sphere-sphere, sphere-Aabb, sphere-Obb (closest point),
///     Obb-Obb and Obb-Aabb (15-axis separating-axis test, Gottschalk; Ericson 4.4.1,
///     with an epsilon on |R| for parallel edges), Kdop-Kdop and Kdop-Aabb (the slabs'
///     intersection is itself a k-DOP: empty or not, by vertex enumeration);
///   - every other pair: GJK distance between the volumes' cores (point sets: box
///     corners, k-DOP or hull vertices, a capsule's segment, a sphere's centre) compared
///     with the sum of their radii (Gilbert, Johnson, Keerthi 1988; van den Bergen 1999).
/// Arguments may come in either order.

#include <proxima/bounds/bounding_capsule.hpp>
#include <proxima/bounds/bounding_sphere.hpp>
#include <proxima/bounds/kdop.hpp>
#include <proxima/bounds/obb.hpp>
#include <proxima/geometry/aabb.hpp>
#include <proxima/shapes/convex_hull.hpp>

namespace proxima {

/// Two boxes share a point.
inline bool overlaps(const Aabb& a, const Aabb& b) { return a.overlaps(b); }
/// Box and sphere share a point (squared distance from the centre to the box, Arvo).
bool overlaps(const Aabb& a, const BoundingSphere& b);
/// Box and oriented box share a point (SAT, 15 axes).
bool overlaps(const Aabb& a, const Obb& b);
/// Box and capsule share a point (GJK: segment vs box).
bool overlaps(const Aabb& a, const BoundingCapsule& b);
/// Box and k-DOP share a point (the box narrows the k-DOP's axis slabs; non-empty?).
template <int K>
bool overlaps(const Aabb& a, const Kdop<K>& b);
/// Box and hull share a point (GJK).
bool overlaps(const Aabb& a, const ConvexHull& b);

/// Two spheres share a point.
bool overlaps(const BoundingSphere& a, const BoundingSphere& b);
/// Sphere and oriented box share a point (closest point of the box to the centre).
bool overlaps(const BoundingSphere& a, const Obb& b);
/// Sphere and capsule share a point (distance from the centre to the segment).
bool overlaps(const BoundingSphere& a, const BoundingCapsule& b);
/// Sphere and k-DOP share a point (GJK: centre vs k-DOP vertices).
template <int K>
bool overlaps(const BoundingSphere& a, const Kdop<K>& b);
/// Sphere and hull share a point (GJK).
bool overlaps(const BoundingSphere& a, const ConvexHull& b);

/// Two oriented boxes share a point (SAT, 15 axes, robust for parallel edges).
bool overlaps(const Obb& a, const Obb& b);
/// Oriented box and capsule share a point (GJK).
bool overlaps(const Obb& a, const BoundingCapsule& b);
/// Oriented box and k-DOP share a point (GJK on corners and vertices).
template <int K>
bool overlaps(const Obb& a, const Kdop<K>& b);
/// Oriented box and hull share a point (GJK).
bool overlaps(const Obb& a, const ConvexHull& b);

/// Two capsules share a point (GJK on the segments, i.e. segment-segment distance).
bool overlaps(const BoundingCapsule& a, const BoundingCapsule& b);
/// Capsule and k-DOP share a point (GJK).
template <int K>
bool overlaps(const BoundingCapsule& a, const Kdop<K>& b);
/// Capsule and hull share a point (GJK).
bool overlaps(const BoundingCapsule& a, const ConvexHull& b);

/// Two k-DOPs of the same K share a point: their slabs' intersection is non-empty. Exact
/// (unlike the classic per-slab interval test, which is conservative; see
/// kdop_slabs_overlap). O(K^4) worst case, O(K) when a slab separates them.
template <int K>
bool overlaps(const Kdop<K>& a, const Kdop<K>& b);
/// k-DOP and hull share a point (GJK).
template <int K>
bool overlaps(const Kdop<K>& a, const ConvexHull& b);

/// Two hulls share a point (GJK).
bool overlaps(const ConvexHull& a, const ConvexHull& b);

/// The classic k-DOP test: every slab interval overlaps. Conservative by design (true for
/// some disjoint pairs, never false for overlapping ones); O(K), what tree traversals use.
template <int K>
bool kdop_slabs_overlap(const Kdop<K>& a, const Kdop<K>& b) {
  for (int i = 0; i < K / 2; ++i) {
    if (a.min[i] > b.max[i] || b.min[i] > a.max[i]) return false;
  }
  return true;
}

// Mirrored argument orders.
/// Mirror of overlaps(Aabb, BoundingSphere).
inline bool overlaps(const BoundingSphere& a, const Aabb& b) { return overlaps(b, a); }
/// Mirror of overlaps(Aabb, Obb).
inline bool overlaps(const Obb& a, const Aabb& b) { return overlaps(b, a); }
/// Mirror of overlaps(Aabb, BoundingCapsule).
inline bool overlaps(const BoundingCapsule& a, const Aabb& b) { return overlaps(b, a); }
/// Mirror of overlaps(Aabb, Kdop).
template <int K>
bool overlaps(const Kdop<K>& a, const Aabb& b) {
  return overlaps(b, a);
}
/// Mirror of overlaps(Aabb, ConvexHull).
inline bool overlaps(const ConvexHull& a, const Aabb& b) { return overlaps(b, a); }
/// Mirror of overlaps(BoundingSphere, Obb).
inline bool overlaps(const Obb& a, const BoundingSphere& b) { return overlaps(b, a); }
/// Mirror of overlaps(BoundingSphere, BoundingCapsule).
inline bool overlaps(const BoundingCapsule& a, const BoundingSphere& b) { return overlaps(b, a); }
/// Mirror of overlaps(BoundingSphere, Kdop).
template <int K>
bool overlaps(const Kdop<K>& a, const BoundingSphere& b) {
  return overlaps(b, a);
}
/// Mirror of overlaps(BoundingSphere, ConvexHull).
inline bool overlaps(const ConvexHull& a, const BoundingSphere& b) { return overlaps(b, a); }
/// Mirror of overlaps(Obb, BoundingCapsule).
inline bool overlaps(const BoundingCapsule& a, const Obb& b) { return overlaps(b, a); }
/// Mirror of overlaps(Obb, Kdop).
template <int K>
bool overlaps(const Kdop<K>& a, const Obb& b) {
  return overlaps(b, a);
}
/// Mirror of overlaps(Obb, ConvexHull).
inline bool overlaps(const ConvexHull& a, const Obb& b) { return overlaps(b, a); }
/// Mirror of overlaps(BoundingCapsule, Kdop).
template <int K>
bool overlaps(const Kdop<K>& a, const BoundingCapsule& b) {
  return overlaps(b, a);
}
/// Mirror of overlaps(BoundingCapsule, ConvexHull).
inline bool overlaps(const ConvexHull& a, const BoundingCapsule& b) { return overlaps(b, a); }
/// Mirror of overlaps(Kdop, ConvexHull).
template <int K>
bool overlaps(const ConvexHull& a, const Kdop<K>& b) {
  return overlaps(b, a);
}

}  // namespace proxima
