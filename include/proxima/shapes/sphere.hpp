#pragma once
/// @file sphere.hpp
/// Sphere: a point core (the local origin) plus a radius.

#include <proxima/core/result.hpp>
#include <proxima/shapes/convex_shape.hpp>

namespace proxima {

/// Solid sphere centred on its local origin.
///
/// Every shape offers the same members, all in the shape's local frame unless the name
/// says world: validated `create`, `support`, `core_support` + `core_radius` (the
/// "core + radius" form: support(d) = core_support(d) + core_radius * d/|d|), `local_aabb`,
/// `world_aabb`, `raycast`, `contains`, `closest_point`, `mass_properties`.
class Sphere {
 public:
  /// Dispatch tag.
  static constexpr ShapeType kType = ShapeType::Sphere;

  /// Validated construction: radius finite and > 0 (error field "radius").
  static Result<Sphere> create(Real radius);

  /// Radius (> 0).
  Real radius() const { return radius_; }

  /// Farthest point of the sphere in `direction` (any non-zero vector; zero gives a point
  /// of the surface).
  Vec3 support(const Vec3& direction) const;
  /// Farthest point of the core (the centre) in `direction`: always the origin.
  Vec3 core_support(const Vec3& /*direction*/) const { return Vec3(Real(0)); }
  /// Radius added around the core: the sphere's radius.
  Real core_radius() const { return radius_; }

  /// Tight box in the local frame.
  Aabb local_aabb() const;
  /// Tight box in the world frame under `pose`.
  Aabb world_aabb(const Transform& pose) const;

  /// First hit of `ray` (local frame) with the solid sphere within [0, max_t].
  std::optional<RayHit> raycast(const Ray& ray, Real max_t) const;
  /// True when `point` (local) is inside or on the surface.
  bool contains(const Vec3& point) const;
  /// Nearest surface point to `point` (local) with signed distance (< 0 inside).
  SurfacePoint closest_point(const Vec3& point) const;
  /// Volume, mass, centroid (origin) and inertia (2/5 m r^2 E) for uniform `density`.
  MassProperties mass_properties(Real density = Real(1)) const;

 private:
  explicit Sphere(Real radius) : radius_(radius) {}
  Real radius_;
};

}  // namespace proxima
