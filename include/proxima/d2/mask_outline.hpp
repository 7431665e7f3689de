#pragma once
/// @file mask_outline.hpp
/// The outline of a sprite mask's set pixels as closed polygons, optionally simplified.
///
/// Frame: the mask's pixel corners, in pixels: point (x, y) is the corner at column x and
/// row y of the image (x to the right, y down; pixel (i, j) is the square [i, i + 1] x
/// [j, j + 1]). Orientation is stated in the math frame that reads these coordinates with
/// y up: outer boundaries run counter-clockwise (positive shoelace area), holes clockwise,
/// so that the signed areas of all loops add up to the set pixel count. On screen (y
/// down) the same loops appear clockwise.

#include <proxima/core/math.hpp>
#include <proxima/d2/sprite_mask.hpp>

#include <vector>

namespace proxima::d2 {

/// One closed loop: its vertices in order; the closing edge from the last vertex back to
/// the first is implied (the first vertex is not repeated).
using OutlineLoop = std::vector<Vec2>;

/// The boundary of the set pixels as closed loops (frame and orientation in the file
/// comment). Set pixels that touch only at a corner belong to separate loops (the set
/// region is taken 4-connected), so a loop never crosses itself or another loop; loops may
/// touch at such corners.
///
/// With tolerance <= 0 the loops are exact: their vertices are the corners of the pixel
/// staircase (no collinear vertices), and their signed areas sum to mask.set_count().
/// With tolerance > 0 (pixels) each loop is simplified by Douglas-Peucker (split at the
/// vertex farthest from the first one): every vertex of the exact loop lies within
/// `tolerance` of the simplified loop, which keeps at least 3 vertices.
///
/// Steps: (1) every edge between a set pixel and a clear one (or the outside) becomes a
/// directed edge with the set pixel on its left; (2) edges are linked into loops, turning
/// left first where two leave one corner (marching squares' saddle rule for a
/// 4-connected set); (3) collinear vertices are dropped; (4) optional simplification.
/// Time O(width x height + boundary length); empty result for an empty mask.
std::vector<OutlineLoop> mask_outline(const SpriteMask& mask, double tolerance = 0);

/// The signed area of a loop by the shoelace formula, in square pixels (positive when
/// counter-clockwise in the math frame of the file comment), accumulated in double.
double signed_area(const OutlineLoop& loop);

}  // namespace proxima::d2
