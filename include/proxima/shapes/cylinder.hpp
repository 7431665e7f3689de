#pragma once
/// @file cylinder.hpp
/// Cylinder: a solid capped cylinder about the local z axis.

#include <proxima/shapes/unrounded_core.hpp>

namespace proxima {

/// Solid capped cylinder centred on its local origin: axis = local z, circular caps of
/// radius `radius` at z = -half_length and z = +half_length.
///
/// Same members as Sphere (see sphere.hpp), all in the local frame unless the name says
/// world. The core is the whole cylinder and the core radius is 0.
class Cylinder : public UnroundedCore<Cylinder> {
 public:
  /// Dispatch tag.
  static constexpr ShapeType kType = ShapeType::Cylinder;

  /// Validated construction: radius and half_length finite and > 0 (error fields "radius",
  /// "half_length").
  static Result<Cylinder> create(Real radius, Real half_length);

  /// Radius of the caps and of the side (> 0).
  Real radius() const { return radius_; }
  /// Half the distance between the caps, along local z (> 0).
  Real half_length() const { return half_length_; }

  /// Farthest point of the cylinder in `direction` (any vector): a point of a cap rim, or
  /// the centre of a cap when `direction` is parallel to the axis (the centre of the top
  /// cap for a zero or non-finite direction). O(1).
  Vec3 support(const Vec3& direction) const;

  /// Tight box in the local frame: [-r, -r, -h] .. [r, r, h].
  Aabb local_aabb() const;
  /// Exact tight box in the world frame under `pose`: on world axis i the half extent is
  /// h |a_i| + r sqrt(1 - a_i^2), a = the world axis direction (extent of the two cap discs).
  Aabb world_aabb(const Transform& pose) const;

  /// First hit of `ray` (local frame) with the solid cylinder within [0, max_t] (conventions
  /// of ray.hpp: origin inside hits at t = 0 with normal -direction/|direction|).
  std::optional<RayHit> raycast(const Ray& ray, Real max_t) const;
  /// True when `point` (local) is inside or on the surface.
  bool contains(const Vec3& point) const;
  /// Nearest surface point to `point` (local) with signed distance (< 0 inside); solved in
  /// the (radial, z) half-plane as the nearest point of a rectangle's boundary. Inside
  /// points go to the nearest face (side or cap) with that face's normal. A non-finite
  /// point gives the top cap's centre at distance +infinity.
  SurfacePoint closest_point(const Vec3& point) const;
  /// Volume 2 pi r^2 h, mass, centroid (origin) and inertia about it for uniform
  /// `density`: I_zz = m r^2 / 2, I_xx = I_yy = m (3 r^2 + (2h)^2) / 12.
  MassProperties mass_properties(Real density = Real(1)) const;

 private:
  Cylinder(Real radius, Real half_length) : radius_(radius), half_length_(half_length) {}
  Real radius_;
  Real half_length_;
};

}  // namespace proxima
