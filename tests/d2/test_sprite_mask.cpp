// SpriteMask: construction from text rows, W9 hex rows and alpha bytes; the errors name
// their field; get, set count and bounds agree with the pixels given, at widths around
// the 64-bit word boundaries.
#include <gtest/gtest.h>

#include <proxima/d2/sprite_mask.hpp>

#include <string>
#include <vector>

#include "d2/sprite_reference.hpp"

namespace proxima::d2 {
namespace {

using Rows = std::vector<std::string>;

TEST(SpriteMask, FromRowsReadsRowZeroAtTheTop) {
  const Rows rows = {"0110", "1000", "0000"};
  const SpriteMask mask = SpriteMask::from_rows(rows).value();
  EXPECT_EQ(mask.width(), 4);
  EXPECT_EQ(mask.height(), 3);
  EXPECT_TRUE(mask.get(1, 0));
  EXPECT_TRUE(mask.get(2, 0));
  EXPECT_TRUE(mask.get(0, 1));
  EXPECT_FALSE(mask.get(0, 0));
  EXPECT_FALSE(mask.get(-1, 0));
  EXPECT_FALSE(mask.get(4, 0));
  EXPECT_FALSE(mask.get(0, 3));
  EXPECT_EQ(mask.set_count(), 3u);
  EXPECT_EQ(mask.bounds(), (PixelRect{0, 0, 3, 2}));
}

TEST(SpriteMask, WidthsAroundWordBoundaries) {
  for (const int w : {1, 63, 64, 65, 129}) {
    test::Random rng(static_cast<std::uint64_t>(w));
    const SpriteMask mask = test::random_mask(rng, w, 3, 1);
    EXPECT_EQ(mask.words_per_row(), (w + 63) / 64);
    std::uint64_t count = 0;
    for (int y = 0; y < 3; ++y) {
      for (int x = 0; x < w; ++x) count += mask.get(x, y) ? 1u : 0u;
      const std::uint64_t last = mask.row(y)[mask.words_per_row() - 1];
      if (w % 64 != 0) {
        EXPECT_EQ(last >> (w % 64), 0u) << "padding bits of row " << y << " at width " << w;
      }
    }
    EXPECT_EQ(mask.set_count(), count) << w;
    const SpriteMask full = test::mask_where(w, 2, [](int, int) { return true; });
    EXPECT_EQ(full.set_count(), 2u * static_cast<std::uint64_t>(w));
    EXPECT_EQ(full.bounds(), (PixelRect{0, 0, w, 2}));
  }
}

TEST(SpriteMask, EmptyMaskHasEmptyBounds) {
  const SpriteMask mask = SpriteMask::create(70, 5).value();
  EXPECT_EQ(mask.set_count(), 0u);
  EXPECT_TRUE(mask.bounds().is_empty());
}

TEST(SpriteMask, HexRowsPutTheLeftmostPixelInTheHighBit) {
  const Rows rows = {"8c", "01", "A0"};  // 1000 1100 / 0000 0001 / 1010 0000
  const SpriteMask mask = SpriteMask::from_hex_rows(8, rows).value();
  EXPECT_TRUE(mask.get(0, 0));
  EXPECT_TRUE(mask.get(4, 0));
  EXPECT_TRUE(mask.get(5, 0));
  EXPECT_TRUE(mask.get(7, 1));
  EXPECT_TRUE(mask.get(0, 2));
  EXPECT_TRUE(mask.get(2, 2));
  EXPECT_EQ(mask.set_count(), 6u);
  const SpriteMask odd = SpriteMask::from_hex_rows(5, Rows{"f8"}).value();  // 5 pixels, 3 padding bits
  EXPECT_EQ(odd.set_count(), 5u);
}

TEST(SpriteMask, AlphaThresholdIsInclusive) {
  const std::vector<std::uint8_t> alpha = {0, 127, 128, 255};
  const SpriteMask mask = SpriteMask::from_alpha(2, 2, alpha, 128).value();
  EXPECT_FALSE(mask.get(0, 0));
  EXPECT_FALSE(mask.get(1, 0));
  EXPECT_TRUE(mask.get(0, 1));
  EXPECT_TRUE(mask.get(1, 1));
  std::vector<std::uint8_t> rgba(16, 200);
  rgba[3] = 10;  // pixel (0, 0) nearly transparent
  const SpriteMask from_rgba = SpriteMask::from_rgba(2, 2, rgba, 11).value();
  EXPECT_EQ(from_rgba.set_count(), 3u);
  EXPECT_FALSE(from_rgba.get(0, 0));
  EXPECT_EQ(SpriteMask::from_alpha(2, 2, alpha, 0).value().set_count(), 4u);
}

void expect_field(const Result<SpriteMask>& r, const std::string& field) {
  ASSERT_FALSE(r.ok()) << field;
  EXPECT_EQ(r.error().field, field);
}

TEST(SpriteMask, BadInputNamesItsField) {
  expect_field(SpriteMask::create(0, 4), "width");
  expect_field(SpriteMask::create(4, -1), "height");
  expect_field(SpriteMask::create(kMaxSpriteSide + 1, 4), "width");
  expect_field(SpriteMask::from_rows(Rows{}), "height");
  expect_field(SpriteMask::from_rows(Rows{""}), "width");
  expect_field(SpriteMask::from_rows(Rows{"01", "011"}), "rows[1]");
  expect_field(SpriteMask::from_rows(Rows{"01", "0x"}), "rows[1][1]");
  expect_field(SpriteMask::from_hex_rows(8, Rows{"0g"}), "rows[0][1]");
  expect_field(SpriteMask::from_hex_rows(8, Rows{"000"}), "rows[0]");
  expect_field(SpriteMask::from_hex_rows(5, Rows{"fc"}), "rows[0]");  // a padding bit set
  expect_field(SpriteMask::from_hex_rows(0, Rows{"0"}), "width");
  expect_field(SpriteMask::from_hex_rows(4, Rows{}), "height");
  const std::vector<std::uint8_t> three(3, 255);
  expect_field(SpriteMask::from_alpha(2, 2, three, 1), "pixels");
  expect_field(SpriteMask::from_rgba(1, 1, three, 1), "pixels");
  EXPECT_EQ(SpriteMask::create(0, 4).error().code, ErrorCode::NonPositive);
  EXPECT_EQ(SpriteMask::create(kMaxSpriteSide + 1, 4).error().code, ErrorCode::OutOfRange);
}

}  // namespace
}  // namespace proxima::d2
