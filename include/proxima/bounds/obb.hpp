#pragma once
/// @file obb.hpp
/// Obb: the oriented bounding box (centre, orthonormal axes, half extents).

#include <proxima/core/math.hpp>
#include <proxima/core/result.hpp>
#include <proxima/core/transform.hpp>
#include <proxima/geometry/aabb.hpp>

#include <array>

namespace proxima {

/// Closed oriented box {center + sum_i s_i axes[i] : |s_i| <= half_extents[i]}.
///
/// `axes` holds the box axes as columns (axes[i] is the i-th unit axis, in the frame of the
/// bounded geometry); they are orthonormal. Half extents of 0 are allowed (flat boxes of
/// planar or collinear point sets).
struct Obb {
  Vec3 center{Real(0)};        ///< centre of the box
  Mat3 axes{Real(1)};          ///< columns = unit, mutually orthogonal box axes
  Vec3 half_extents{Real(0)};  ///< half edge lengths along each axis (length, >= 0)

  /// Validated construction: center finite ("center.x" ...), axes finite ("axes[1].z" ...)
  /// and orthonormal within 1e-3 ("axes", InvalidArgument; they are then re-orthonormalised
  /// by Gram-Schmidt, keeping axes[0] and the handedness), half extents finite and >= 0
  /// ("half_extents.y" ...).
  static Result<Obb> create(const Vec3& center, const Mat3& axes, const Vec3& half_extents);
  /// The box of `box` (an axis-aligned box in a local frame) placed at `pose`.
  static Obb from_aabb(const Aabb& box, const Transform& pose);

  /// Volume 8 hx hy hz (length^3).
  Real volume() const { return Real(8) * half_extents.x * half_extents.y * half_extents.z; }
  /// True when `point` is inside or on the box: |(point - center) . axes[i]| <= half_extents[i]
  /// for every axis, evaluated exactly so (the fitters guarantee their points pass it).
  bool contains(const Vec3& point) const {
    const Vec3 d = point - center;
    for (int i = 0; i < 3; ++i) {
      if (!(std::abs(glm::dot(d, axes[i])) <= half_extents[i])) return false;
    }
    return true;
  }
  /// Farthest corner in `direction` (any vector; ties pick the + side).
  Vec3 support(const Vec3& direction) const;
  /// The 8 corners; corner k takes the + side of axis i when bit i of k is set.
  std::array<Vec3, 8> corners() const;
  /// Tight axis-aligned box of the oriented box.
  Aabb aabb() const;
  /// Point in box coordinates (components along the axes, relative to the centre).
  Vec3 to_local(const Vec3& point) const { return glm::transpose(axes) * (point - center); }
};

}  // namespace proxima
