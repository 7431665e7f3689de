// sprite_overlap and sprites_overlap against the plain per-pixel loops of
// sprite_reference.hpp: seeded random masks and placements (translation, then turned and
// scaled), and named edge cases (word-boundary widths, negative offsets, touching masks,
// empty masks, quarter turns equal to permuted masks, bad placements).
#include <gtest/gtest.h>

#include <proxima/d2/sprite_overlap.hpp>

#include "d2/sprite_reference.hpp"
#include "sweep_size.hpp"

namespace proxima::d2 {
namespace {

constexpr int kWidths[] = {1, 2, 7, 63, 64, 65, 100, 129, 200};

SpriteMask random_sized_mask(test::Random& rng) {
  const int w = kWidths[rng.integer(0, 8)], h = rng.integer(1, 70);
  return test::random_mask(rng, w, h, rng.integer(0, 2));
}

void expect_same(const SpriteOverlap& got, const SpriteOverlap& want, int k) {
  EXPECT_EQ(got.count, want.count) << "case " << k;
  EXPECT_EQ(got.overlap, want.overlap) << "case " << k;
  ASSERT_EQ(got.first.has_value(), want.first.has_value()) << "case " << k;
  if (got.first) {
    EXPECT_EQ(got.first->x, want.first->x) << "case " << k;
    EXPECT_EQ(got.first->y, want.first->y) << "case " << k;
  }
}

TEST(SpriteOverlap, TranslationMatchesPerPixelLoop) {
  test::Random rng(91);
  int overlapping = 0;
  const int cases = test::sweep_size(4000);
  for (int k = 0; k < cases; ++k) {
    const SpriteMask a = random_sized_mask(rng), b = random_sized_mask(rng);
    const PixelPoint pa{rng.integer(-300, 300), rng.integer(-100, 100)};
    const PixelPoint pb{pa.x + rng.integer(-b.width(), a.width()), pa.y + rng.integer(-b.height(), a.height())};
    const SpriteOverlap want = test::reference_overlap(a, pa, b, pb);
    expect_same(sprite_overlap(a, pa, b, pb), want, k);
    EXPECT_EQ(sprites_overlap(a, pa, b, pb), want.overlap) << "case " << k;
    overlapping += want.overlap ? 1 : 0;
  }
  EXPECT_GT(overlapping, cases / 5);
}

TEST(SpriteOverlap, TurnedAndScaledMatchesPerPixelLoop) {
  test::Random rng(92);
  int overlapping = 0;
  const int cases = test::sweep_size(3000);
  for (int k = 0; k < cases; ++k) {
    const SpriteMask a = random_sized_mask(rng), b = random_sized_mask(rng);
    const double degrees = k % 2 == 0 ? rng.integer(-360, 360) : static_cast<double>(rng.uniform(-400, 400));
    const double scale = rng.integer(25, 300) / 100.0;
    const PixelPoint pa{rng.integer(-50, 50), rng.integer(-50, 50)};
    const PixelPoint pb{pa.x + rng.integer(-b.width(), a.width()), pa.y + rng.integer(-b.height(), a.height())};
    const TurnedPlacement placement = TurnedPlacement::create(pb, degrees, scale).value();
    const SpriteOverlap want = test::reference_turned(a, pa, b, pb, degrees, scale);
    expect_same(sprite_overlap(a, pa, b, placement), want, k);
    EXPECT_EQ(sprites_overlap(a, pa, b, placement), want.overlap) << "case " << k;
    overlapping += want.overlap ? 1 : 0;
  }
  EXPECT_GT(overlapping, cases / 5);
}

TEST(SpriteOverlap, WordBoundaryWidthsAtEveryShift) {
  for (const int w : {1, 63, 64, 65, 129}) {
    test::Random rng(static_cast<std::uint64_t>(300 + w));
    const SpriteMask a = test::random_mask(rng, w, 5, 1), b = test::random_mask(rng, 129 - w + 1, 4, 1);
    for (int dx = -b.width() - 1; dx <= w + 1; ++dx) {
      const PixelPoint pa{-7, 3}, pb{-7 + dx, 4};
      expect_same(sprite_overlap(a, pa, b, pb), test::reference_overlap(a, pa, b, pb), dx);
    }
  }
}

TEST(SpriteOverlap, NegativeOffsetsAndFirstPixel) {
  const SpriteMask a = test::mask_where(3, 3, [](int, int) { return true; });
  const SpriteMask b = test::mask_where(2, 2, [](int x, int y) { return x == 1 && y == 1; });
  const SpriteOverlap r = sprite_overlap(a, {-10, -20}, b, {-11, -21});  // B's set pixel on screen (-10, -20)
  EXPECT_TRUE(r.overlap);
  EXPECT_EQ(r.count, 1u);
  ASSERT_TRUE(r.first);
  EXPECT_EQ(*r.first, (PixelPoint{-10, -20}));
  const SpriteOverlap all = sprite_overlap(a, {-10, -20}, a, {-9, -20});
  EXPECT_EQ(all.count, 6u);
  EXPECT_EQ(*all.first, (PixelPoint{-9, -20}));
}

TEST(SpriteOverlap, TouchingMasksDoNotOverlap) {
  const SpriteMask a = test::mask_where(64, 8, [](int, int) { return true; });
  for (const PixelPoint pb : {PixelPoint{64, 0}, PixelPoint{-64, 0}, PixelPoint{0, 8}, PixelPoint{0, -8}}) {
    EXPECT_FALSE(sprites_overlap(a, {0, 0}, a, pb));
    EXPECT_EQ(sprite_overlap(a, {0, 0}, a, pb), SpriteOverlap{});
  }
  EXPECT_EQ(sprite_overlap(a, {0, 0}, a, {63, 7}).count, 1u);
}

TEST(SpriteOverlap, EmptyMasksNeverOverlap) {
  const SpriteMask empty = SpriteMask::create(65, 9).value();
  const SpriteMask full = test::mask_where(65, 9, [](int, int) { return true; });
  EXPECT_EQ(sprite_overlap(empty, {0, 0}, full, {0, 0}), SpriteOverlap{});
  EXPECT_EQ(sprite_overlap(full, {0, 0}, empty, {0, 0}), SpriteOverlap{});
  const TurnedPlacement turned = TurnedPlacement::create({0, 0}, 30, 1.5).value();
  EXPECT_EQ(sprite_overlap(full, {0, 0}, empty, turned), SpriteOverlap{});
  EXPECT_FALSE(sprites_overlap(empty, {0, 0}, full, turned));
  EXPECT_TRUE(turned_bounds(empty, turned).is_empty());
}

/// B turned by a quarter-turn multiple about its centre (scale 1), as a plain mask and the
/// position it sits at: W9's rule maps pixel centres to pixel centres when the sides have
/// the same parity (always for 0 and 180 degrees).
std::pair<SpriteMask, PixelPoint> quarter_turned(const SpriteMask& b, PixelPoint pb, int quarters) {
  const int w = b.width(), h = b.height();
  if (quarters % 2 == 0) {
    const bool half = quarters == 2;
    return {test::mask_where(w, h, [&](int x, int y) { return half ? b.get(w - 1 - x, h - 1 - y) : b.get(x, y); }), pb};
  }
  const PixelPoint at{pb.x + (w - h) / 2, pb.y + (h - w) / 2};
  if (quarters == 1) return {test::mask_where(h, w, [&](int x, int y) { return b.get(y, h - 1 - x); }), at};
  return {test::mask_where(h, w, [&](int x, int y) { return b.get(w - 1 - y, x); }), at};
}

TEST(SpriteOverlap, QuarterTurnsEqualPermutedMasks) {
  test::Random rng(93);
  for (int k = 0; k < test::sweep_size(400); ++k) {
    const int quarters = k % 4;
    const int w = rng.integer(1, 90), h = quarters % 2 == 1 ? w + 2 * rng.integer(-w / 2, 20) : rng.integer(1, 90);
    const SpriteMask a = random_sized_mask(rng), b = test::random_mask(rng, w, std::max(h, 1), rng.integer(0, 2));
    const PixelPoint pa{rng.integer(-20, 20), rng.integer(-20, 20)};
    const PixelPoint pb{pa.x + rng.integer(-b.width(), a.width()), pa.y + rng.integer(-b.height(), a.height())};
    if (quarters % 2 == 1 && (b.width() - b.height()) % 2 != 0) continue;
    const auto [turned, at] = quarter_turned(b, pb, quarters);
    const TurnedPlacement placement = TurnedPlacement::create(pb, 90.0 * quarters, 1.0).value();
    expect_same(sprite_overlap(a, pa, b, placement), sprite_overlap(a, pa, turned, at), k);
  }
}

TEST(SpriteOverlap, PositiveAngleTurnsClockwiseOnScreen) {
  // B's top row, turned by +90 degrees, becomes its right column (y points down).
  const SpriteMask b = test::mask_where(3, 3, [](int, int y) { return y == 0; });
  const SpriteMask dot = test::mask_where(1, 1, [](int, int) { return true; });
  const TurnedPlacement placement = TurnedPlacement::create({0, 0}, 90, 1).value();
  EXPECT_TRUE(sprites_overlap(dot, {2, 0}, b, placement));
  EXPECT_TRUE(sprites_overlap(dot, {2, 2}, b, placement));
  EXPECT_FALSE(sprites_overlap(dot, {0, 0}, b, placement));
}

TEST(SpriteOverlap, BadPlacementNamesItsField) {
  const auto field = [](const Result<TurnedPlacement>& r) { return r.ok() ? std::string() : r.error().field; };
  EXPECT_EQ(field(TurnedPlacement::create({0, 0}, 10, 0)), "scale");
  EXPECT_EQ(field(TurnedPlacement::create({0, 0}, 10, -1)), "scale");
  EXPECT_EQ(field(TurnedPlacement::create({0, 0}, 10, 1e9)), "scale");
  EXPECT_EQ(field(TurnedPlacement::create({kMaxSpritePosition + 1, 0}, 10, 1)), "position");
  test::ScopedNoFpTraps no_traps;
  EXPECT_EQ(field(TurnedPlacement::create({0, 0}, std::nan(""), 1)), "angle_degrees");
  EXPECT_EQ(field(TurnedPlacement::from_radians({0, 0}, INFINITY, 1)), "angle_radians");
  EXPECT_EQ(field(TurnedPlacement::create({0, 0}, 0, std::nan(""))), "scale");
}

}  // namespace
}  // namespace proxima::d2
