#pragma once
// A PNG or SVG picture of a collision world as it is now (the demos' pictures): the world
// recorded as a one-step capture in memory and drawn by `proxima render`'s renderer.
#include <proxima/core/result.hpp>
#include <proxima/debug/capture_recorder.hpp>
#include <proxima/world/collision_world.hpp>

#include <optional>
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

}  // namespace proxima::tool
