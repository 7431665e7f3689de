/// @file sprite_mask.cpp
/// Validated construction of sprite masks from text rows, W9 hex rows and alpha bytes, and
/// the summary (set count, bounding rectangle) computed once per mask.

#include <proxima/d2/sprite_mask.hpp>

#include <algorithm>
#include <bit>
#include <optional>
#include <string>

namespace proxima::d2 {
namespace {

/// The error for a width or height outside 1..kMaxSpriteSide, if it is.
std::optional<Error> check_side(std::int64_t side, const char* field) {
  if (side <= 0) return make_error(ErrorCode::NonPositive, field, "must be > 0");
  if (side > kMaxSpriteSide) {
    return make_error(ErrorCode::OutOfRange, field, "must be <= " + std::to_string(kMaxSpriteSide));
  }
  return std::nullopt;
}

/// The error for the first bad side of width x height, if any.
std::optional<Error> check_size(std::int64_t width, std::int64_t height) {
  if (auto error = check_side(width, "width")) return error;
  return check_side(height, "height");
}

/// Field name "rows[i]" or "rows[i][j]".
std::string row_field(std::size_t i) { return "rows[" + std::to_string(i) + "]"; }
std::string char_field(std::size_t i, std::size_t j) { return row_field(i) + "[" + std::to_string(j) + "]"; }

/// The value 0..15 of a hex digit, or -1.
int hex_value(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

}  // namespace

SpriteMask::SpriteMask(std::int32_t width, std::int32_t height)
    : width_(width),
      height_(height),
      words_per_row_((width + 63) / 64),
      words_(static_cast<std::size_t>(height) * static_cast<std::size_t>((width + 63) / 64), 0) {}

Result<SpriteMask> SpriteMask::create(std::int32_t width, std::int32_t height) {
  if (auto error = check_size(width, height)) return *error;
  return SpriteMask(width, height);
}

Result<SpriteMask> SpriteMask::from_rows(std::span<const std::string> rows) {
  const std::int64_t width = rows.empty() ? 0 : static_cast<std::int64_t>(rows[0].size());
  if (auto error = check_side(static_cast<std::int64_t>(rows.size()), "height")) return *error;
  if (auto error = check_side(width, "width")) return *error;
  SpriteMask mask(static_cast<std::int32_t>(width), static_cast<std::int32_t>(rows.size()));
  for (std::size_t y = 0; y < rows.size(); ++y) {
    if (static_cast<std::int64_t>(rows[y].size()) != width) {
      return make_error(ErrorCode::InvalidArgument, row_field(y), "must have as many characters as rows[0]");
    }
    for (std::size_t x = 0; x < rows[y].size(); ++x) {
      const char c = rows[y][x];
      if (c != '0' && c != '1') return make_error(ErrorCode::InvalidArgument, char_field(y, x), "must be '0' or '1'");
      if (c == '1') mask.set_bit(static_cast<std::int32_t>(x), static_cast<std::int32_t>(y));
    }
  }
  mask.summarize();
  return mask;
}

Result<SpriteMask> SpriteMask::from_hex_rows(std::int32_t width, std::span<const std::string> rows) {
  if (auto error = check_size(width, static_cast<std::int64_t>(rows.size()))) return *error;
  SpriteMask mask(width, static_cast<std::int32_t>(rows.size()));
  const std::size_t digits = static_cast<std::size_t>(width + 3) / 4;
  for (std::size_t y = 0; y < rows.size(); ++y) {
    if (rows[y].size() != digits) {
      return make_error(ErrorCode::InvalidArgument, row_field(y),
                        "must have ceil(width / 4) = " + std::to_string(digits) + " hex digits");
    }
    for (std::size_t j = 0; j < digits; ++j) {
      const int value = hex_value(rows[y][j]);
      if (value < 0) return make_error(ErrorCode::InvalidArgument, char_field(y, j), "must be a hex digit");
      for (int bit = 0; bit < 4; ++bit) {
        if (((value >> (3 - bit)) & 1) == 0) continue;
        const std::size_t x = 4 * j + static_cast<std::size_t>(bit);
        if (x >= static_cast<std::size_t>(width)) {
          return make_error(ErrorCode::InvalidArgument, row_field(y), "has a padding bit set past the width");
        }
        mask.set_bit(static_cast<std::int32_t>(x), static_cast<std::int32_t>(y));
      }
    }
  }
  mask.summarize();
  return mask;
}

Result<SpriteMask> SpriteMask::from_alpha_bytes(std::int32_t width, std::int32_t height,
                                                std::span<const std::uint8_t> bytes, std::size_t bytes_per_pixel,
                                                std::uint8_t alpha_threshold) {
  if (auto error = check_size(width, height)) return *error;
  const std::size_t pixels = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  if (bytes.size() != pixels * bytes_per_pixel) {
    return make_error(ErrorCode::InvalidArgument, "pixels",
                      "must hold " + std::to_string(bytes_per_pixel) + " x width x height bytes");
  }
  SpriteMask mask(width, height);
  for (std::int32_t y = 0; y < height; ++y) {
    for (std::int32_t x = 0; x < width; ++x) {
      const std::size_t pixel = static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + x;
      if (bytes[pixel * bytes_per_pixel + bytes_per_pixel - 1] >= alpha_threshold) mask.set_bit(x, y);
    }
  }
  mask.summarize();
  return mask;
}

Result<SpriteMask> SpriteMask::from_alpha(std::int32_t width, std::int32_t height, std::span<const std::uint8_t> alpha,
                                          std::uint8_t alpha_threshold) {
  return from_alpha_bytes(width, height, alpha, 1, alpha_threshold);
}

Result<SpriteMask> SpriteMask::from_rgba(std::int32_t width, std::int32_t height, std::span<const std::uint8_t> rgba,
                                         std::uint8_t alpha_threshold) {
  return from_alpha_bytes(width, height, rgba, 4, alpha_threshold);
}

void SpriteMask::summarize() {
  set_count_ = 0;
  row_words_.assign(static_cast<std::size_t>(height_), WordRange{});
  std::int64_t x0 = width_, y0 = height_, x1 = 0, y1 = 0;
  for (std::int32_t y = 0; y < height_; ++y) {
    const std::uint64_t* words = row(y);
    WordRange& range = row_words_[static_cast<std::size_t>(y)];
    for (std::int32_t k = 0; k < words_per_row_; ++k) {
      if (words[k] == 0) continue;
      set_count_ += static_cast<std::uint64_t>(std::popcount(words[k]));
      if (range.first == range.last) range.first = k;
      range.last = k + 1;
      x0 = std::min<std::int64_t>(x0, 64 * k + std::countr_zero(words[k]));
      x1 = std::max<std::int64_t>(x1, 64 * k + 64 - std::countl_zero(words[k]));
      y0 = std::min<std::int64_t>(y0, y);
      y1 = y + 1;
    }
  }
  bounds_ = set_count_ == 0 ? PixelRect{} : PixelRect{x0, y0, x1, y1};
}

}  // namespace proxima::d2
