#pragma once
/// @file cone.hpp
/// Cone: a solid right circular cone about the local z axis.

#include <proxima/shapes/unrounded_core.hpp>

namespace proxima {

/// Solid right circular cone: axis = local z, apex at (0, 0, +half_length), base disc of
/// radius `radius` centred at (0, 0, -half_length). The local origin is the middle of the
/// axis, not the centroid (which is at (0, 0, -half_length / 2)).
///
/// Same members as Sphere (see sphere.hpp), all in the local frame unless the name says
/// world. The core is the whole cone and the core radius is 0.
class Cone : public UnroundedCore<Cone> {
 public:
  /// Dispatch tag.
  static constexpr ShapeType kType = ShapeType::Cone;

  /// Validated construction: radius and half_length finite and > 0 (error fields "radius",
  /// "half_length").
  static Result<Cone> create(Real radius, Real half_length);

  /// Radius of the base disc (> 0).
  Real radius() const { return radius_; }
  /// Half the height, along local z (> 0): the apex is at +half_length, the base at
  /// -half_length.
  Real half_length() const { return half_length_; }

  /// Farthest point of the cone in `direction` (any vector): the apex or a point of the
  /// base rim (the base centre for a direction along -z, the apex for a zero or
  /// non-finite direction). O(1).
  Vec3 support(const Vec3& direction) const;

  /// Tight box in the local frame: [-r, -r, -h] .. [r, r, h].
  Aabb local_aabb() const;
  /// Exact tight box in the world frame under `pose`: the box of the apex and of the base
  /// disc, whose half extent on world axis i is r sqrt(1 - a_i^2), a = the world axis
  /// direction.
  Aabb world_aabb(const Transform& pose) const;

  /// First hit of `ray` (local frame) with the solid cone within [0, max_t] (conventions of
  /// ray.hpp: origin inside hits at t = 0 with normal -direction/|direction|).
  std::optional<RayHit> raycast(const Ray& ray, Real max_t) const;
  /// True when `point` (local) is inside or on the surface.
  bool contains(const Vec3& point) const;
  /// Nearest surface point to `point` (local) with signed distance (< 0 inside); solved in
  /// the (radial, z) half-plane as the nearest point of the slant edge and the base edge of
  /// the profile triangle. Inside points go to the nearest face (slant side or base) with
  /// that face's normal. A non-finite point gives the apex at distance +infinity.
  SurfacePoint closest_point(const Vec3& point) const;
  /// Volume 2 pi r^2 h / 3, mass, centroid (0, 0, -h/2) and inertia about the centroid for
  /// uniform `density`: I_zz = 3/10 m r^2, I_xx = I_yy = 3/20 m r^2 + 3/80 m (2h)^2.
  MassProperties mass_properties(Real density = Real(1)) const;

 private:
  Cone(Real radius, Real half_length) : radius_(radius), half_length_(half_length) {}
  Real radius_;
  Real half_length_;
};

}  // namespace proxima
