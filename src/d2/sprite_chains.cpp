/// @file sprite_chains.cpp
/// A mask's outline as closed chains in a body frame.
///
/// Steps: (1) the outline loops of the mask (marching squares, simplified; mask_outline.cpp),
/// in pixel corners with y down; (2) each vertex moved to the body frame: centred on the mask,
/// y flipped, scaled by the pixel size; (3) the flip turns every loop round, so each loop's
/// order is reversed to keep the solid on its left; (4) one closed Chain per loop.

#include <proxima/core/validate.hpp>
#include <proxima/d2/mask_outline.hpp>
#include <proxima/d2/sprite_chains.hpp>

#include <algorithm>
#include <cmath>

namespace proxima::d2 {

Result<std::vector<Chain>> sprite_chains(const SpriteMask& mask, double tolerance, Real pixel_size) {
  if (auto e = validate::positive(pixel_size, "pixel_size")) return *e;
  if (!std::isfinite(tolerance)) return Error{ErrorCode::NotFinite, "tolerance", "must be finite"};
  const Real half_w = Real(0.5) * static_cast<Real>(mask.width());
  const Real half_h = Real(0.5) * static_cast<Real>(mask.height());
  std::vector<Chain> chains;
  for (OutlineLoop loop : mask_outline(mask, tolerance)) {
    for (Vec2& p : loop) p = {(p.x - half_w) * pixel_size, (half_h - p.y) * pixel_size};
    std::reverse(loop.begin(), loop.end());
    auto chain = Chain::create(loop, true);
    if (!chain) return chain.error();
    chains.push_back(std::move(chain).value());
  }
  return chains;
}

}  // namespace proxima::d2
