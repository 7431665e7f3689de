/// @file sprite_overlap_turned.cpp
/// Overlap of a placed mask A with a turned, scaled mask B by W9's rule of
/// shared/bench/FORMATS.md (restated in sprite_overlap.hpp), evaluated exactly as written,
/// in double.
///
/// Steps:
///   1. the axis-aligned box of B's turned, scaled set rectangle, widened by a pixel
///      (turned_bounds), and A's set rectangle bound the screen rows and columns to visit;
///   2. per screen row, the column of B that the rule maps pixel X to is a monotonic
///      function of X (each rounded operation is monotonic), and so is the row of B: the
///      pixels that map into B's set rectangle form one span of X. Its ends are found by
///      evaluating the rule itself, starting from the analytic solution of the rule for the
///      rectangle's edges (gallop from the guess, then bisect), so the span is exact;
///   3. A's set pixels in the span (walked word by word, lowest bit first) are mapped by the
///      rule and looked up in B.
/// Pixels are visited in increasing (Y, X), so the first hit is the smallest.

#include <proxima/d2/sprite_overlap.hpp>

#include <algorithm>
#include <bit>
#include <cmath>

namespace proxima::d2 {
namespace {

/// Half-open column range [x0, x1) of one screen row.
struct Span {
  std::int64_t x0 = 0;  ///< first column
  std::int64_t x1 = 0;  ///< one past the last column
};

/// B's placement and set rectangle in the terms of the rule.
class TurnedRule {
 public:
  TurnedRule(const SpriteMask& b, const TurnedPlacement& p)
      : c_(p.cos()),
        s_(p.sin()),
        scale_(p.scale()),
        half_w_(b.width() / 2.0),
        half_h_(b.height() / 2.0),
        cx_(static_cast<double>(p.position().x) + b.width() / 2.0),
        cy_(static_cast<double>(p.position().y) + b.height() / 2.0),
        set_(b.bounds()) {}

  /// Prepares row Y: dy and its two products, as the rule computes them.
  void start_row(std::int64_t y) {
    const double dy = (static_cast<double>(y) + 0.5) - cy_;
    s_dy_ = s_ * dy;
    c_dy_ = c_ * dy;
  }
  /// Column of B that pixel X of the current row maps to: floor(u + wB / 2), in double.
  double column(std::int64_t x) const {
    const double dx = (static_cast<double>(x) + 0.5) - cx_;
    const double u = (c_ * dx + s_dy_) / scale_;
    return std::floor(u + half_w_);
  }
  /// Row of B that pixel X of the current row maps to: floor(v + hB / 2), in double.
  double row(std::int64_t x) const {
    const double dx = (static_cast<double>(x) + 0.5) - cx_;
    const double v = (-s_ * dx + c_dy_) / scale_;
    return std::floor(v + half_h_);
  }
  /// The columns of the current row, within `limits`, that map into B's set rectangle.
  Span span(Span limits) const;

 private:
  template <class Map>
  Span span_of(Span limits, Map map, double slope, double offset, double half, std::int64_t lo, std::int64_t hi) const;

