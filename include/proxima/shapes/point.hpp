#pragma once
/// @file point.hpp
/// Point: a shape reduced to its local origin (a sphere of radius zero), the simplest
/// core for "core + radius" queries and a probe for distance tests.

#include <proxima/shapes/unrounded_core.hpp>

namespace proxima {

/// The single point at the local origin. A shape without interior: its closest-point
/// distances are never negative and `contains` accepts only points within
/// `linear_tolerance(0)` (= kRelativeTolerance) of the origin.
///
/// Members as every shape (see Sphere), all in the local frame unless the name says world.
class Point : public UnroundedCore<Point> {
 public:
  /// Dispatch tag.
  static constexpr ShapeType kType = ShapeType::Point;

  /// Construction (nothing to validate; always succeeds).
  static Result<Point> create();

  /// Farthest point in `direction`: the origin, for every direction.
  Vec3 support(const Vec3& /*direction*/) const { return Vec3(Real(0)); }

  /// The degenerate box [0, 0] in the local frame.
  Aabb local_aabb() const;
  /// The degenerate box of the point `pose.position` in the world frame.
  Aabb world_aabb(const Transform& pose) const;

  /// Hit of `ray` (local frame) when it passes within linear_tolerance(largest coordinate of
  /// the ray origin) of the point for some t in [0, max_t], else nothing (also for a
  /// negative or NaN max_t and for a non-finite ray). The hit is the ray's nearest approach to the point, its normal
  /// -direction/|direction|; a zero direction hits (t = 0, normal +z) only when the origin
  /// is on the point. O(1).
  std::optional<RayHit> raycast(const Ray& ray, Real max_t) const;
  /// True when `point` (local) is within kRelativeTolerance of the origin (false for a
  /// non-finite point).
  bool contains(const Vec3& point) const;
  /// The origin, its distance |point| (>= 0) and the unit direction from the origin towards
  /// `point` (+z when `point` is on the origin; +z at distance +infinity for a non-finite
  /// point).
  SurfacePoint closest_point(const Vec3& point) const;
  /// Zero volume, mass and inertia; centroid at the origin.
  MassProperties mass_properties(Real density = Real(1)) const;

 private:
  Point() = default;
};

}  // namespace proxima
