#pragma once
/// @file shape_cast.hpp
/// Shape casts (linear sweeps): the first fraction t in [0, 1] of a translation at which a
/// moving geometry A comes within a target distance of a still geometry B.
///
/// Two convex shapes: GJK ray casting on the cores with the radii added (gjk_raycast.hpp).
/// A half-space: a closed form along its normal. A triangle mesh or a compound: its
/// hierarchy walked nearest-first with the box of A swept along the translation, each
/// triangle or child cast as above, the least t kept. A mesh or compound that moves against
/// a convex shape is cast the other way round; two non-convex geometries go through
/// time_of_impact with translations.
///
/// The t = 0 contract (docs/conventions.md), per convex pair (so per mesh triangle):
///   - penetrating at t = 0 by more than the tolerance: InitiallyOverlapping, t = 0, with the
///     depth and the push-out normal from A to B;
///   - within target + tolerance at t = 0 and moving in (normal . translation > tolerance):
///     Hit at 0;
///   - within target + tolerance and not moving in: no hit from that pair. So on a mesh, a
///     grazing edge that A slides along never hides a later face hit: candidates are
///     validated before the least t is taken. Likewise a hit on an inactive (flat or
///     concave) mesh edge or corner while A does not move into that triangle's plane is a
///     seam between flat triangles, not a wall, and is dropped.
#include <proxima/ccd/time_of_impact.hpp>
#include <proxima/core/math.hpp>
#include <proxima/core/result.hpp>
#include <proxima/core/sub_shape_id.hpp>
#include <proxima/core/transform.hpp>
#include <proxima/shapes/shape_ref.hpp>

#include <optional>

namespace proxima {

/// Options of shape_cast.
struct CastOptions {
  /// Distance (length units, >= 0) whose first reach is the hit: 0 for touching.
  Real target_distance = Real(0);
  /// Length tolerance (>= 0): at the hit the shapes are within target + tolerance. Raised to
  /// the pair's precision floor as in ToiOptions; 0 picks the floor.
  Real tolerance = Real(1e-4);
  /// Iteration cap of each GJK cast (>= 1).
  int max_iterations = 64;
  /// Meshes: ignore the triangles that A would reach from behind (translation along the
  /// triangle's normal), as a one-sided surface.
  bool cull_back_faces = false;
};

/// Answer of shape_cast. Points and normals are in the world frame, with A at its placement
/// at t.
struct CastResult {
  CcdStatus status = CcdStatus::Separated;  ///< Hit, Separated, InitiallyOverlapping, MaxIterations
  Real t = Real(1);                         ///< fraction of the translation at the hit (0 when overlapping; 1: no hit)
  Real distance = Real(0);                  ///< signed distance at t (length units; -depth when overlapping)
  Real depth = Real(0);                     ///< InitiallyOverlapping: penetration depth (> 0)
  Vec3 point{Real(0)};                      ///< contact point, midway between point_a and point_b
  Vec3 point_a{Real(0)};                    ///< nearest point of A at t
  Vec3 point_b{Real(0)};                    ///< nearest point of B
  Vec3 normal{Real(0), Real(0), Real(1)};   ///< unit, from A to B (overlap: push-out direction of B)
  int iterations = 0;                       ///< GJK iterations over every pair of parts tried
  SubShapeId sub_a{};                       ///< part of A at the hit (mesh triangle, compound child)
  SubShapeId sub_b{};                       ///< part of B at the hit
};

/// Checks CastOptions: empty when acceptable, else the Error naming the field
/// ("options.target_distance", "options.tolerance", "options.max_iterations").
std::optional<Error> validate_cast_options(const CastOptions& options);

/// Casts A, placed at `pose_a`, along `translation` (world, length units) against B at
/// `pose_b`. Errors (Result, never an exception): non-finite or non-unit poses ("pose_a.rotation"
/// ...), non-finite translation ("translation"), negative or non-finite target or tolerance
/// ("options.target_distance", "options.tolerance"), max_iterations < 1. A zero translation
/// is valid (a static test).
Result<CastResult> shape_cast(ShapeRef a, const Transform& pose_a, const Vec3& translation, ShapeRef b,
                              const Transform& pose_b, const CastOptions& options = {});

}  // namespace proxima
