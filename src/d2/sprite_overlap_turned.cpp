/// @file sprite_overlap_turned.cpp
/// Overlap of a placed mask A with a turned, scaled mask B by W9's rule of
/// shared/bench/FORMATS.md (restated in sprite_overlap.hpp), evaluated exactly as written,
/// in double.
///
/// Steps:
///   1. the axis-aligned box of B's turned, scaled set rectangle, widened by a pixel
///      (turned_bounds), and A's set rectangle bound the screen rows and columns to visit;
///   2. per screen row, the pixels whose centres map into B's set rectangle form one span
///      of X (the map is affine); its ends are solved from the rule analytically and
///      widened by two pixels, so that rounding cannot leave a pixel out;
///   3. A's set pixels in the span (walked word by word, lowest bit first) are mapped and
///      looked up in B. The map is computed with a multiplication by 1 / scale, and with the
///      rule's own division (exactly as written) whenever the product lands within 1e-7 of
///      a pixel edge: the two differ by far less than that, so every pixel gets the rule's
///      answer.
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

/// Distance to the nearest integer below which the fast mapping defers to the rule itself.
constexpr double kNearEdge = 1e-7;

/// B's placement and set rectangle in the terms of the rule.
class TurnedRule {
 public:
  TurnedRule(const SpriteMask& b, const TurnedPlacement& p)
      : c_(p.cos()),
        s_(p.sin()),
        scale_(p.scale()),
        inverse_scale_(1.0 / p.scale()),
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

  /// The columns of the current row, within `limits`, whose centres can map into B's set
  /// rectangle: the analytic solution of the rule for the rectangle's edges, widened by
  /// two pixels (more where the map is nearly flat) so that rounding cannot leave one out.
  Span span(Span limits) const {
    const Span by_column = span_of(limits, c_, s_dy_, half_w_, set_.x0, set_.x1);
    const Span by_row = span_of(limits, -s_, c_dy_, half_h_, set_.y0, set_.y1);
    return {std::max(by_column.x0, by_row.x0), std::min(by_column.x1, by_row.x1)};
  }

  /// True when the rule maps pixel X of the current row to a set pixel of B. The map is
  /// first computed with a multiplication by 1 / scale; when that lands within kNearEdge
  /// of a pixel edge, the rule's own division decides.
  bool covers(const SpriteMask& b, std::int64_t x) const {
    const double dx = (static_cast<double>(x) + 0.5) - cx_;
    const double p = c_ * dx + s_dy_, q = -s_ * dx + c_dy_;
    const std::int64_t col = fast_floor(p * inverse_scale_ + half_w_, b.width(), p, half_w_);
    const std::int64_t row = fast_floor(q * inverse_scale_ + half_h_, b.height(), q, half_h_);
    return b.get(col, row);
  }

 private:
  /// floor(t) for t = p / scale + half when it is in [0, side), else -1. `t` is that
  /// value computed with 1 / scale: it is within 1e-10 of the rule's value whenever that
  /// value is anywhere near [0, side].
  std::int64_t fast_floor(double t, std::int32_t side, double p, double half) const {
    if (!(t >= -0.5 && t < side + 0.5)) return -1;
    const std::int64_t whole = static_cast<std::int64_t>(t + 1.0) - 1;
    const double fraction = t - static_cast<double>(whole);
    if (fraction < kNearEdge || fraction > 1.0 - kNearEdge)
      return static_cast<std::int64_t>(std::floor(p / scale_ + half));
    return whole;
  }

  /// The columns X in `limits` where lo <= floor((slope dx + offset) / scale + half) < hi
  /// can hold, dx = X + 0.5 - cx, widened by the margin of span().
  Span span_of(Span limits, double slope, double offset, double half, std::int64_t lo, std::int64_t hi) const {
    if (std::abs(slope) < 1e-12) return limits;  // nearly flat: the whole row may map inside
    const auto edge = [&](std::int64_t value) {
      return cx_ - 0.5 + ((static_cast<double>(value) - half) * scale_ - offset) / slope;
    };
    const double a = edge(lo), b = edge(hi), margin = 2.0 + 1e-6 * scale_ / std::abs(slope);
    const auto clamp = [&](double x) {
      return static_cast<std::int64_t>(std::clamp(x, static_cast<double>(limits.x0), static_cast<double>(limits.x1)));
    };
    return {clamp(std::floor(std::min(a, b) - margin)), clamp(std::ceil(std::max(a, b) + margin))};
  }

  double c_, s_, scale_, inverse_scale_, half_w_, half_h_, cx_, cy_;
  PixelRect set_;
  double s_dy_ = 0, c_dy_ = 0;
};

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
        if (rule.covers(b, x) && visit(x, y)) return;
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
