#pragma once
/// @file triangle.hpp
/// Triangle: a two-sided flat triangle, a shape without interior (the element of meshes
/// and height fields).

#include <proxima/shapes/unrounded_core.hpp>

#include <array>

namespace proxima {

/// Two-sided triangle abc, vertices in local coordinates. A shape without interior:
/// distances are never negative and `contains` accepts only points within `tolerance()` of
/// the triangle.
///
/// Members as every shape (see Sphere), all in the local frame unless the name says world.
class Triangle : public UnroundedCore<Triangle> {
 public:
  /// Dispatch tag.
  static constexpr ShapeType kType = ShapeType::Triangle;

  /// Validated construction: finite vertices (error fields "a.x" ... "c.z", NotFinite or
  /// OutOfRange), not collinear: |(b - a) x (c - a)| must exceed kRelativeTolerance times
  /// the square of the longest edge (ErrorCode::Degenerate, field "vertices").
  static Result<Triangle> create(const Vec3& a, const Vec3& b, const Vec3& c);

  /// First vertex (local frame).
  const Vec3& a() const { return v_[0]; }
  /// Second vertex (local frame).
  const Vec3& b() const { return v_[1]; }
  /// Third vertex (local frame).
  const Vec3& c() const { return v_[2]; }
  /// Vertex `i` in 0..2 (a, b, c); other indices are a programming error (asserted in
  /// debug builds; release builds wrap them into 0..2).
  const Vec3& vertex(int i) const;
  /// Unit normal (b - a) x (c - a) / |(b - a) x (c - a)| (local frame).
  const Vec3& normal() const { return normal_; }
  /// Area (length^2).
  Real area() const;
  /// Distance within which a point counts as on the triangle: linear_tolerance of the
  /// largest vertex coordinate (which bounds both the size and the coordinate rounding).
  Real tolerance() const { return tolerance_; }

  /// Farthest vertex in `direction` (the first of equal ones; a for a zero or non-finite
  /// direction).
  Vec3 support(const Vec3& direction) const;

  /// Box of the three vertices in the local frame.
  Aabb local_aabb() const;
  /// Box of the three transformed vertices in the world frame (exact).
  Aabb world_aabb(const Transform& pose) const;

  /// First hit of `ray` (local frame) with the two-sided triangle within [0, max_t],
  /// watertight (geometry::ray_triangle); the normal faces the ray origin. Nothing for a
  /// negative or NaN max_t or a non-finite ray.
  std::optional<RayHit> raycast(const Ray& ray, Real max_t) const;
  /// True when `point` (local) is within tolerance() of the triangle (false for a
  /// non-finite point).
  bool contains(const Vec3& point) const;
  /// Nearest point of the triangle, its distance (>= 0) and the unit direction from it
  /// towards `point`; when `point` is on the triangle (within tolerance()), the face normal
  /// turned towards `point` (normal() when exactly in the plane). A non-finite point gives
  /// a() and normal() at distance +infinity.
  SurfacePoint closest_point(const Vec3& point) const;
  /// Zero volume, mass and inertia; centroid at (a + b + c) / 3.
  MassProperties mass_properties(Real density = Real(1)) const;

 private:
  Triangle(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& normal, Real tolerance)
      : v_{a, b, c}, normal_(normal), tolerance_(tolerance) {}
  std::array<Vec3, 3> v_;
  Vec3 normal_;
  Real tolerance_;
};

}  // namespace proxima
