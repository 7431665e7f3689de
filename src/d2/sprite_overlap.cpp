/// @file sprite_overlap.cpp
/// Pixel-perfect overlap of placed sprite masks; the rule is W9's of
/// shared/bench/FORMATS.md (restated in sprite_overlap.hpp).
///
/// Translation only (integer offsets):
///   1. intersect the bounding rectangles of both masks' set pixels on screen; none: done;
///   2. for each common row, AND each of A's words where both rows hold set pixels with
///      the 64 bits of B's row that fall on the same screen pixels (two words of B joined
///      by shifts of the same amount for every word);
///   3. popcount the results; the first non-zero word, lowest bit first, gives the first
///      pixel in (y, x) order.
/// Turned and scaled B:
///   1. the axis-aligned box of B's turned, scaled set rectangle, widened by a pixel, and
///      A's set rectangle bound the screen rows and columns to look at;
///   2. per screen row, the column B's rule maps a pixel centre to is a monotonic function
///      of X (every rounding step is monotonic), and so is the row: the pixels mapping into
///      B's set rectangle form one span, found exactly by evaluating the rule itself from an
///      analytic guess (galloping, then bisection if the guess is off);
///   3. A's set pixels in the span are mapped by the rule, each exactly, and looked up in B.

#include <proxima/d2/sprite_overlap.hpp>

#include <algorithm>
#include <bit>
#include <cmath>
#include <numbers>

namespace proxima::d2 {
namespace {

/// Largest scale of a TurnedPlacement (2^20): B's turned footprint then stays far within
/// the range where the spans below are exact to a pixel.
constexpr double kMaxScale = 1048576.0;

/// Number of set bits: the processor's instruction when the build targets it, else the
/// branch-free SWAR sum (no library call).
inline int count_bits(std::uint64_t x) {
#if defined(__POPCNT__) || !defined(__x86_64__)
  return std::popcount(x);
#else
  x -= (x >> 1) & 0x5555555555555555u;
  x = (x & 0x3333333333333333u) + ((x >> 2) & 0x3333333333333333u);
  x = (x + (x >> 4)) & 0x0f0f0f0f0f0f0f0fu;
  return static_cast<int>((x * 0x0101010101010101u) >> 56);
#endif
}

/// A mask's set rectangle on screen when placed at `position`.
PixelRect placed_bounds(const SpriteMask& mask, PixelPoint position) {
  const PixelRect& r = mask.bounds();
  return {r.x0 + position.x, r.y0 + position.y, r.x1 + position.x, r.y1 + position.y};
}

/// B's bits under A's word k of one row, for a fixed shift: word k + word_shift of B's row
/// shifted down by bit_shift, joined with the next word's low bits (words outside B's
/// non-zero range read as 0).
class ShiftedRow {
 public:
  ShiftedRow(const std::uint64_t* row, WordRange range, std::int64_t shift)
      : row_(row), range_(range), word_shift_(shift >> 6), bit_shift_(static_cast<int>(shift & 63)) {}
  /// The first word of A that can meet a non-zero word of B.
  std::int64_t first_a_word() const { return range_.first - word_shift_ - (bit_shift_ != 0 ? 1 : 0); }
  /// One past the last such word of A.
  std::int64_t last_a_word() const { return range_.last - word_shift_; }
  /// The 64 bits of B under A's word k.
  std::uint64_t under(std::int64_t k) const {
    const std::uint64_t low = word(k + word_shift_);
    if (bit_shift_ == 0) return low;
    return (low >> bit_shift_) | (word(k + word_shift_ + 1) << (64 - bit_shift_));
  }

 private:
  std::uint64_t word(std::int64_t index) const {
    return index >= range_.first && index < range_.last ? row_[index] : 0;
  }
  const std::uint64_t* row_;
  WordRange range_;
  std::int64_t word_shift_;
  int bit_shift_;
};

/// Calls visit(Y, x_of_bit_0, common_bits) for every non-zero AND of A's words with B's
/// aligned bits, rows then words in increasing order, until visit returns true. Per row,
/// only the words where both rows hold set pixels are visited.
template <class Visit>
void for_each_common_word(const SpriteMask& a, PixelPoint pa, const SpriteMask& b, PixelPoint pb, Visit visit) {
  const PixelRect common = intersection(placed_bounds(a, pa), placed_bounds(b, pb));
  if (common.is_empty()) return;
  const std::int64_t shift = pa.x - pb.x;  // B's pixel under A's pixel x is x + shift
  for (std::int64_t y = common.y0; y < common.y1; ++y) {
    const auto ya = static_cast<std::int32_t>(y - pa.y), yb = static_cast<std::int32_t>(y - pb.y);
    const std::uint64_t* row_a = a.row(ya);
    const ShiftedRow row_b(b.row(yb), b.row_words(yb), shift);
    const std::int64_t first = std::max<std::int64_t>(a.row_words(ya).first, row_b.first_a_word());
    const std::int64_t last = std::min<std::int64_t>(a.row_words(ya).last, row_b.last_a_word());
    for (std::int64_t k = first; k < last; ++k) {
      const std::uint64_t both = row_a[k] & row_b.under(k);
      if (both != 0 && visit(y, pa.x + 64 * k, both)) return;
    }
  }
}

}  // namespace

TurnedPlacement::TurnedPlacement(PixelPoint position, double angle_radians, double scale)
    : position_(position), cos_(std::cos(angle_radians)), sin_(std::sin(angle_radians)), scale_(scale) {}

Result<TurnedPlacement> TurnedPlacement::from_radians(PixelPoint position, double angle_radians, double scale) {
  if (std::max(std::abs(position.x), std::abs(position.y)) > kMaxSpritePosition) {
    return make_error(ErrorCode::OutOfRange, "position", "must have |x|, |y| <= 2^40");
  }
  if (!std::isfinite(angle_radians)) return make_error(ErrorCode::NotFinite, "angle_radians", "must be finite");
  if (!std::isfinite(scale)) return make_error(ErrorCode::NotFinite, "scale", "must be finite");
  if (!(scale > 0)) return make_error(ErrorCode::NonPositive, "scale", "must be > 0");
  if (scale > kMaxScale) return make_error(ErrorCode::OutOfRange, "scale", "must be <= 2^20");
  return TurnedPlacement(position, angle_radians, scale);
}

Result<TurnedPlacement> TurnedPlacement::create(PixelPoint position, double angle_degrees, double scale) {
  if (!std::isfinite(angle_degrees)) return make_error(ErrorCode::NotFinite, "angle_degrees", "must be finite");
  return from_radians(position, angle_degrees * std::numbers::pi / 180.0, scale);
}

SpriteOverlap sprite_overlap(const SpriteMask& a, PixelPoint position_a, const SpriteMask& b, PixelPoint position_b) {
  SpriteOverlap result;
  for_each_common_word(a, position_a, b, position_b, [&](std::int64_t y, std::int64_t x, std::uint64_t both) {
    if (!result.first) result.first = PixelPoint{x + std::countr_zero(both), y};
    result.count += static_cast<std::uint64_t>(count_bits(both));
    return false;
  });
  result.overlap = result.count > 0;
  return result;
}

bool sprites_overlap(const SpriteMask& a, PixelPoint position_a, const SpriteMask& b, PixelPoint position_b) {
  bool found = false;
  for_each_common_word(a, position_a, b, position_b, [&](std::int64_t, std::int64_t, std::uint64_t) {
    found = true;
    return true;
  });
  return found;
}

}  // namespace proxima::d2
