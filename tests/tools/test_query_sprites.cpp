// The sprite_overlap operation: masks from rows and from a PNG file written here with
// libpng, turned placements, and errors that name their field.
#include <gtest/gtest.h>

#include <filesystem>
#include <png.h>
#include <vector>

#include "query_test_util.hpp"

namespace proxima::test {
namespace {

Json rows_mask(int w, int h, std::vector<std::string> rows) { return {{"width", w}, {"height", h}, {"rows", rows}}; }

Json request(const Json& mask_a, Json position_a, const Json& mask_b, Json position_b) {
  return {{"op", "sprite_overlap"},
          {"a", {{"mask", mask_a}, {"position", position_a}}},
          {"b", {{"mask", mask_b}, {"position", position_b}}}};
}

TEST(QuerySprites, RowsMasksOverlap) {
  const Json square = rows_mask(2, 2, {"11", "11"});
  const Json a = answer(request(square, {0, 0}, square, {1, -1}));
  EXPECT_EQ(a["overlap"], true);
  EXPECT_EQ(a["count"], 1);
  EXPECT_EQ(a["first"], Json::array({1, 0}));
  const Json miss = answer(request(square, {0, 0}, square, {2, 0}));
  EXPECT_EQ(miss["overlap"], false);
  EXPECT_EQ(miss["count"], 0);
  EXPECT_TRUE(miss["first"].is_null());
}

TEST(QuerySprites, TurnedPlacement) {
  // B's top row turned by +90 degrees (clockwise on screen) becomes its right column.
  Json r = request(rows_mask(1, 3, {"1", "1", "1"}), {2, 0}, rows_mask(3, 3, {"111", "000", "000"}), {0, 0});
  r["b"]["angle_degrees"] = 90;
  EXPECT_EQ(answer(r)["count"], 3);
  r["b"]["angle_degrees"] = -90;
  EXPECT_EQ(answer(r)["count"], 0);
  r["b"]["scale"] = 0;
  EXPECT_EQ(answer(r, false)["field"], "b.scale");
}

/// Writes a w x h RGBA PNG whose alpha is alpha(x, y).
void write_png(const std::string& file, int w, int h, int (*alpha)(int, int)) {
  std::vector<std::uint8_t> pixels(static_cast<std::size_t>(4 * w * h), 255);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x)
      pixels[static_cast<std::size_t>(4 * (y * w + x) + 3)] = static_cast<std::uint8_t>(alpha(x, y));
  }
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  image.width = static_cast<png_uint_32>(w);
  image.height = static_cast<png_uint_32>(h);
  image.format = PNG_FORMAT_RGBA;
  ASSERT_NE(png_image_write_to_file(&image, file.c_str(), 0, pixels.data(), 0, nullptr), 0) << image.message;
}

TEST(QuerySprites, PngMaskWithAlphaThreshold) {
  const std::string file = (std::filesystem::temp_directory_path() / "proxima_test_sprite.png").string();
  write_png(file, 3, 2, [](int x, int) { return x * 100; });  // alpha 0, 100, 200 per column
  const Json full = rows_mask(3, 2, {"111", "111"});
  Json r = request({{"png", file}}, {0, 0}, full, {0, 0});  // default threshold 128: column 2
  EXPECT_EQ(answer(r)["count"], 2);
  EXPECT_EQ(answer(r)["first"], Json::array({2, 0}));
  r["a"]["mask"]["alpha_threshold"] = 100;
  EXPECT_EQ(answer(r)["count"], 4);
  r["a"]["mask"]["alpha_threshold"] = 0;
  EXPECT_EQ(answer(r)["count"], 6);
  r["a"]["mask"]["alpha_threshold"] = 256;
  EXPECT_EQ(answer(r, false)["field"], "a.mask.alpha_threshold");
  std::filesystem::remove(file);
  r["a"]["mask"]["alpha_threshold"] = 1;
  EXPECT_EQ(answer(r, false)["field"], "a.mask.png");
}

TEST(QuerySprites, ErrorsNameTheField) {
  const Json ok = rows_mask(2, 1, {"10"});
  EXPECT_EQ(answer(request(rows_mask(2, 1, {"1x"}), {0, 0}, ok, {0, 0}), false)["field"], "a.mask.rows[0][1]");
  EXPECT_EQ(answer(request(rows_mask(2, 1, {"101"}), {0, 0}, ok, {0, 0}), false)["field"], "a.mask.rows[0]");
  EXPECT_EQ(answer(request(rows_mask(2, 2, {"10"}), {0, 0}, ok, {0, 0}), false)["field"], "a.mask.rows");
  EXPECT_EQ(answer(request(rows_mask(0, 1, {""}), {0, 0}, ok, {0, 0}), false)["field"], "a.mask.width");
  EXPECT_EQ(answer(request(ok, {0.5, 0}, ok, {0, 0}), false)["field"], "a.position.x");
  EXPECT_EQ(answer(request(ok, {0, 0}, ok, {0}), false)["field"], "b.position");
  Json extra = request(ok, {0, 0}, ok, {0, 0});
  extra["a"]["angle_degrees"] = 3;
  EXPECT_EQ(answer(extra, false)["field"], "a.angle_degrees");
  Json missing = request(ok, {0, 0}, ok, {0, 0});
  missing["b"].erase("mask");
  const Json error = answer(missing, false);
  EXPECT_EQ(error["field"], "b.mask");
  EXPECT_EQ(error["code"], "missing");
}

}  // namespace
}  // namespace proxima::test
