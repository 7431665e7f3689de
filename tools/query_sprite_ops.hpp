#pragma once
// The query operation on sprite masks: sprite_overlap (pixel-perfect overlap of two placed
// masks, B optionally turned and scaled by W9's rule, proxima/d2/sprite_overlap.hpp).
#include "json_values.hpp"

namespace proxima::tool {

/// {"a": {"mask", "position"}, "b": {"mask", "position", "angle_degrees"?, "scale"?}} ->
/// overlap, count (screen pixels set in both), first ([x, y] of the first common pixel in
/// (y, x) order, or null). A mask is {"width", "height", "rows"} ('1' = set, row 0 at the
/// top) or {"png", "alpha_threshold"?} (a PNG file; pixel set iff alpha >= the threshold,
/// 128 when absent).
Json op_sprite_overlap(const Json& request);

}  // namespace proxima::tool
