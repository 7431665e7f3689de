#pragma once
/// @file box.hpp
/// Box: a solid rectangular box centred on its local origin, aligned with the local axes
/// (an oriented box once placed).

#include <proxima/shapes/unrounded_core.hpp>

namespace proxima {

/// Solid box [-h, h] (h = half extents) in its local frame.
///
/// Members as every shape (see Sphere), all in the local frame unless the name says world.
class Box : public UnroundedCore<Box> {
 public:
  /// Dispatch tag.
  static constexpr ShapeType kType = ShapeType::Box;

  /// Validated construction: every half extent finite and > 0 (error fields
  /// "half_extents.x", "half_extents.y", "half_extents.z").
  static Result<Box> create(const Vec3& half_extents);

  /// Half extents along local x, y, z (each > 0).
  const Vec3& half_extents() const { return half_extents_; }

  /// Farthest corner in `direction` (the + side on axes where the direction component is
  /// zero; the corner h for a zero direction, -h for a NaN one).
  Vec3 support(const Vec3& direction) const;

  /// Tight box in the local frame: [-h, h].
  Aabb local_aabb() const;
  /// Tight box in the world frame under `pose`: the exact box of the 8 transformed corners,
  /// in O(1) from |R| h (Arvo).
  Aabb world_aabb(const Transform& pose) const;

  /// First hit of `ray` (local frame) with the solid box within [0, max_t] (slab method,
  /// geometry::ray_aabb); origin inside: t = 0, normal -direction/|direction|. Nothing for
  /// a negative or NaN max_t or a non-finite ray.
  std::optional<RayHit> raycast(const Ray& ray, Real max_t) const;
  /// True when `point` (local) is inside or on the surface: |p_i| <= h_i on every axis
  /// (false for a non-finite point).
  bool contains(const Vec3& point) const;
  /// Nearest surface point to `point` (local) with signed distance (< 0 inside). Outside:
  /// the clamped point and (point - clamped)/distance. Inside: the projection on the face
  /// nearest to `point` (ties go to x, then y, then z; the + face when the coordinate is 0)
  /// with that face's normal. A non-finite point gives the centre of the +z face at
  /// distance +infinity.
  SurfacePoint closest_point(const Vec3& point) const;
  /// Volume 8 hx hy hz, mass, centroid (origin) and the diagonal inertia
  /// m/3 (hy^2 + hz^2), m/3 (hx^2 + hz^2), m/3 (hx^2 + hy^2).
  MassProperties mass_properties(Real density = Real(1)) const;

 private:
  explicit Box(const Vec3& half_extents) : half_extents_(half_extents) {}
  Vec3 half_extents_;
};

}  // namespace proxima
