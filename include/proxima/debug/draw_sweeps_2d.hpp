#pragma once
/// @file draw_sweeps_2d.hpp
/// Emitters of 2D continuous detection at z = 0, drawn as the 3D ones are (draw_sweeps.hpp):
/// a shape along its motion (at t = 0, at the time of impact, at t = 1, and the path of its
/// origin), and a time-of-impact answer's contact point and normal. World frame.
#include <proxima/core/debug_draw.hpp>
#include <proxima/d2/shape.hpp>
#include <proxima/d2/time_of_impact.hpp>
#include <proxima/debug/draw_sweeps.hpp>

#include <optional>

namespace proxima::debug {

/// Draws `shape` moving by `motion` (t in [0, 1]): its fill and outline (draw_shape_2d, with
/// options.tessellation.segments per turn) at t = 0 and t = 1 (faded: alpha / 3) and at `toi`
/// when given (clamped to [0, 1]; full colour), and the path of its origin as
/// options.path_samples lines (clamped to [1, 1024]); everything tagged {Sweeps, 0}.
void draw_sweep_2d(DebugDraw& sink, const d2::Shape& shape, const d2::Motion& motion, std::optional<Real> toi,
                   const SweepDrawOptions& options = {});

/// Draws a time of impact between A (moving by motion_a) and B (motion_b): both sweeps (B in
/// grey) with the impact time when `result` is a Hit or InitiallyOverlapping, and then the
/// contact point ({Contacts, 0} marker) and the normal from A to B ({Normals, 0} line of
/// `normal_length`, length units).
void draw_time_of_impact_2d(DebugDraw& sink, const d2::Shape& shape_a, const d2::Motion& motion_a,
                            const d2::Shape& shape_b, const d2::Motion& motion_b, const d2::ToiResult& result,
                            Real normal_length = Real(0.25), const SweepDrawOptions& options = {});

}  // namespace proxima::debug
