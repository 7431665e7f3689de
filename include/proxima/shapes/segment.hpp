#pragma once
/// @file segment.hpp
/// Segment: the line segment between two local points, a shape without interior and the
/// core of the capsule.

#include <proxima/shapes/unrounded_core.hpp>

namespace proxima {

/// Line segment ab, end points in local coordinates. A shape without interior: distances
/// are never negative and `contains` accepts points within `tolerance()` of the segment.
///
/// Members as every shape (see Sphere), all in the local frame unless the name says world.
class Segment : public UnroundedCore<Segment> {
 public:
  /// Dispatch tag.
  static constexpr ShapeType kType = ShapeType::Segment;

  /// Validated construction: finite end points (error fields "a.x" ... "b.z", NotFinite or
  /// OutOfRange) that do not coincide: |b - a| must exceed kRelativeTolerance times the
  /// largest end-point coordinate (ErrorCode::Degenerate, field "b").
  static Result<Segment> create(const Vec3& a, const Vec3& b);

  /// First end point (local frame).
  const Vec3& a() const { return a_; }
  /// Second end point (local frame).
  const Vec3& b() const { return b_; }
  /// Length |b - a| (> 0).
  Real length() const { return glm::length(b_ - a_); }
  /// Distance within which a point counts as on the segment: linear_tolerance of the
  /// largest end-point coordinate (which bounds both the size and the coordinate rounding).
  Real tolerance() const { return tolerance_; }

  /// Farthest end point in `direction` (a for a zero or non-finite direction or a tie).
  Vec3 support(const Vec3& direction) const;

  /// Box of the two end points in the local frame.
  Aabb local_aabb() const;
  /// Box of the two transformed end points in the world frame (exact).
  Aabb world_aabb(const Transform& pose) const;

  /// Hit of `ray` (local frame) when, for some t in [0, max_t], it passes within
  /// max(tolerance(), linear_tolerance(largest coordinate of the ray origin)) of the
  /// segment, else nothing (also for a negative or NaN max_t and for a non-finite ray). The
  /// hit is the ray's nearest
  /// approach to the segment (Ericson's clamped closest points of two segments), with a
  /// unit normal orthogonal to the segment facing the ray origin. A ray running along the
  /// segment (both end points within that tolerance of the ray's line) hits where it enters
  /// the segment, with normal -direction/|direction|. A zero direction hits (t = 0, a normal
  /// orthogonal to the segment) only when the origin is on the segment. O(1).
  std::optional<RayHit> raycast(const Ray& ray, Real max_t) const;
  /// True when `point` (local) is within tolerance() of the segment (false for a non-finite
  /// point).
  bool contains(const Vec3& point) const;
  /// Nearest point of the segment, its distance (>= 0) and the unit direction from it
  /// towards `point` (a unit vector orthogonal to the segment when `point` is on it). A
  /// non-finite point gives a() at distance +infinity.
  SurfacePoint closest_point(const Vec3& point) const;
  /// Zero volume, mass and inertia; centroid at the midpoint (a + b) / 2.
  MassProperties mass_properties(Real density = Real(1)) const;

 private:
  Segment(const Vec3& a, const Vec3& b, Real tolerance) : a_(a), b_(b), tolerance_(tolerance) {}
  Vec3 a_;
  Vec3 b_;
  Real tolerance_;
};

}  // namespace proxima
