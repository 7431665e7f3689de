// The tool's interim sort-and-sweep against the brute-force pair set (every pair tested with
// Aabb::overlaps), on random boxes with touching, identical, flat and empty boxes.
#include <gtest/gtest.h>

#include <vector>

#include "sort_and_sweep.hpp"
#include "support/random.hpp"
#include "svg_writer.hpp"

namespace proxima {
namespace {

std::vector<tool::IndexPair> brute_force(const std::vector<Aabb>& boxes) {
  std::vector<tool::IndexPair> pairs;
  for (std::uint32_t i = 0; i < boxes.size(); ++i) {
    for (std::uint32_t j = i + 1; j < boxes.size(); ++j) {
      if (boxes[i].is_valid() && boxes[j].is_valid() && boxes[i].overlaps(boxes[j])) pairs.emplace_back(i, j);
    }
  }
  return pairs;
}

TEST(SortAndSweep, MatchesBruteForceOnRandomBoxes) {
  test::Random rng(201);
  tool::SortAndSweep sweep;
  std::vector<tool::IndexPair> pairs;
  std::size_t total = 0;
  for (int trial = 0; trial < 1000; ++trial) {
    const int n = rng.integer(0, 60);
    // Coordinates on a coarse grid so that touching boxes (equal faces) are common.
    std::vector<Aabb> boxes;
    for (int i = 0; i < n; ++i) {
      const int kind = rng.integer(0, 9);
      if (kind == 0 && !boxes.empty()) {
        boxes.push_back(boxes[static_cast<std::size_t>(rng.integer(0, static_cast<int>(boxes.size()) - 1))]);
        continue;
      }
      if (kind == 1) {
        boxes.push_back(Aabb::empty());
        continue;
      }
      Vec3 lo, size;
      for (int k = 0; k < 3; ++k) {
        lo[k] = Real(rng.integer(-20, 20)) * Real(0.5);
        size[k] = kind == 2 ? Real(0) : Real(rng.integer(1, 8)) * Real(0.5);
      }
      boxes.push_back({lo, lo + size});
    }
    const auto expected = brute_force(boxes);
    for (int axis = 0; axis < 3; ++axis) {
      sweep.find_pairs(boxes, pairs, axis);
      ASSERT_EQ(pairs, expected) << "trial " << trial << " axis " << axis;
    }
    total += expected.size();
  }
  EXPECT_GT(total, 5000u);
}

TEST(SortAndSweep, UnboundedBoxes) {
  // Half-space style boxes (+-kRealMax on free sides) pair with everything they reach.
  const std::vector<Aabb> boxes = {
      {Vec3(-kRealMax), Vec3(kRealMax, kRealMax, Real(0))},
      {Vec3(0, 0, Real(-1)), Vec3(1, 1, Real(-0.5))},
      {Vec3(0, 0, Real(0)), Vec3(1, 1, Real(1))},
      {Vec3(0, 0, Real(0.5)), Vec3(1, 1, Real(2))},
  };
  tool::SortAndSweep sweep;
  std::vector<tool::IndexPair> pairs;
  sweep.find_pairs(boxes, pairs);
  EXPECT_EQ(pairs, brute_force(boxes));
  EXPECT_EQ(pairs.size(), 3u);  // (0,1) (0,2) touching, (2,3)
}

TEST(SvgWriter, EscapesTextAndStartsWithSvg) {
  EXPECT_EQ(tool::xml_escape("a<b & \"c\" 'd'>"), "a&lt;b &amp; &quot;c&quot; &apos;d&apos;&gt;");
  tool::SvgWriter svg(100, 50);
  svg.polyline({{0, 0}, {10, 5.5}}, "red", 1.5);
  svg.text(1, 2, "x < y", 10);
  const std::string s = svg.str();
  EXPECT_EQ(s.rfind("<svg", 0), 0u);
  EXPECT_NE(s.find("points=\"0,0 10,5.5\""), std::string::npos) << s;
  EXPECT_NE(s.find(">x &lt; y</text>"), std::string::npos) << s;
  EXPECT_NE(s.find("</svg>"), std::string::npos);
}

}  // namespace
}  // namespace proxima
