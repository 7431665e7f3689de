#pragma once
/// @file draw_sweeps.hpp
/// Emitters of continuous detection: a shape along its motion over a step (at t = 0, at the
/// time of impact and at t = 1, with the path of its origin), and a time-of-impact answer's
/// contact point and normal. World frame.
#include <proxima/ccd/motion.hpp>
#include <proxima/ccd/time_of_impact.hpp>
#include <proxima/core/debug_draw.hpp>
#include <proxima/debug/tessellate.hpp>
#include <proxima/shapes/shape_ref.hpp>

#include <optional>

namespace proxima::debug {

/// How a sweep is drawn.
struct SweepDrawOptions {
  Rgba color{80, 160, 255, 255};     ///< the shape at the time of impact (at t = 0 and 1: the same, alpha / 3)
  int path_samples = 16;             ///< segments of the origin's path (>= 1; clamped to [1, 1024])
  TessellationOptions tessellation;  ///< how the shape is tessellated
};

/// `color` at a third of its opacity: how a sweep draws its shape at t = 0 and t = 1.
Rgba sweep_end_color(Rgba color);

/// The contact of a time of impact: a red marker at `point` ({Contacts, 0}) and the yellow
/// normal from it, `normal_length` long ({Normals, 0}); world frame.
void draw_impact_point(DebugDraw& sink, const Vec3& point, const Vec3& normal, Real normal_length);

/// Draws `shape` moving by `motion` (t in [0, 1]): its surface at t = 0 and t = 1 (faded),
/// at `toi` when given (clamped to [0, 1]; full colour), all tagged {Sweeps, 0}, and the
/// path of its origin (motion.at(t).position) as `path_samples` lines tagged {Sweeps, 0}.
void draw_sweep(DebugDraw& sink, ShapeRef shape, const Motion& motion, std::optional<Real> toi,
                const SweepDrawOptions& options = {});

/// Draws a time of impact between A (moving by motion_a) and B (motion_b): both sweeps
/// (B in its own colour, faded) with the impact time when `result` is a Hit or
/// InitiallyOverlapping, and then the contact point and the normal from A to B at that time
/// ({Contacts, 0} marker, {Normals, 0} line of `normal_length`).
void draw_time_of_impact(DebugDraw& sink, ShapeRef shape_a, const Motion& motion_a, ShapeRef shape_b,
                         const Motion& motion_b, const ToiResult& result, Real normal_length = Real(0.25),
                         const SweepDrawOptions& options = {});

}  // namespace proxima::debug
