#pragma once
/// @file time_of_impact.hpp
/// Certified time of impact and shape casts in the plane, with the 3D contract
/// (ccd/time_of_impact.hpp): on [0, t_lower] the shapes are apart by more than the target
/// distance (proved by a bound on their closing speed, never sampled); at t_upper they are
/// within target + tolerance (measured by the narrow phase). `toi` is t_upper.
///
/// The t = 0 contract: penetrating deeper than the tolerance at t = 0 gives
/// InitiallyOverlapping (toi 0, depth, push-out normal from A to B); within target +
/// tolerance and approaching gives Hit at 0; within reach and not approaching (the certified
/// closing speed along the normal is at most the tolerance per unit time) gives Separated.
///
/// Chains take part segment by segment and one-sided, as in contacts: a segment is ignored
/// when the other shape's vertex centroid starts behind it.

#include <proxima/ccd/time_of_impact.hpp>
#include <proxima/core/result.hpp>
#include <proxima/d2/contact.hpp>
#include <proxima/d2/shape.hpp>

#include <optional>

namespace proxima::d2 {

using proxima::CcdStatus;

/// A rigid motion over t in [0, 1]: the position moves linearly by `translation`, the angle
/// turns linearly by `rotation` radians about the local origin (any magnitude: 3 turns are
/// 3 turns, unlike the end pose alone).
struct Motion {
  Pose start{};               ///< pose at t = 0
  Vec2 translation{Real(0)};  ///< displacement of the origin over [0, 1]
  Real rotation = Real(0);    ///< turn over [0, 1], radians, counter-clockwise
  /// The pose at time t.
  Pose at(Real t) const {
    return {start.position + t * translation, start.rotation * Rotation::from_angle(t * rotation)};
  }
  /// The motion from `start` to `end` with the shorter turn (|rotation| <= pi).
  static Motion between(const Pose& start, const Pose& end) {
    return {start, end.position - start.position, (start.rotation.inverse() * end.rotation).angle()};
  }
  /// A pure translation.
  static Motion translating(const Pose& start, const Vec2& translation) { return {start, translation, Real(0)}; }
};

/// Options of time_of_impact (the 3D ones: target distance, tolerance with the pair's
/// precision floor, iteration cap).
using ToiOptions = proxima::ToiOptions;

/// Answer of time_of_impact. Points and normals are in the world frame at t = toi.
struct ToiResult {
  CcdStatus status = CcdStatus::Separated;
  Real toi = Real(1);             ///< Hit: t_upper; MaxIterations: t_lower; InitiallyOverlapping: 0; Separated: 1
  Real t_lower = Real(1);         ///< apart by more than target_distance on [0, t_lower]
  Real t_upper = Real(1);         ///< Hit: within target_distance + tolerance at t_upper (else 1)
  Real distance = Real(0);        ///< Hit and InitiallyOverlapping: signed distance at toi
  Real depth = Real(0);           ///< InitiallyOverlapping: penetration depth at t = 0 (> 0)
  Vec2 point{Real(0)};            ///< midway between point_a and point_b
  Vec2 point_a{Real(0)};          ///< nearest point of A at toi
  Vec2 point_b{Real(0)};          ///< nearest point of B at toi
  Vec2 normal{Real(1), Real(0)};  ///< unit, from A to B
  int iterations = 0;             ///< distance queries made
  PartIndex part_a = -1;          ///< chain segment of A at the contact
  PartIndex part_b = -1;          ///< chain segment of B at the contact
};

/// First time in [0, 1] at which A moving along `motion_a` and B along `motion_b` come
/// within options.target_distance, by conservative advancement (Mirtich 1996): each step
/// measures the signed distance d and normal n and advances by (d - target) / mu, where mu
/// bounds the closing speed along n: the relative velocity of the origins along n plus
/// |rotation| times each shape's reach from its origin. Any pair of kinds (chains per
/// segment). Errors name the field: "motion_a.start" / "motion_b.start" (not finite),
/// "motion_a.translation", "motion_a.rotation" (the same for b), and the options' fields as
/// in 3D ("options.target_distance", "options.tolerance", "options.max_iterations").
Result<ToiResult> time_of_impact(const Shape& a, const Motion& motion_a, const Shape& b, const Motion& motion_b,
                                 const ToiOptions& options = {});

/// Shape cast (as ccd/shape_cast.hpp in 3D): A at `pose_a` translated by `translation` (t in
/// [0, 1] along it) against B resting at `pose_b`; time_of_impact with those two motions
/// (errors name "motion_a.translation" for the translation).
Result<ToiResult> shape_cast(const Shape& a, const Pose& pose_a, const Vec2& translation, const Shape& b,
                             const Pose& pose_b, const ToiOptions& options = {});

}  // namespace proxima::d2
