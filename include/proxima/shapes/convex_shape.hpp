#pragma once
/// @file convex_shape.hpp
/// The ConvexShape concept: the member set every convex shape shares (no virtual call;
/// UnroundedCore in unrounded_core.hpp). Templates over shapes (placed.hpp's world-frame helpers, the narrow
/// phase's generic GJK / EPA path) are constrained by it, so a type without these members
/// is rejected at the call site rather than deep inside the template.
///
/// All members answer in the shape's local frame unless the name says world:
///   support(d)        farthest point in direction d (any length, not zero)
///   core_support(d)   the same for the core; the shape is core ⊕ ball(core_radius())
///   local_aabb()      tight box; world_aabb(pose) the exact box of the placed shape
///   raycast(ray, t)   first hit in [0, t]; a ray starting inside hits at t = 0
///   contains(p)       closed solid membership
///   closest_point(p)  nearest surface point, signed distance, outward normal
/// and, for the shapes of finite volume (every convex shape but the half-space),
///   mass_properties(density).
#include <proxima/core/math.hpp>
#include <proxima/core/transform.hpp>
#include <proxima/geometry/aabb.hpp>
#include <proxima/geometry/ray.hpp>
#include <proxima/shapes/mass_properties.hpp>
#include <proxima/shapes/shape_type.hpp>
#include <proxima/shapes/surface_point.hpp>

#include <concepts>
#include <optional>

namespace proxima {

/// A shape answering ray casts in its local frame (every convex shape and the mesh).
template <class S>
concept RayCastable = requires(const S& s, const Ray& ray, Real max_t) {
  { s.raycast(ray, max_t) } -> std::same_as<std::optional<RayHit>>;
};

/// A shape answering point queries in its local frame (every convex shape and the mesh).
template <class S>
concept PointQueryable = requires(const S& s, const Vec3& p) {
  { s.contains(p) } -> std::same_as<bool>;
  { s.closest_point(p) } -> std::same_as<SurfacePoint>;
};

/// A convex shape: support mapping, core + radius, bounds, ray cast and point queries.
template <class S>
concept ConvexShape = RayCastable<S> && PointQueryable<S> &&
    requires(const S& s, const Vec3& d, const Transform& pose) {
  { S::kType } -> std::convertible_to<ShapeType>;
  { s.support(d) } -> std::same_as<Vec3>;
  { s.core_support(d) } -> std::same_as<Vec3>;
  { s.core_radius() } -> std::same_as<Real>;
  { s.local_aabb() } -> std::same_as<Aabb>;
  { s.world_aabb(pose) } -> std::same_as<Aabb>;
};

/// A convex shape of finite volume: it also has mass properties.
template <class S>
concept FiniteConvexShape = ConvexShape<S> && requires(const S& s, Real density) {
  { s.mass_properties(density) } -> std::same_as<MassProperties>;
};

}  // namespace proxima
