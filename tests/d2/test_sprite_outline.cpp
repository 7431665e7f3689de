// mask_outline: exact loops are closed, axis-aligned, free of collinear vertices, and
// their signed areas add up to the set pixel count; on simple masks no loop crosses or
// touches itself; simplified loops stay within their tolerance of every exact vertex.
#include <gtest/gtest.h>

#include <proxima/d2/mask_outline.hpp>

#include <cmath>

#include "d2/sprite_reference.hpp"
#include "sweep_size.hpp"

namespace proxima::d2 {
namespace {

double total_area(const std::vector<OutlineLoop>& loops) {
  double sum = 0;
  for (const OutlineLoop& loop : loops) sum += signed_area(loop);
  return sum;
}

/// Every edge, the closing one included, is axis-aligned between integer corners, and no
/// vertex sits between two collinear edges.
void expect_staircase(const OutlineLoop& loop) {
  ASSERT_GE(loop.size(), 4u);
  for (std::size_t i = 0; i < loop.size(); ++i) {
    const Vec2 a = loop[i], b = loop[(i + 1) % loop.size()], c = loop[(i + 2) % loop.size()];
    EXPECT_EQ(a.x, std::floor(a.x));
    EXPECT_EQ(a.y, std::floor(a.y));
    EXPECT_TRUE((a.x == b.x) != (a.y == b.y)) << "edge " << i << " is not axis-aligned";
    EXPECT_FALSE((a.x == b.x && b.x == c.x) || (a.y == b.y && b.y == c.y)) << "collinear at " << i;
  }
}

/// No two non-adjacent edges of the loop share a point (axis-aligned edges).
void expect_simple(const OutlineLoop& loop) {
  const std::size_t n = loop.size();
  const auto box_of = [&](std::size_t i) {
    const Vec2 a = loop[i], b = loop[(i + 1) % n];
    return std::array<double, 4>{std::min(a.x, b.x), std::min(a.y, b.y), std::max(a.x, b.x), std::max(a.y, b.y)};
  };
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = i + 2; j < n; ++j) {
      if (i == 0 && j == n - 1) continue;
      const auto p = box_of(i), q = box_of(j);
      EXPECT_FALSE(p[0] <= q[2] && q[0] <= p[2] && p[1] <= q[3] && q[1] <= p[3]) << "edges " << i << ", " << j;
    }
  }
}

TEST(MaskOutline, SignedAreasSumToSetCount) {
  test::Random rng(71);
  for (int k = 0; k < test::sweep_size(300); ++k) {
    const SpriteMask mask = test::random_mask(rng, rng.integer(1, 80), rng.integer(1, 80), k % 3);
    const auto loops = mask_outline(mask);
    EXPECT_EQ(total_area(loops), static_cast<double>(mask.set_count())) << "case " << k;
    for (const OutlineLoop& loop : loops) expect_staircase(loop);
  }
}

TEST(MaskOutline, SimpleMasksGiveSimpleLoops) {
  const SpriteMask rect = test::mask_where(70, 9, [](int x, int y) { return x >= 3 && x < 66 && y >= 2 && y < 7; });
  const SpriteMask disc = test::mask_where(41, 41, [](int x, int y) { return std::hypot(x - 20, y - 20) <= 17.5; });
  const SpriteMask ring = test::mask_where(41, 41, [](int x, int y) {
    const double r = std::hypot(x - 20, y - 20);
    return r <= 17.5 && r >= 8.5;
  });
  const auto rect_loops = mask_outline(rect);
  ASSERT_EQ(rect_loops.size(), 1u);
  EXPECT_EQ(rect_loops[0].size(), 4u);
  EXPECT_EQ(signed_area(rect_loops[0]), 63.0 * 5.0);
  ASSERT_EQ(mask_outline(disc).size(), 1u);
  const auto ring_loops = mask_outline(ring);
  ASSERT_EQ(ring_loops.size(), 2u);
  EXPECT_GT(signed_area(ring_loops[0]), 0.0);  // outer boundary first (found first in row order)
  EXPECT_LT(signed_area(ring_loops[1]), 0.0);  // the hole, clockwise
  for (const SpriteMask* mask : {&rect, &disc, &ring}) {
    for (const OutlineLoop& loop : mask_outline(*mask)) expect_simple(loop);
  }
}

TEST(MaskOutline, CornerTouchingPixelsAreSeparateLoops) {
  const SpriteMask diagonal = test::mask_where(2, 2, [](int x, int y) { return x == y; });
  const auto loops = mask_outline(diagonal);
  ASSERT_EQ(loops.size(), 2u);
  for (const OutlineLoop& loop : loops) EXPECT_EQ(signed_area(loop), 1.0);
  EXPECT_TRUE(mask_outline(SpriteMask::create(5, 5).value()).empty());
}

/// Distance from p to the closed polygon `loop` (its edges).
double distance_to_loop(const Vec2& p, const OutlineLoop& loop) {
  double best = INFINITY;
  for (std::size_t i = 0; i < loop.size(); ++i) {
    const Vec2 a = loop[i], b = loop[(i + 1) % loop.size()];
    const double abx = b.x - a.x, aby = b.y - a.y;
    const double t = std::clamp(((p.x - a.x) * abx + (p.y - a.y) * aby) / (abx * abx + aby * aby), 0.0, 1.0);
    best = std::min(best, std::hypot(p.x - a.x - t * abx, p.y - a.y - t * aby));
  }
  return best;
}

TEST(MaskOutline, SimplificationStaysWithinTolerance) {
  test::Random rng(72);
  for (int k = 0; k < test::sweep_size(150); ++k) {
    const SpriteMask mask = test::random_mask(rng, rng.integer(2, 90), rng.integer(2, 90), k % 2 == 0 ? 0 : 2);
    const double tolerance = rng.integer(1, 30) / 10.0;
    const auto exact = mask_outline(mask);
    const auto simple = mask_outline(mask, tolerance);
    ASSERT_EQ(exact.size(), simple.size()) << "case " << k;
    for (std::size_t i = 0; i < exact.size(); ++i) {
      EXPECT_GE(simple[i].size(), 3u);
      EXPECT_LE(simple[i].size(), exact[i].size());
      for (const Vec2& p : exact[i]) EXPECT_LE(distance_to_loop(p, simple[i]), tolerance + 1e-9) << "case " << k;
    }
  }
}

}  // namespace
}  // namespace proxima::d2
