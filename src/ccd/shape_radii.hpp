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

/// Radii about the line through the local origin along the unit `local_axis` (the axis of a
/// rotation, fixed in the body's frame): `core` for the points that the rotation moves,
/// `full` for the whole shape; each at most the matching radius of shape_radii. Half-spaces:
/// +infinity. Exact for boxes, hulls and capsules; other shapes use the corners of their
/// local box (distance from a line is convex, so a box's farthest point is a corner).
ShapeRadii shape_radii_about_axis(ShapeRef shape, const Vec3& local_axis);

/// World support point of a bounded convex shape at `pose` (only when ShapeRadii::convex;
/// the pose's position otherwise).
Vec3 world_support(ShapeRef shape, const Transform& pose, const Vec3& direction);

}  // namespace proxima::detail
