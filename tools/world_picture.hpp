#pragma once
// A PNG or SVG picture of a collision world as it is now (the demos' pictures): the world
// recorded as a one-step capture in memory (a 3D world by debug::CaptureRecorder, a 2D one
// by debug::CaptureRecorder2D, drawn at z = 0) and drawn by `proxima render`'s renderer.
#include <proxima/core/result.hpp>
#include <proxima/d2/collision_world.hpp>
#include <proxima/debug/capture_recorder.hpp>
#include <proxima/debug/draw_world_2d.hpp>
#include <proxima/world/collision_world.hpp>

#include <optional>
#include <span>
#include <string>

#include "capture_render.hpp"

namespace proxima::tool {

/// Writes the picture of `world` after its last step to `path` (.png or .svg): objects,
/// contacts and `extra` (may be null) drawn as `proxima render` draws a capture's step,
/// seen by `camera` when given (else options.view fitted to the scene). Errors as
/// render_file's.
std::optional<Error> write_world_picture(const CollisionWorld& world, const std::string& path,
                                         const RenderOptions& options,
                                         const std::optional<debug::CaptureCamera>& camera = std::nullopt,
                                         const DrawBuffer* extra = nullptr);

/// Writes the picture of 2D `world` after its last step to `path` (.png or .svg): its
/// objects, contacts and impacts, and `extra` (may be null), all in the plane z = 0 as
/// debug::CaptureRecorder2D records them with `capture` (its camera when given, else from
/// above, fitted to the drawing; how contacts are drawn). Errors as render_file's.
std::optional<Error> write_world_picture_2d(const d2::CollisionWorld& world, const std::string& path,
                                            const RenderOptions& options, const debug::CaptureOptions& capture = {},
                                            const DrawBuffer* extra = nullptr);

}  // namespace proxima::tool
