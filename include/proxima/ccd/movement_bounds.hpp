#pragma once
/// @file movement_bounds.hpp
/// Bounds of a moving shape and swept volumes: the box, sphere and oriented box containing
/// every placement of a shape along a motion between two poses, the capsule swept by a
/// sphere, and the convex hull swept by a box or a convex hull.
///
/// A Motion (motion.hpp) moves the position linearly and the rotation by slerp (constant
/// angular velocity about a fixed axis, shortest arc) as t goes from 0 to 1. Pure translations
/// (identical start and end rotations) get tight answers; motions with rotation get
/// conservative ones, as stated per function.

#include <proxima/bounds/bounding_sphere.hpp>
#include <proxima/bounds/fit_shape.hpp>
#include <proxima/bounds/obb.hpp>
#include <proxima/ccd/motion.hpp>
#include <proxima/core/math.hpp>
#include <proxima/core/result.hpp>
#include <proxima/core/transform.hpp>
#include <proxima/geometry/aabb.hpp>
#include <proxima/shapes/box.hpp>
#include <proxima/shapes/capsule.hpp>
#include <proxima/shapes/convex_hull.hpp>
#include <proxima/shapes/sphere.hpp>

#include <algorithm>
#include <cmath>
#include <span>

namespace proxima {

/// Radius of the ball about the local origin that contains `local_box` (its farthest
/// corner's distance).
Real radius_about_origin(const Aabb& local_box);

/// Radius about the local origin of a ball containing `shape` (local frame): the smaller of
/// the farthest corner of its local box and |centre| + radius of its own bounding sphere.
/// Infinite for a half-space.
template <class S>
Real shape_radius_about_origin(const S& shape) {
  const BoundingSphere s = fit_shape_sphere(shape, Transform::identity());
  const Real by_sphere = glm::length(s.center) + s.radius;
  const Real by_box = radius_about_origin(shape.local_aabb());
  const Real r = std::min(by_sphere, by_box);
  return std::isfinite(r) && r < kRealMax ? r : std::numeric_limits<Real>::infinity();
}

/// World box containing every placement along `motion` of a geometry with local box
/// `local_box` contained in the ball of `radius` about the local origin (negative:
/// radius_about_origin(local_box)).
/// Translation: the union of the start and end world boxes of `local_box` (exact for the
/// box itself). With rotation: the box of the segment start.position - end.position grown
/// by the radius (conservative for any rotation path). An infinite radius gives the box of
/// +-kRealMax. O(1).
Aabb motion_aabb(const Aabb& local_box, const Motion& motion, Real radius = Real(-1));

/// motion_aabb for a shape: translation uses the shape's exact world boxes (fit_shape_aabb,
/// padded by a few ulps; tight: the box of the swept shape), rotation its radius about the
/// origin.
template <class S>
Aabb motion_aabb(const S& shape, const Motion& motion) {
  if (motion.is_translation()) return merge(fit_shape_aabb(shape, motion.start), fit_shape_aabb(shape, motion.end));
  return motion_aabb(shape.local_aabb(), motion, shape_radius_about_origin(shape));
}

/// World ball containing every placement along `motion` of a geometry whose local bounding
/// ball is `local_sphere`. Translation: centre at the midpoint of the start and end centres,
/// radius half their distance plus the radius (the smallest ball of the swept ball).
/// With rotation: centre at the midpoint of the start and end positions, radius half their
/// distance plus |local centre| + radius (conservative). O(1).
BoundingSphere motion_sphere(const BoundingSphere& local_sphere, const Motion& motion);

/// motion_sphere for a shape, from its own bounding sphere (fit_shape_sphere).
template <class S>
BoundingSphere motion_sphere(const S& shape, const Motion& motion) {
  return motion_sphere(fit_shape_sphere(shape, Transform::identity()), motion);
}

/// World oriented box containing every placement along `motion` of a geometry with local
/// box `local_box` inside the ball of `radius` about the local origin (negative:
/// radius_about_origin(local_box)).
/// Translation: the smaller (by volume) of the box aligned with the start rotation, grown
/// by half the displacement on each axis, and the box with its first axis along the
/// displacement (exact support along it). With rotation: first axis along the displacement,
/// half extents (|d| / 2 + radius, radius, radius) about the midpoint of the positions
/// (conservative). O(1).
Obb motion_obb(const Aabb& local_box, const Motion& motion, Real radius = Real(-1));

/// motion_obb for a shape (its local box, and its radius about the origin under rotation).
template <class S>
Obb motion_obb(const S& shape, const Motion& motion) {
  return motion_obb(shape.local_aabb(), motion, shape_radius_about_origin(shape));
}

/// A capsule with its world placement (the capsule's axis is its local z).
struct PlacedCapsule {
  Capsule capsule;  ///< radius and half length
  Transform pose;   ///< placement of its centre and axis
};

/// The capsule swept by a ball of `radius` whose centre moves from `from` to `to` (world):
/// exact. Errors: NotFinite ("from.x" ...), NonPositive / NotFinite ("radius").
Result<PlacedCapsule> swept_sphere(const Vec3& from, const Vec3& to, Real radius);
/// The capsule swept by `sphere` along `motion` (rotation does not move a sphere): exact.
Result<PlacedCapsule> swept_sphere(const Sphere& sphere, const Motion& motion);

/// How swept_hull samples a motion with rotation.
struct SweepOptions {
  /// Largest rotation (radians) between two sampled placements (> 0). The hull of the samples
  /// is grown by the largest deviation of a point from the chords, radius * step^2 / 8, so a
  /// smaller step gives a tighter, larger hull.
  Real max_angle_step = Real(kPi / 16);
};

/// World convex hull containing every placement along `motion` of the convex hull of
/// `local_points` (local frame). Translation: ConvexHull::create of the start and end
/// placements of the points: exact (the Minkowski sum of the hull and the displacement).
/// With rotation: conservative: the placements at n + 1 evenly spaced t (n = ceil(angle /
/// max_angle_step)), each point grown into a cube of half side delta = R step^2 / 8 (R the
/// largest |point|, step = angle / n), which bounds how far a rotating point strays from the
/// chord between two samples; the excess over the true swept volume is below sqrt(3) delta
/// plus the hull's own convexification. Errors: those of ConvexHull::create, NotFinite for a
/// non-finite motion ("motion"), OutOfRange for max_angle_step <= 0 ("options.max_angle_step").
/// O(n V log(n V)).
Result<ConvexHull> swept_hull(std::span<const Vec3> local_points, const Motion& motion,
                              const SweepOptions& options = {});
/// swept_hull of a convex hull's vertices.
Result<ConvexHull> swept_hull(const ConvexHull& hull, const Motion& motion, const SweepOptions& options = {});
/// swept_hull of a box's 8 corners.
Result<ConvexHull> swept_box(const Box& box, const Motion& motion, const SweepOptions& options = {});

}  // namespace proxima
