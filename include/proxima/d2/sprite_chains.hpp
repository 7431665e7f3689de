#pragma once
/// @file sprite_chains.hpp
/// A sprite joins the rigid 2D world: its mask's outline (mask_outline.hpp) as closed chains
/// in a body frame, so that a sprite can be a static object of a d2::CollisionWorld and take
/// part in contacts, rays and continuous detection like any level geometry.
///
/// Frame: the body's local frame has its origin at the mask's centre, x to the right, y up
/// (the image's rows are flipped), one pixel = `pixel_size` length units. Each loop is turned
/// so that the solid is on its left: outer boundaries counter-clockwise, holes clockwise, so
/// the chains collide from outside the set pixels (a chain's right side, chain.hpp), holes
/// from inside the hole.

#include <proxima/core/result.hpp>
#include <proxima/d2/chain.hpp>
#include <proxima/d2/sprite_mask.hpp>

#include <vector>

namespace proxima::d2 {

/// The closed chains of a mask's outline, simplified within `tolerance` pixels (0: exact
/// staircase), scaled by `pixel_size` (> 0, field "pixel_size"; tolerance finite, field
/// "tolerance"). An empty mask gives no chain. O(width x height + outline length).
Result<std::vector<Chain>> sprite_chains(const SpriteMask& mask, double tolerance, Real pixel_size);

}  // namespace proxima::d2
