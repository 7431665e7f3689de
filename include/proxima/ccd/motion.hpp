#pragma once
/// @file motion.hpp
/// Motion: a rigid motion over one time step, and the bound on how fast any point of a
/// shape can move along it.
///
/// The model (the W6 workload's, FCL's InterpMotion, Bullet's integrateTransform): over
/// t in [0, 1] the local origin moves linearly from start to end position, and the rotation
/// turns at constant angular velocity about a fixed world axis by the shortest arc
/// (q(t) = slerp(q0, q1, t)). A point x of the shape (local frame) is at
///     p(t) = p0 + t (p1 - p0) + R(t) x,
/// and its velocity is v + w x (R(t) x), with v = p1 - p0 and w = angle * axis (world) both
/// constant. So every point within radius r of the local origin moves at speed at most
/// |v| + |w| r, and its velocity along a fixed unit direction n is at most
/// n.v + |n x w| r (the rotational part is n.(w x y) = y.(n x w), |y| <= r).
#include <proxima/core/math.hpp>
#include <proxima/core/result.hpp>
#include <proxima/core/transform.hpp>

#include <optional>
#include <string_view>

namespace proxima {

/// A rigid motion from `start` (t = 0) to `end` (t = 1), both local-to-world placements.
struct Motion {
  Transform start;  ///< placement at t = 0
  Transform end;    ///< placement at t = 1

  /// A motion that stays at `pose` (start = end): a static shape.
  static Motion stationary(const Transform& pose) { return {pose, pose}; }
  /// The motion over `dt` seconds of a body at `pose` with constant linear velocity
  /// `linear` (world, length units per second) of its origin and angular velocity `angular`
  /// (world, radians per second): end = (pose.position + linear dt, exp(angular dt) q).
  /// Parameter t of the motion is time / dt. Rotations of more than pi over the step are
  /// folded to the shortest arc by the model, so keep |angular| dt below pi.
  static Motion from_velocity(const Transform& pose, const Vec3& linear, const Vec3& angular, Real dt);

  /// The placement at `t` in [0, 1]: position start + t (end - start), rotation slerp
  /// (shortest arc) from start to end.
  Transform at(Real t) const;
  /// Angle in radians, in [0, pi], of the rotation from start to end along the slerp path.
  Real rotation_angle() const;
  /// True when start and end rotations are equal (q or -q): the motion is a translation.
  bool is_translation() const;
  /// Displacement of the origin, end.position - start.position (its constant velocity in
  /// length units per unit t).
  Vec3 displacement() const { return end.position - start.position; }
  /// Angular velocity in radians per unit t, world frame: the axis of the shortest-arc
  /// rotation from start to end times its angle (zero for a translation).
  Vec3 angular_velocity() const;
};

/// Checks a motion at an API boundary: finite positions (|x| <= kMaxCoordinate) and unit
/// quaternions (|1 - |q|| <= 1e-3). Empty when acceptable, else the Error naming the field:
/// "<name>.start.rotation", "<name>.end.position" ...
std::optional<Error> validate_motion(const Motion& motion, std::string_view name);

/// Upper bound of the speed, along the unit direction `n`, of any point within `radius` of
/// the origin of a shape moving with origin velocity `linear` and angular velocity
/// `angular`: n.linear + |n x angular| radius. Valid over the whole step (v and w are
/// constant). An infinite radius with a zero cross product gives n.linear.
Real directional_speed_bound(const Vec3& n, const Vec3& linear, const Vec3& angular, Real radius);

}  // namespace proxima
