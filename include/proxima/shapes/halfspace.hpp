#pragma once
/// @file halfspace.hpp
/// HalfSpace: the unbounded solid n . x <= d (floors, walls, clipping planes).

#include <proxima/shapes/unrounded_core.hpp>

namespace proxima {

/// Solid half-space {x : normal . x <= offset} in its local frame; `normal` is unit and
/// points out of the solid.
///
/// Members as every shape (see Sphere), all in the local frame unless the name says world,
/// except mass_properties: a half-space has infinite volume and no mass properties.
class HalfSpace : public UnroundedCore<HalfSpace> {
 public:
  /// Dispatch tag.
  static constexpr ShapeType kType = ShapeType::HalfSpace;

  /// Half size of the cube |x|_inf <= kSupportExtent (local frame) in which support()
  /// looks for its farthest point, since the half-space itself has none: 1e5 in float
  /// (1e10 in double), ten times (a million times) the 1e4 coordinates of large scenes,
  /// while the float spacing there (0.008) stays small next to ordinary shapes. The cube
  /// grows to |offset| when the plane lies farther than that from the origin.
  static constexpr Real kSupportExtent = sizeof(Real) == 4 ? Real(1e5) : Real(1e10);

  /// Validated construction. `normal` must be finite (error fields "normal.x" ...,
  /// NotFinite or OutOfRange) and non-zero (ErrorCode::Degenerate, field "normal"); it is
  /// normalised and `offset` divided by its length, so the solid is unchanged. `offset`
  /// must be finite (field "offset", NotFinite or OutOfRange, also when the rescaled offset
  /// exceeds kMaxCoordinate).
  static Result<HalfSpace> create(const Vec3& normal, Real offset);

  /// Unit outward normal (local frame).
  const Vec3& normal() const { return normal_; }
  /// Offset d of the boundary plane normal . x = d: the signed distance of the plane from
  /// the local origin along the normal.
  Real offset() const { return offset_; }

  /// Farthest point in `direction` of the half-space clipped to the cube |x|_inf <=
  /// max(kSupportExtent, |offset|): a vertex of that convex polytope (exact linear
  /// programme: the cube's support corner, moved back onto the plane along the axes that
  /// cost the least progress in `direction`). A zero or non-finite direction gives a valid
  /// point.
  Vec3 support(const Vec3& direction) const;

  /// Box in the local frame: -kRealMax / +kRealMax on unbounded sides; bounded only on the
  /// axis that the normal matches exactly (normal = +e_i: max_i = offset; -e_i: min_i =
  /// -offset).
  Aabb local_aabb() const;
  /// Box in the world frame under `pose`, computed from the world normal and offset
  /// (never by transforming an unbounded box): bounded only on an axis that the world
  /// normal matches exactly.
  Aabb world_aabb(const Transform& pose) const;

  /// First hit of `ray` (local frame) with the solid within [0, max_t]
  /// (geometry::ray_halfspace); origin inside: t = 0, normal -direction/|direction|.
  /// Nothing for a negative or NaN max_t or a non-finite ray.
  std::optional<RayHit> raycast(const Ray& ray, Real max_t) const;
  /// True when `point` (local) is inside or on the boundary: normal . point <= offset
  /// (false for a non-finite point).
  bool contains(const Vec3& point) const;
  /// Projection of `point` on the boundary plane, normal = normal(), signed distance
  /// normal . point - offset. A non-finite point gives the plane point offset * normal at
  /// distance +infinity.
  SurfacePoint closest_point(const Vec3& point) const;

 private:
  HalfSpace(const Vec3& normal, Real offset) : normal_(normal), offset_(offset) {}
  Vec3 normal_;
  Real offset_;
};

}  // namespace proxima
