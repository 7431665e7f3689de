#pragma once
/// @file capsule.hpp
/// Capsule: a segment core along local z plus a radius (a cylinder capped by two
/// hemispheres).

#include <proxima/core/result.hpp>
#include <proxima/shapes/convex_shape.hpp>

namespace proxima {

/// Solid capsule: the points within `radius` of the segment (0, 0, -half_length) –
/// (0, 0, +half_length) of its local z axis, centred on the local origin.
///
/// Members as every shape (see Sphere), all in the local frame unless the name says world.
class Capsule {
 public:
  /// Dispatch tag.
  static constexpr ShapeType kType = ShapeType::Capsule;

  /// Validated construction: radius finite and > 0 (error field "radius"), half_length
  /// finite and >= 0 (field "half_length"; 0 gives a sphere).
  static Result<Capsule> create(Real radius, Real half_length);

  /// Radius of the caps and the cylindrical part (> 0).
  Real radius() const { return radius_; }
  /// Half the length of the core segment (>= 0); the capsule's total height is
  /// 2 (half_length + radius).
  Real half_length() const { return half_length_; }
  /// Upper end of the core segment, (0, 0, half_length).
  Vec3 top() const { return {Real(0), Real(0), half_length_}; }
  /// Lower end of the core segment, (0, 0, -half_length).
  Vec3 bottom() const { return {Real(0), Real(0), -half_length_}; }

  /// Farthest point of the capsule in `direction`: core_support + radius * direction /
  /// |direction| (the top pole for a zero or non-finite direction).
  Vec3 support(const Vec3& direction) const;
  /// Farthest point of the core segment in `direction`: the end with the same sign of z as
  /// `direction` (top() when direction.z == 0).
  Vec3 core_support(const Vec3& direction) const { return direction.z >= Real(0) ? top() : bottom(); }
  /// Radius added around the core: the capsule's radius.
  Real core_radius() const { return radius_; }

  /// Tight box in the local frame: [-r, r] x [-r, r] x [-h - r, h + r].
  Aabb local_aabb() const;
  /// Tight box in the world frame under `pose`: the box of the two transformed segment ends
  /// grown by the radius (exact for every rotation).
  Aabb world_aabb(const Transform& pose) const;

  /// First hit of `ray` (local frame) with the solid capsule within [0, max_t]
  /// (geometry::ray_capsule); origin inside: t = 0, normal -direction/|direction|. Nothing
  /// for a negative or NaN max_t or a non-finite ray.
  std::optional<RayHit> raycast(const Ray& ray, Real max_t) const;
  /// True when `point` (local) is inside or on the surface: distance to the core segment
  /// <= radius (false for a non-finite point).
  bool contains(const Vec3& point) const;
  /// Nearest surface point to `point` (local) with signed distance (< 0 inside): the core
  /// point nearest to `point` pushed out by the radius. A point on the axis gets the
  /// normal +x (the cylindrical wall is then nearest, at distance radius). A non-finite
  /// point gives the top pole at distance +infinity.
  SurfacePoint closest_point(const Vec3& point) const;
  /// Volume pi r^2 (2h) + 4/3 pi r^3, mass, centroid (origin) and inertia about the origin:
  /// the cylinder plus the two hemispheres shifted by the parallel-axis theorem; the axis
  /// is local z.
  MassProperties mass_properties(Real density = Real(1)) const;

 private:
  Capsule(Real radius, Real half_length) : radius_(radius), half_length_(half_length) {}
  Real radius_;
  Real half_length_;
};

}  // namespace proxima