  double c_, s_, scale_, half_w_, half_h_, cx_, cy_;
  PixelRect set_;
  double s_dy_ = 0, c_dy_ = 0;
};

/// The smallest X in [x0, x1] with pred(X) true, x1 when none in [x0, x1); pred must be
/// monotonic (false, then true). Starts at `guess`, gallops, then bisects.
template <class Pred>
std::int64_t first_true(Pred pred, std::int64_t x0, std::int64_t x1, std::int64_t guess) {
  if (x0 >= x1) return x1;
  guess = std::clamp(guess, x0, x1 - 1);
  std::int64_t known_false = x0 - 1, known_true = x1;
  if (pred(guess)) {
    known_true = guess;
    for (std::int64_t step = 1; known_true - step >= x0; step *= 2) {
      if (!pred(known_true - step)) {
        known_false = known_true - step;
        break;
      }
      known_true -= step;
    }
  } else {
    known_false = guess;
    for (std::int64_t step = 1; known_false + step < x1; step *= 2) {
      if (pred(known_false + step)) {
        known_true = known_false + step;
        break;
      }
      known_false += step;
    }
  }
  while (known_true - known_false > 1) {
    const std::int64_t mid = known_false + (known_true - known_false) / 2;
    (pred(mid) ? known_true : known_false) = mid;
  }
  return known_true;
}

/// ceil(x) clamped to [lo, hi]; lo when x is not finite.
std::int64_t clamped_ceil(double x, std::int64_t lo, std::int64_t hi) {
  if (!std::isfinite(x)) return lo;
  return static_cast<std::int64_t>(std::clamp(std::ceil(x), static_cast<double>(lo), static_cast<double>(hi)));
}

/// The columns X in `limits` where lo <= map(X) < hi, for map(X) = floor((slope dx +
/// offset) / scale + half) with dx = X + 0.5 - cx: monotonic, increasing when slope >= 0.
template <class Map>
Span TurnedRule::span_of(Span limits, Map map, double slope, double offset, double half, std::int64_t lo,
                         std::int64_t hi) const {
  const auto edge = [&](std::int64_t value) {  // the X where map reaches `value`, unrounded
    if (slope == 0) return limits.x0;
    return clamped_ceil(cx_ - 0.5 + ((static_cast<double>(value) - half) * scale_ - offset) / slope, limits.x0,
                        limits.x1);
  };
  const auto at_least = [&](std::int64_t value) {
    return first_true([&](std::int64_t x) { return map(x) >= static_cast<double>(value); }, limits.x0, limits.x1,
                      edge(value));
  };
  const auto below = [&](std::int64_t value) {
    return first_true([&](std::int64_t x) { return map(x) < static_cast<double>(value); }, limits.x0, limits.x1,
                      edge(value));
  };
  if (slope >= 0) return {at_least(lo), at_least(hi)};
  return {below(hi), below(lo)};
}

Span TurnedRule::span(Span limits) const {
  const Span by_column = span_of(
      limits, [&](std::int64_t x) { return column(x); }, c_, s_dy_, half_w_, set_.x0, set_.x1);
  const Span by_row = span_of(
      limits, [&](std::int64_t x) { return row(x); }, -s_, c_dy_, half_h_, set_.y0, set_.y1);
  return {std::max(by_column.x0, by_row.x0), std::min(by_column.x1, by_row.x1)};
}

/// Calls visit(X, Y) for every screen pixel set in A and in the turned B, in increasing
/// (Y, X), until visit returns true.
template <class Visit>
void for_each_common_pixel(const SpriteMask& a, PixelPoint pa, const SpriteMask& b, const TurnedPlacement& pb,
                           Visit visit) {
  const PixelRect& set_a = a.bounds();
  const PixelRect box =
      intersection({set_a.x0 + pa.x, set_a.y0 + pa.y, set_a.x1 + pa.x, set_a.y1 + pa.y}, turned_bounds(b, pb));
  if (box.is_empty()) return;
  TurnedRule rule(b, pb);
  for (std::int64_t y = box.y0; y < box.y1; ++y) {
    rule.start_row(y);
    const Span span = rule.span({box.x0, box.x1});
    if (span.x0 >= span.x1) continue;
    const std::uint64_t* row_a = a.row(static_cast<std::int32_t>(y - pa.y));
    const std::int64_t first = span.x0 - pa.x, last = span.x1 - 1 - pa.x;  // A's pixels
    for (std::int64_t k = first >> 6; k <= last >> 6; ++k) {
      std::uint64_t bits = row_a[k];
      if (k == first >> 6) bits &= ~std::uint64_t{0} << (first & 63);
      if (k == last >> 6) bits &= ~std::uint64_t{0} >> (63 - (last & 63));
      for (; bits != 0; bits &= bits - 1) {
        const std::int64_t x = pa.x + 64 * k + std::countr_zero(bits);
        if (!b.get(static_cast<std::int64_t>(rule.column(x)), static_cast<std::int64_t>(rule.row(x)))) continue;
        if (visit(x, y)) return;
      }
    }
  }
}

}  // namespace

PixelRect turned_bounds(const SpriteMask& b, const TurnedPlacement& placement_b) {
  const PixelRect& set = b.bounds();
  if (set.is_empty()) return {};
  const double c = placement_b.cos(), s = placement_b.sin(), scale = placement_b.scale();
  const double cx = static_cast<double>(placement_b.position().x) + b.width() / 2.0;
  const double cy = static_cast<double>(placement_b.position().y) + b.height() / 2.0;
  double x_lo = cx, x_hi = cx, y_lo = cy, y_hi = cy;
  for (const std::int64_t col : {set.x0, set.x1}) {
    for (const std::int64_t row : {set.y0, set.y1}) {
      const double u = static_cast<double>(col) - b.width() / 2.0, v = static_cast<double>(row) - b.height() / 2.0;
      const double x = cx + scale * (c * u - s * v), y = cy + scale * (s * u + c * v);
      x_lo = std::min(x_lo, x), x_hi = std::max(x_hi, x), y_lo = std::min(y_lo, y), y_hi = std::max(y_hi, y);
    }
  }
  const auto low = [](double t) { return static_cast<std::int64_t>(std::floor(t - 0.5)) - 1; };
  const auto high = [](double t) { return static_cast<std::int64_t>(std::ceil(t - 0.5)) + 2; };
  return {low(x_lo), low(y_lo), high(x_hi), high(y_hi)};
}

SpriteOverlap sprite_overlap(const SpriteMask& a, PixelPoint position_a, const SpriteMask& b,
                             const TurnedPlacement& placement_b) {
  SpriteOverlap result;
  for_each_common_pixel(a, position_a, b, placement_b, [&](std::int64_t x, std::int64_t y) {
    if (!result.first) result.first = PixelPoint{x, y};
    ++result.count;
    return false;
  });
  result.overlap = result.count > 0;
  return result;
}

bool sprites_overlap(const SpriteMask& a, PixelPoint position_a, const SpriteMask& b,
                     const TurnedPlacement& placement_b) {
  bool found = false;
  for_each_common_pixel(a, position_a, b, placement_b, [&](std::int64_t, std::int64_t) {
    found = true;
    return true;
  });
  return found;
}

}  // namespace proxima::d2
