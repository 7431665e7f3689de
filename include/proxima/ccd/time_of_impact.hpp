#pragma once
/// @file time_of_impact.hpp
/// Certified time of impact of two moving geometries of any kind (convex shapes, half-spaces,
/// triangle meshes, compounds), each moving along its own Motion over t in [0, 1].
///
/// The answer comes with a certificate: on [0, t_lower] the shapes are apart by more than
/// the target distance (proved by the motion bound of motion.hpp, never sampled), and at
/// t_upper they are within target distance + tolerance (measured by the narrow phase's
/// distance, an upper bound from two surface points). `toi` is t_upper.
///
/// The t = 0 contract (docs/conventions.md):
///   - overlapping at t = 0 (penetration deeper than the tolerance): InitiallyOverlapping,
///     toi 0, with the depth and the minimum-translation normal (from A to B);
///   - within target + tolerance at t = 0 and approaching: Hit at t = 0;
///   - within target + tolerance at t = 0 and not approaching (the certified closing speed
///     along the normal, in length per step, is at most the tolerance): Separated.
#include <proxima/ccd/motion.hpp>
#include <proxima/core/math.hpp>
#include <proxima/core/result.hpp>
#include <proxima/core/sub_shape_id.hpp>
#include <proxima/shapes/shape_ref.hpp>

#include <cstdint>
#include <optional>

namespace proxima {

/// How a continuous query ended (time of impact, shape cast).
enum class CcdStatus : std::uint8_t {
  Hit,                   ///< the shapes come within target distance + tolerance at toi
  Separated,             ///< certified: apart by more than the target distance on all of [0, 1]
  InitiallyOverlapping,  ///< penetrating at t = 0: toi 0, depth and push-out normal given
  MaxIterations,         ///< the iteration cap stopped the search; [t_lower, t_upper] is the bracket
  Failed,                ///< never expected: the distance query could not answer
};

/// Options of time_of_impact.
struct ToiOptions {
  /// Distance (length units, >= 0) whose first reach is the impact: 0 for touching, a contact
  /// skin > 0 for speculative contacts.
  Real target_distance = Real(0);
  /// Length tolerance (> 0): at t_upper the shapes are within target_distance + tolerance.
  /// It is raised to the precision floor of the pair, 64 * epsilon * scale, scale being the
  /// shapes' size plus the reach of their motions after recentring on B (so the accuracy is
  /// relative, whatever the shapes' size or their distance from the origin). 0 picks that
  /// floor.
  Real tolerance = Real(1e-4);
  /// Iteration cap of the conservative advancement (>= 1); reaching it gives MaxIterations.
  /// Most queries take 1 to 20 distance calls; a pair that turns while it grazes (a spinning
  /// compound or mesh, whose bound is the Lipschitz one alone) can take several hundred, and
  /// the independent reference (tests/ccd/test_time_of_impact.cpp) finds every hit of its
  /// sweeps under this cap (with 128, 27 of 90,000 were left at MaxIterations).
  int max_iterations = 1024;
};

/// Answer of time_of_impact. Points and normals are in the world frame at t = toi.
struct ToiResult {
  CcdStatus status = CcdStatus::Separated;
  /// Hit: t_upper; MaxIterations: t_lower (the time proved safe); InitiallyOverlapping: 0;
  /// Separated: 1.
  Real toi = Real(1);
  Real t_lower = Real(1);                  ///< apart by more than target_distance on [0, t_lower]
  Real t_upper = Real(1);                  ///< Hit: within target_distance + tolerance at t_upper (else 1)
  Real distance = Real(0);                 ///< Hit and InitiallyOverlapping: signed distance at toi (length units)
  Real depth = Real(0);                    ///< InitiallyOverlapping: penetration depth at t = 0 (> 0)
  Vec3 point{Real(0)};                     ///< contact point: midway between point_a and point_b
  Vec3 point_a{Real(0)};                   ///< nearest point of A at toi
  Vec3 point_b{Real(0)};                   ///< nearest point of B at toi
  Vec3 normal{Real(0), Real(0), Real(1)};  ///< unit, from A to B (InitiallyOverlapping: push-out of B)
  int iterations = 0;                      ///< distance queries made
  SubShapeId sub_a{};                      ///< part of A at the contact (mesh triangle, compound child)
  SubShapeId sub_b{};                      ///< part of B at the contact
};

/// First time in [0, 1] at which A, moving along `motion_a`, and B, moving along
/// `motion_b`, come within options.target_distance, by conservative advancement (Mirtich,
/// "Impulse-based dynamic simulation of rigid body systems", 1996, ch. 3; Zhang, Redon, Lee,
/// Kim, "Continuous collision detection for articulated models using Taylor models and
/// temporal culling", 2007, for the directional bound): each step measures the distance d
/// and normal n, bounds the closing speed along n by the motion bounds of both geometries,
/// and advances by (d - target) / speed, which is certified not to cross the target.
/// Errors (Result, never an exception): a non-finite or non-unit pose ("motion_a.start.rotation"
/// ...), NotFinite / Negative target_distance ("options.target_distance"), NotFinite /
/// Negative tolerance ("options.tolerance"), max_iterations < 1 ("options.max_iterations").
/// Identical start and end poses are valid: a static overlap test. Any pair of geometry
/// kinds. Two convex shapes whose cores do not turn (translations; spheres and points may
/// spin) are answered by one GJK ray cast (shape_cast.hpp), with the same certificate.
/// Cost: a few distance queries, more for fast rotations of elongated shapes.
Result<ToiResult> time_of_impact(ShapeRef a, const Motion& motion_a, ShapeRef b, const Motion& motion_b,
                                 const ToiOptions& options = {});

/// Checks ToiOptions: empty when acceptable, else the Error naming the field
/// ("options.target_distance", "options.tolerance", "options.max_iterations").
std::optional<Error> validate_toi_options(const ToiOptions& options);

/// Name of a status ("hit", "separated", "initially_overlapping", "max_iterations", "failed").
const char* to_string(CcdStatus status);

}  // namespace proxima
