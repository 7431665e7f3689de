#pragma once
/// @file safe_step.hpp
/// Safe time step: the longest time over which two bodies with constant linear and angular
/// velocities cannot come closer than a target distance ("the largest step that can be
/// simulated with no bullet through paper").
///
/// From the current distance d and normal n (A to B) and the directional motion bound of
/// motion.hpp: every point of a body within radius r of its origin moves along n at most at
/// n.v + |n x w| r, so the gap along n, which bounds the distance from below at every
/// time, closes at most at mu = n.(v_a - v_b) + |n x w_a| r_a + |n x w_b| r_b, and
///     dt = (d - target) / mu        (+infinity when mu <= 0).
/// The kernel (safe_time_step_from_distance) is a handful of flops; safe_time_step adds one
/// narrow-phase distance query; safe_time_steps answers one body against many.
#include <proxima/core/math.hpp>
#include <proxima/core/result.hpp>
#include <proxima/core/transform.hpp>
#include <proxima/shapes/shape_ref.hpp>

#include <span>

namespace proxima {

/// A body's state for safe_time_step: its shape, placement and constant velocities.
struct MovingBody {
  ShapeRef shape;         ///< the geometry (any kind; a half-space must not rotate)
  Transform pose;         ///< placement now
  Vec3 linear{Real(0)};   ///< velocity of the origin, world frame, length units per second
  Vec3 angular{Real(0)};  ///< angular velocity, world frame, radians per second
};

/// The kernel: safe step (seconds) from a separation `gap` (length units, >= the true
/// distance's lower bound) along the unit normal `n` from A to B, the bodies' velocities and
/// the radii about their origins of the points that rotation moves. +infinity when the bodies
/// cannot close along n; 0 when gap <= target. No validation (hot path).
Real safe_time_step_from_distance(Real gap, const Vec3& n, const Vec3& linear_a, const Vec3& angular_a, Real radius_a,
                                  const Vec3& linear_b, const Vec3& angular_b, Real radius_b, Real target_distance);

/// Radius about the local origin of the points of `shape` that a rotation moves (0 for a
/// sphere or a point, the half length of a capsule's core, the farthest vertex of a hull, the
/// farthest box corner otherwise; +infinity for a half-space).
Real rotation_radius(ShapeRef shape);

/// Safe step (seconds, +infinity when the bodies never approach along the current normal)
/// for A and B over which they stay apart by at least `target_distance` (>= 0), from one
/// narrow-phase distance query and the motion bound. 0 when they are already within the
/// target. Errors: non-finite or non-unit poses ("a.pose.rotation" ...), non-finite
/// velocities ("b.linear" ...), negative target ("target_distance").
Result<Real> safe_time_step(const MovingBody& a, const MovingBody& b, Real target_distance = Real(0));

/// safe_time_step of `a` against each of `others`, written to `steps` (same length as
/// `others`; InvalidArgument "steps" otherwise); the same errors, the first bad body named
/// "others[3].pose" .... Nothing is written when an error is returned.
Result<Real> safe_time_steps(const MovingBody& a, std::span<const MovingBody> others, std::span<Real> steps,
                             Real target_distance = Real(0));

}  // namespace proxima
