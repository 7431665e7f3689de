#pragma once
/// @file sprite_mask.hpp
/// SpriteMask: which pixels of a sprite are solid, one bit per pixel, for pixel-perfect
/// collision (sprite_overlap.hpp) and outlines (mask_outline.hpp).
///
/// Frame: image coordinates, unlike the rest of the 2D module. Pixel (x, y) has x = 0..width-1
/// to the right and y = 0..height-1 down (row 0 is the top row); it covers the unit square
/// [x, x + 1) x [y, y + 1) and its centre is (x + 0.5, y + 0.5). Units are pixels.
///
/// Storage: each row is words_per_row() = ceil(width / 64) 64-bit words; pixel x of a row is
/// bit (x mod 64) of word (x div 64), least significant bit first (pixel 0 is bit 0 of
/// word 0). The bits past `width` in a row's last word (padding) are always 0.

#include <proxima/core/result.hpp>

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace proxima::d2 {

/// Largest width and height of a SpriteMask, in pixels (2^15 = 32768): a full mask then
/// has at most 2^30 pixels (128 MiB of bits).
inline constexpr std::int32_t kMaxSpriteSide = 32768;

/// A rectangle of pixels [x0, x1) x [y0, y1) (half-open, in pixels, integer corners), in
/// the frame its producer names. Empty when x0 >= x1 or y0 >= y1.
struct PixelRect {
  std::int64_t x0 = 0;  ///< first column
  std::int64_t y0 = 0;  ///< first row
  std::int64_t x1 = 0;  ///< one past the last column
  std::int64_t y1 = 0;  ///< one past the last row

  /// True when the rectangle holds no pixel.
  bool is_empty() const { return x0 >= x1 || y0 >= y1; }
  /// Exact equality of the four corners.
  bool operator==(const PixelRect&) const = default;
};

/// The pixels common to two rectangles (empty when they share none).
inline PixelRect intersection(const PixelRect& a, const PixelRect& b) {
  return {a.x0 > b.x0 ? a.x0 : b.x0, a.y0 > b.y0 ? a.y0 : b.y0, a.x1 < b.x1 ? a.x1 : b.x1, a.y1 < b.y1 ? a.y1 : b.y1};
}

/// A range of word indices [first, last) within one row of a SpriteMask.
struct WordRange {
  std::int32_t first = 0;  ///< first word
  std::int32_t last = 0;   ///< one past the last word
};

/// A bit mask of width x height pixels (frame and storage in the file comment). Immutable
/// after construction; its set count and the bounding rectangle of its set pixels are
/// computed once.
class SpriteMask {
 public:
  /// A mask with no pixel set. Width and height in 1..kMaxSpriteSide (fields "width",
  /// "height").
  static Result<SpriteMask> create(std::int32_t width, std::int32_t height);
  /// A mask from text rows, row 0 at the top: '1' = set pixel, '0' = clear. The height is
  /// rows.size() (field "height" when 0 or above kMaxSpriteSide), the width rows[0].size()
  /// (field "width"); every row must have that length (field "rows[i]") and only '0'/'1'
  /// characters (field "rows[i][j]").
  static Result<SpriteMask> from_rows(std::span<const std::string> rows);
  /// A mask from W9 hex rows (shared/bench/FORMATS.md): row y has ceil(width / 4) hex digits
  /// (either case); pixel x is bit 3 - x mod 4 of digit x div 4 (leftmost pixel = most
  /// significant bit). Fields: "width" (1..kMaxSpriteSide), "height" (rows.size(), same
  /// bounds), "rows[i]" (wrong length, or a padding bit set), "rows[i][j]" (not a hex digit).
  static Result<SpriteMask> from_hex_rows(std::int32_t width, std::span<const std::string> rows);
  /// A mask from one alpha byte per pixel, rows top first, `width` bytes per row: pixel
  /// set iff alpha >= alpha_threshold (threshold 0 sets every pixel). Fields "width",
  /// "height", and "pixels" when alpha.size() != width * height.
  static Result<SpriteMask> from_alpha(std::int32_t width, std::int32_t height, std::span<const std::uint8_t> alpha,
                                       std::uint8_t alpha_threshold);
  /// A mask from 8-bit RGBA pixels (4 bytes per pixel in the order R, G, B, A; rows top
  /// first, 4 width bytes per row): pixel set iff its A byte >= alpha_threshold. Fields
  /// "width", "height", and "pixels" when rgba.size() != 4 * width * height.
  static Result<SpriteMask> from_rgba(std::int32_t width, std::int32_t height, std::span<const std::uint8_t> rgba,
                                      std::uint8_t alpha_threshold);

  /// Width in pixels (1..kMaxSpriteSide).
  std::int32_t width() const { return width_; }
  /// Height in pixels (1..kMaxSpriteSide).
  std::int32_t height() const { return height_; }
  /// 64-bit words per row: ceil(width / 64).
  std::int32_t words_per_row() const { return words_per_row_; }
  /// True when pixel (x, y) is set; false outside the mask (any x, y).
  bool get(std::int64_t x, std::int64_t y) const {
    if (x < 0 || y < 0 || x >= width_ || y >= height_) return false;
    return (row(static_cast<std::int32_t>(y))[x >> 6] >> (x & 63)) & 1u;
  }
  /// The words of row y (0 <= y < height): words_per_row() words, layout in the file comment.
  const std::uint64_t* row(std::int32_t y) const {
    return words_.data() + static_cast<std::size_t>(y) * static_cast<std::size_t>(words_per_row_);
  }
  /// The words of row y (0 <= y < height) that hold set pixels: [first, last) word indices,
  /// first == last when the row is clear.
  WordRange row_words(std::int32_t y) const { return row_words_[static_cast<std::size_t>(y)]; }
  /// Number of set pixels.
  std::uint64_t set_count() const { return set_count_; }
  /// The smallest rectangle holding every set pixel, in mask pixels; empty ({0, 0, 0, 0})
  /// when no pixel is set.
  const PixelRect& bounds() const { return bounds_; }
  /// The whole mask: {0, 0, width, height}.
  PixelRect extent() const { return {0, 0, width_, height_}; }

 private:
  SpriteMask(std::int32_t width, std::int32_t height);
  void set_bit(std::int32_t x, std::int32_t y) {
    words_[static_cast<std::size_t>(y) * static_cast<std::size_t>(words_per_row_) + static_cast<std::size_t>(x >> 6)] |=
        std::uint64_t{1} << (x & 63);
  }
  void summarize();
  static Result<SpriteMask> from_alpha_bytes(std::int32_t width, std::int32_t height,
                                             std::span<const std::uint8_t> bytes, std::size_t bytes_per_pixel,
                                             std::uint8_t alpha_threshold);

  std::int32_t width_;
  std::int32_t height_;
  std::int32_t words_per_row_;
  std::vector<std::uint64_t> words_;
  std::vector<WordRange> row_words_;
  std::uint64_t set_count_ = 0;
  PixelRect bounds_{};
};

}  // namespace proxima::d2
