#pragma once
/// @file draw_rays_2d.hpp
/// Emitters of 2D ray queries at z = 0, drawn as the 3D ones are (draw_rays.hpp): the ray to
/// its hit (or its full extent when it misses), a marker at the hit and its normal.
#include <proxima/core/debug_draw.hpp>
#include <proxima/d2/contact.hpp>
#include <proxima/debug/draw_rays.hpp>

#include <optional>

namespace proxima::debug {

/// Draws `ray` (world frame) over [0, max_t] (a non-finite max_t: over [0, 1]) and its hit
/// when given (d2::raycast's or d2::CollisionWorld::raycast's `hit`), as draw_ray: one line
/// to the hit or, missing, to the end in options.miss_color; a marker and the normal at the
/// hit; all tagged {Queries, 0}.
void draw_ray_2d(DebugDraw& sink, const d2::Ray& ray, Real max_t, const std::optional<d2::RayHit>& hit,
                 const RayDrawOptions& options = {});

}  // namespace proxima::debug
