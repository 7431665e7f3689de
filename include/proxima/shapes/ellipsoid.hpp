#pragma once
/// @file ellipsoid.hpp
/// Ellipsoid: a solid axis-aligned ellipsoid in its local frame.

#include <proxima/shapes/unrounded_core.hpp>

namespace proxima {

/// Solid ellipsoid centred on its local origin with semi-axes `radii` along local x, y, z:
/// the points with (x/rx)^2 + (y/ry)^2 + (z/rz)^2 <= 1.
///
/// Same members as Sphere (see sphere.hpp), all in the local frame unless the name says
/// world. The core is the whole ellipsoid and the core radius is 0.
class Ellipsoid : public UnroundedCore<Ellipsoid> {
 public:
  /// Dispatch tag.
  static constexpr ShapeType kType = ShapeType::Ellipsoid;

  /// Validated construction: each radius finite and > 0 (error fields "radii.x", "radii.y",
  /// "radii.z").
  static Result<Ellipsoid> create(const Vec3& radii);

  /// Semi-axis lengths along local x, y, z (each > 0).
  const Vec3& radii() const { return radii_; }

  /// Farthest point of the ellipsoid in `direction`: R^2 d / |R d| with R = diag(radii)
  /// (any non-zero vector; zero or non-finite gives the surface point (0, 0, rz)). O(1).
  Vec3 support(const Vec3& direction) const;

  /// Tight box in the local frame: [-radii, radii].
  Aabb local_aabb() const;
  /// Exact tight box in the world frame under `pose`: half extent on world axis i is
  /// sqrt(sum_j (M_ij r_j)^2), M = the rotation matrix.
  Aabb world_aabb(const Transform& pose) const;

  /// First hit of `ray` (local frame) with the solid ellipsoid within [0, max_t] (conventions
  /// of ray.hpp). The ray is scaled into the unit sphere, which keeps t; the normal is mapped
  /// back with the inverse transpose of the scaling.
  std::optional<RayHit> raycast(const Ray& ray, Real max_t) const;
  /// True when `point` (local) is inside or on the surface.
  bool contains(const Vec3& point) const;
  /// Nearest surface point to `point` (local) with signed distance (< 0 inside), by Eberly's
  /// robust bisection (works for points on the axes, on the symmetry planes and inside, and
  /// for any ratio of radii; at most a fixed number of iterations). A non-finite point gives
  /// (0, 0, rz) at distance +infinity.
  SurfacePoint closest_point(const Vec3& point) const;
  /// Volume 4/3 pi rx ry rz, mass, centroid (origin) and inertia for uniform `density`:
  /// I_xx = m (ry^2 + rz^2) / 5 and cyclic.
  MassProperties mass_properties(Real density = Real(1)) const;

 private:
  explicit Ellipsoid(const Vec3& radii) : radii_(radii) {}
  Vec3 radii_;
};

}  // namespace proxima
