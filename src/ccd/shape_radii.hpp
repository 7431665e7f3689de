#pragma once
// Internal: the radii of a geometry that the motion bounds need, and the world support
// point of a bounded convex shape (shared by time_of_impact and safe_step).
#include <proxima/core/math.hpp>
#include <proxima/core/transform.hpp>
#include <proxima/shapes/shape_ref.hpp>

namespace proxima::detail {

/// Radii of a geometry about its local origin: `core` bounds the points that rotation moves
/// (0 for a sphere or point, the core half length of a capsule, +infinity for a half-space),
/// `full` bounds the whole shape.
struct ShapeRadii {
  Real core = Real(0);
  Real full = Real(0);
  bool convex = false;     ///< bounded convex shape: it has a support mapping
  bool halfspace = false;  ///< unbounded
};

/// The radii of `shape` (O(1), a hull: O(vertices)).
ShapeRadii shape_radii(ShapeRef shape);

/// World support point of a bounded convex shape at `pose` (only when ShapeRadii::convex;
/// the pose's position otherwise).
Vec3 world_support(ShapeRef shape, const Transform& pose, const Vec3& direction);

}  // namespace proxima::detail
