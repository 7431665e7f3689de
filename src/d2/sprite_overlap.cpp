/// @file sprite_overlap.cpp
/// Pixel-perfect overlap of placed sprite masks; the rule is W9's of
/// shared/bench/FORMATS.md (restated in sprite_overlap.hpp).
///
/// Translation only (integer offsets):
///   1. intersect the bounding rectangles of both masks' set pixels on screen; none: done;
///   2. for each common row, AND each of A's words in the common columns with the 64 bits
///      of B's row that fall on the same screen pixels (two words of B joined by shifts);
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

/// Word `index` of a row of `count` words, 0 outside.
std::uint64_t word_or_zero(const std::uint64_t* row, std::int64_t count, std::int64_t index) {
  return index >= 0 && index < count ? row[index] : 0;
}

/// The 64 bits of a row starting at pixel `first` (any integer; pixels outside are 0):
/// bit i of the result is pixel first + i.
std::uint64_t bits_from(const std::uint64_t* row, std::int64_t count, std::int64_t first) {
  const std::int64_t word = first >> 6;  // floor division (C++20: arithmetic shift)
  const int shift = static_cast<int>(first & 63);
  const std::uint64_t low = word_or_zero(row, count, word);
  if (shift == 0) return low;
  return (low >> shift) | (word_or_zero(row, count, word + 1) << (64 - shift));
}

/// A mask's set rectangle on screen when placed at `position`.
PixelRect placed_bounds(const SpriteMask& mask, PixelPoint position) {
  const PixelRect& r = mask.bounds();
  return {r.x0 + position.x, r.y0 + position.y, r.x1 + position.x, r.y1 + position.y};
}

/// Calls visit(Y, x_of_bit_0, common_bits) for every non-zero AND of A's words with B's
/// aligned bits, rows then words in increasing order, until visit returns true.
template <class Visit>
void for_each_common_word(const SpriteMask& a, PixelPoint pa, const SpriteMask& b, PixelPoint pb, Visit visit) {
  const PixelRect common = intersection(placed_bounds(a, pa), placed_bounds(b, pb));
  if (common.is_empty()) return;
  const std::int64_t first_word = (common.x0 - pa.x) >> 6;
  const std::int64_t last_word = (common.x1 - 1 - pa.x) >> 6;
  const std::int64_t shift = pa.x - pb.x;  // B's pixel under A's pixel x is x + shift
  for (std::int64_t y = common.y0; y < common.y1; ++y) {
    const std::uint64_t* row_a = a.row(static_cast<std::int32_t>(y - pa.y));
    const std::uint64_t* row_b = b.row(static_cast<std::int32_t>(y - pb.y));
    for (std::int64_t k = first_word; k <= last_word; ++k) {
      if (row_a[k] == 0) continue;
      const std::uint64_t both = row_a[k] & bits_from(row_b, b.words_per_row(), 64 * k + shift);
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
    result.count += static_cast<std::uint64_t>(std::popcount(both));
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
