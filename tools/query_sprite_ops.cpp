// sprite_overlap: reads two masks (text rows or PNG files decoded with libpng's simplified
// API to RGBA) and their placements, and answers with proxima::d2::sprite_overlap.
#include "query_sprite_ops.hpp"

#include <proxima/d2/sprite_overlap.hpp>

#include <cmath>
#include <memory>
#include <png.h>
#include <string>
#include <vector>

namespace proxima::tool {

namespace {

/// A JSON number that is an integer in [lo, hi] (error "wrong_type" or "out_of_range").
std::int64_t read_integer(const Json& value, const std::string& path, std::int64_t lo, std::int64_t hi) {
  const double x = read_double(value, path);
  if (x != std::floor(x)) throw FieldError(path, "wrong_type", "must be an integer");
  if (x < static_cast<double>(lo) || x > static_cast<double>(hi)) {
    throw FieldError(path, "out_of_range", "must be in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
  }
  return static_cast<std::int64_t>(x);
}

/// [x, y] integer screen position.
d2::PixelPoint read_position(const Json& value, const std::string& path) {
  if (!value.is_array() || value.size() != 2) throw FieldError(path, "wrong_type", "must be an array [x, y]");
  const std::int64_t limit = d2::kMaxSpritePosition;
  return {read_integer(value[0], join_path(path, "x"), -limit, limit),
          read_integer(value[1], join_path(path, "y"), -limit, limit)};
}

/// The mask of a PNG file: RGBA pixels, set iff alpha >= threshold.
d2::SpriteMask png_mask(const std::string& file, std::uint8_t threshold, const std::string& path) {
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  if (png_image_begin_read_from_file(&image, file.c_str()) == 0) {
    throw FieldError(join_path(path, "png"), "invalid_argument",
                     "cannot read the PNG file: " + std::string(image.message));
  }
  const std::unique_ptr<png_image, void (*)(png_imagep)> guard(&image, png_image_free);
  image.format = PNG_FORMAT_RGBA;
  if (image.width > static_cast<png_uint_32>(d2::kMaxSpriteSide) ||
      image.height > static_cast<png_uint_32>(d2::kMaxSpriteSide)) {
    throw FieldError(join_path(path, "png"), "out_of_range", "the image is larger than 32768 pixels on a side");
  }
  std::vector<std::uint8_t> pixels(PNG_IMAGE_SIZE(image));
  if (png_image_finish_read(&image, nullptr, pixels.data(), 0, nullptr) == 0) {
    throw FieldError(join_path(path, "png"), "invalid_argument",
                     "cannot decode the PNG file: " + std::string(image.message));
  }
  return unwrap(d2::SpriteMask::from_rgba(static_cast<std::int32_t>(image.width),
                                          static_cast<std::int32_t>(image.height), pixels, threshold),
                path);
}

/// The mask of rows '0'/'1' with its declared width and height.
d2::SpriteMask rows_mask(const Json& mask, const std::string& path) {
  reject_unknown_fields(mask, path, {"width", "height", "rows"});
  const std::int64_t width =
      read_integer(require_member(mask, path, "width"), join_path(path, "width"), 1, d2::kMaxSpriteSide);
  const std::int64_t height =
      read_integer(require_member(mask, path, "height"), join_path(path, "height"), 1, d2::kMaxSpriteSide);
  const Json& rows_json = require_member(mask, path, "rows");
  const std::string rows_path = join_path(path, "rows");
  if (!rows_json.is_array() || static_cast<std::int64_t>(rows_json.size()) != height) {
    throw FieldError(rows_path, "wrong_type", "must be an array of `height` strings");
  }
  std::vector<std::string> rows;
  for (std::size_t i = 0; i < rows_json.size(); ++i) {
    rows.push_back(read_string(rows_json[i], index_path(rows_path, i)));
    if (static_cast<std::int64_t>(rows.back().size()) != width) {
      throw FieldError(index_path(rows_path, i), "invalid_argument", "must have `width` characters");
    }
  }
  return unwrap(d2::SpriteMask::from_rows(rows), path);
}

d2::SpriteMask read_mask(const Json& mask, const std::string& path) {
  require_object(mask, path);
  if (find_member(mask, "png") == nullptr) return rows_mask(mask, path);
  reject_unknown_fields(mask, path, {"png", "alpha_threshold"});
  const Json* threshold = find_member(mask, "alpha_threshold");
  const std::int64_t alpha = threshold ? read_integer(*threshold, join_path(path, "alpha_threshold"), 0, 255) : 128;
  return png_mask(read_string(mask["png"], join_path(path, "png")), static_cast<std::uint8_t>(alpha), path);
}

/// A double member, or `fallback` when absent.
double optional_double(const Json& side, const std::string& path, std::string_view key, double fallback) {
  const Json* value = find_member(side, key);
  return value ? read_double(*value, join_path(path, key)) : fallback;
}

}  // namespace

Json op_sprite_overlap(const Json& request) {
  reject_unknown_fields(request, "", {"id", "op", "a", "b"});
  const Json& a = require_member(request, "", "a");
  const Json& b = require_member(request, "", "b");
  require_object(a, "a");
  require_object(b, "b");
  reject_unknown_fields(a, "a", {"mask", "position"});
  reject_unknown_fields(b, "b", {"mask", "position", "angle_degrees", "scale"});
  const d2::SpriteMask mask_a = read_mask(require_member(a, "a", "mask"), "a.mask");
  const d2::PixelPoint position_a = read_position(require_member(a, "a", "position"), "a.position");
  const d2::SpriteMask mask_b = read_mask(require_member(b, "b", "mask"), "b.mask");
  const d2::PixelPoint position_b = read_position(require_member(b, "b", "position"), "b.position");
  const double angle = optional_double(b, "b", "angle_degrees", 0.0);
  const double scale = optional_double(b, "b", "scale", 1.0);
  d2::SpriteOverlap result;
  if (angle == 0.0 && scale == 1.0) {
    result = d2::sprite_overlap(mask_a, position_a, mask_b, position_b);
  } else {
    result = d2::sprite_overlap(mask_a, position_a, mask_b,
                                unwrap(d2::TurnedPlacement::create(position_b, angle, scale), "b"));
  }
  Json answer = Json::object();
  answer["overlap"] = result.overlap;
  answer["count"] = result.count;
  answer["first"] = result.first ? Json::array({result.first->x, result.first->y}) : Json(nullptr);
  return answer;
}

}  // namespace proxima::tool
