#pragma once
// Plain per-pixel references for the sprite tests, written from W9's text
// (shared/bench/FORMATS.md) and independent of the word-parallel code: every screen pixel
// of A's rectangle is looked at, one by one, with SpriteMask::get.
#include <proxima/d2/sprite_overlap.hpp>

#include <cmath>
#include <functional>
#include <numbers>
#include <string>
#include <vector>

#include "support/random.hpp"

namespace proxima::test {

/// A mask of w x h pixels whose pixel (x, y) is set iff set(x, y).
inline d2::SpriteMask mask_where(int w, int h, const std::function<bool(int, int)>& set) {
  std::vector<std::string> rows(static_cast<std::size_t>(h), std::string(static_cast<std::size_t>(w), '0'));
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) rows[y][x] = set(x, y) ? '1' : '0';
  }
  return d2::SpriteMask::from_rows(rows).value();
}

/// A random w x h mask: blobs (a disc), noise of the given density, or a thin diagonal,
/// chosen by `kind` (0, 1, 2).
inline d2::SpriteMask random_mask(Random& rng, int w, int h, int kind) {
  if (kind == 0) {
    const double cx = rng.integer(0, w), cy = rng.integer(0, h), r = rng.integer(1, std::max(w, h));
    return mask_where(w, h, [&](int x, int y) { return std::hypot(x + 0.5 - cx, y + 0.5 - cy) <= r; });
  }
  if (kind == 1) {
    const int percent = rng.integer(1, 99);
    return mask_where(w, h, [&](int, int) { return rng.integer(0, 99) < percent; });
  }
  const int step = rng.integer(1, 3);
  return mask_where(w, h, [&](int x, int y) { return (x + step * y) % (w + 1) == 0; });
}

/// W9's count and first common pixel for A at pa and B at pb, translation only.
inline d2::SpriteOverlap reference_overlap(const d2::SpriteMask& a, d2::PixelPoint pa, const d2::SpriteMask& b,
                                           d2::PixelPoint pb) {
  d2::SpriteOverlap out;
  for (std::int64_t y = pa.y; y < pa.y + a.height(); ++y) {
    for (std::int64_t x = pa.x; x < pa.x + a.width(); ++x) {
      if (!a.get(x - pa.x, y - pa.y) || !b.get(x - pb.x, y - pb.y)) continue;
      if (!out.first) out.first = d2::PixelPoint{x, y};
      ++out.count;
    }
  }
  out.overlap = out.count > 0;
  return out;
}

/// W9's rule for B turned by `degrees` and scaled by `scale` at pb, literally as written.
inline d2::SpriteOverlap reference_turned(const d2::SpriteMask& a, d2::PixelPoint pa, const d2::SpriteMask& b,
                                          d2::PixelPoint pb, double degrees, double scale) {
  const double th = degrees * std::numbers::pi / 180.0;
  const double c = std::cos(th), s = std::sin(th);
  const double wb = b.width(), hb = b.height();
  const double cx = static_cast<double>(pb.x) + wb / 2.0, cy = static_cast<double>(pb.y) + hb / 2.0;
  d2::SpriteOverlap out;
  for (std::int64_t y = pa.y; y < pa.y + a.height(); ++y) {
    for (std::int64_t x = pa.x; x < pa.x + a.width(); ++x) {
      if (!a.get(x - pa.x, y - pa.y)) continue;
      const double dx = (static_cast<double>(x) + 0.5) - cx;
      const double dy = (static_cast<double>(y) + 0.5) - cy;
      const double u = (c * dx + s * dy) / scale;
      const double v = (-s * dx + c * dy) / scale;
      const double sx = std::floor(u + wb / 2.0), sy = std::floor(v + hb / 2.0);
      if (!(sx >= 0 && sx < wb && sy >= 0 && sy < hb)) continue;
      if (!b.get(static_cast<std::int64_t>(sx), static_cast<std::int64_t>(sy))) continue;
      if (!out.first) out.first = d2::PixelPoint{x, y};
      ++out.count;
    }
  }
  out.overlap = out.count > 0;
  return out;
}

}  // namespace proxima::test
