#pragma once
/// @file draw_rays.hpp
/// Emitters of scene queries: a ray (to its first hit, or its full extent when it misses),
/// its hits as markers and their normals. World frame.
#include <proxima/core/debug_draw.hpp>
#include <proxima/geometry/ray.hpp>
#include <proxima/world/scene_query.hpp>

#include <optional>
#include <span>

namespace proxima::debug {

/// How rays are drawn.
struct RayDrawOptions {
  Rgba ray_color{255, 255, 255, 255};   ///< the ray
  Rgba miss_color{128, 128, 128, 255};  ///< a ray that hit nothing
  Rgba hit_color{0, 255, 128, 255};     ///< hit markers and normals
  Real normal_length = Real(0.25);      ///< length of the drawn normals (length units)
  Real point_size = Real(6);            ///< marker diameter, pixels
};

/// Draws `ray` over [0, max_t] (a non-finite max_t: over [0, 1]) and its hit when given: the
/// ray as one line up to the hit (or to its end, in miss_color), a marker at the hit and its
/// normal, all tagged {Queries, 0}.
void draw_ray(DebugDraw& sink, const Ray& ray, Real max_t, const std::optional<RayHit>& hit,
              const RayDrawOptions& options = {});

/// Draws `ray` over [0, max_t] and every world hit (a marker per hit and the normal), the
/// ray drawn to the farthest hit (or its end when `hits` is empty), tagged {Queries, 0}.
void draw_world_hits(DebugDraw& sink, const Ray& ray, Real max_t, std::span<const WorldHit> hits,
                     const RayDrawOptions& options = {});

}  // namespace proxima::debug
