#pragma once
/// @file volume_queries.hpp
/// Point, ray, segment and plane queries on every bounding volume (Aabb, BoundingSphere,
/// Obb, BoundingCapsule, Kdop<K>, ConvexHull), all in the volume's frame.
///
/// Point: the volumes' own `contains` members (closed volumes).
/// Ray: ray_entry gives the entry parameter of a ray into the solid volume, following
/// geometry/ray.hpp: points origin + t direction, 0 <= t <= max_t, t in units of
/// |direction|, origin inside -> 0, zero direction hits only when the origin is inside.
/// Segment pq: the ray {p, q - p} with max_t = 1.
/// Plane n . x = d (n any non-zero vector): which side the volume lies on.

#include <proxima/bounds/bounding_capsule.hpp>
#include <proxima/bounds/bounding_sphere.hpp>
#include <proxima/bounds/kdop.hpp>
#include <proxima/bounds/obb.hpp>
#include <proxima/geometry/aabb.hpp>
#include <proxima/geometry/ray.hpp>
#include <proxima/shapes/convex_hull.hpp>

#include <optional>

namespace proxima {

/// Closed interval [lo, hi] of values (projections on an axis).
struct Interval {
  Real lo = Real(0);  ///< smallest value
  Real hi = Real(0);  ///< largest value
};

/// Where a volume lies relative to the plane n . x = d.
enum class PlaneSide {
  Front,      ///< every point has n . x > d
  Back,       ///< every point has n . x < d
  Straddling  ///< the plane touches or cuts the volume
};

/// Range of axis . x over the box (axis any vector; values in units of length * |axis|).
Interval projection_interval(const Aabb& volume, const Vec3& axis);
/// Range of axis . x over the sphere.
Interval projection_interval(const BoundingSphere& volume, const Vec3& axis);
/// Range of axis . x over the oriented box.
Interval projection_interval(const Obb& volume, const Vec3& axis);
/// Range of axis . x over the capsule.
Interval projection_interval(const BoundingCapsule& volume, const Vec3& axis);
/// Range of axis . x over the k-DOP (over its vertices: O(K^4)).
template <int K>
Interval projection_interval(const Kdop<K>& volume, const Vec3& axis);
/// Range of axis . x over the hull (over its vertices: O(V)).
Interval projection_interval(const ConvexHull& volume, const Vec3& axis);

/// Side of the plane normal . x = offset the volume lies on (touching = Straddling). A zero
/// normal gives Front when offset < 0, Back when offset > 0, else Straddling.
template <class Volume>
PlaneSide classify_plane(const Volume& volume, const Vec3& normal, Real offset) {
  const Interval r = projection_interval(volume, normal);
  if (r.lo > offset) return PlaneSide::Front;
  if (r.hi < offset) return PlaneSide::Back;
  return PlaneSide::Straddling;
}

/// Entry parameter of the ray into the box (slab method, robust to zero direction
/// components), or nullopt when it misses within [0, max_t].
std::optional<Real> ray_entry(const Aabb& volume, const Ray& ray, Real max_t);
/// Entry parameter of the ray into the ball (cancellation-safe quadratic; radius 0 allowed).
std::optional<Real> ray_entry(const BoundingSphere& volume, const Ray& ray, Real max_t);
/// Entry parameter of the ray into the oriented box (slabs along its axes).
std::optional<Real> ray_entry(const Obb& volume, const Ray& ray, Real max_t);
/// Entry parameter of the ray into the capsule: the earliest entry into its cylinder body
/// (infinite cylinder clipped to the segment's slab) or its two end balls.
std::optional<Real> ray_entry(const BoundingCapsule& volume, const Ray& ray, Real max_t);
/// Entry parameter of the ray into the k-DOP (slab method over its K/2 slabs). O(K).
template <int K>
std::optional<Real> ray_entry(const Kdop<K>& volume, const Ray& ray, Real max_t);
/// Entry parameter of the ray into the hull (ConvexHull::raycast, Cyrus-Beck clipping).
std::optional<Real> ray_entry(const ConvexHull& volume, const Ray& ray, Real max_t);

/// True when the segment pq shares a point with the volume.
template <class Volume>
bool intersects_segment(const Volume& volume, const Vec3& p, const Vec3& q) {
  return ray_entry(volume, Ray{p, q - p}, Real(1)).has_value();
}

}  // namespace proxima
