// Convention tests of the narrow phase on every ordered pair of shape types (11 x 11,
// mirrored cells and half-spaces included) at seeded random poses, in the style of Coal's
// convention tests: distance, intersect and collide agree away from the boundary; the
// witnesses satisfy point_b = point_a + signed_distance * normal and lie on their shapes'
// surfaces (checked with the shape layer's closest_point); moving B along the normal by
// -signed_distance makes the pair touch, by eps more apart, by eps less overlap; swapping A
// and B keeps the distance and flips the normal; manifold points share the manifold's normal
// and are no deeper than the pair. Shapes are random in size and ratio (hulls of 8-64 points).
#include <gtest/gtest.h>

#include <string>

#include "narrowphase/dispatch.hpp"
#include "narrowphase/pair_checker.hpp"

namespace proxima {
namespace test_invariants {

struct PairParam {
  ShapeType a;
  ShapeType b;
};

std::string pair_name(const testing::TestParamInfo<PairParam>& info) {
  return std::string(to_string(info.param.a)) + "_" + to_string(info.param.b);
}

std::vector<PairParam> all_pairs() {
  std::vector<PairParam> pairs;
  for (ShapeType a : test::all_shape_types()) {
    for (ShapeType b : test::all_shape_types()) pairs.push_back({a, b});
  }
  return pairs;
}

class Invariants : public testing::TestWithParam<PairParam> {};

// Cases per pair: several hundred in release, fewer in unoptimised builds.
#ifdef NDEBUG
constexpr int kCases = 300;
#else
constexpr int kCases = 60;
#endif

TEST_P(Invariants, ConventionHoldsAtRandomPoses) {
  const PairParam p = GetParam();
  const std::uint64_t seed = 0x9e3779b97f4a7c15ull ^ (std::uint64_t(p.a) * 131u + std::uint64_t(p.b));
  test::Random rng(seed);
  test::PairChecker checker;
  int hits = 0;
  for (int i = 0; i < kCases; ++i) {
    const Shape a = test::random_shape(rng, p.a);
    const Shape b = test::random_shape(rng, p.b);
    const Transform pose_a = rng.pose(Real(0.5));
    const Transform pose_b = rng.pose(Real(1.8));
    checker.check(a, pose_a, b, pose_b, "seed=" + std::to_string(seed) + " case=" + std::to_string(i));
    if (intersect(a, pose_a, b, pose_b)) ++hits;
  }
  std::string detail;
  for (const std::string& m : checker.messages()) detail += "\n  " + m;
  EXPECT_EQ(checker.failed_cases(), 0) << checker.failed_cases() << " of " << checker.cases()
                                       << " cases failed: " << checker.summary() << detail;
  // The sweep must see both outcomes (except half-space pairs, which mostly overlap).
  // Points (and thin pairs) seldom overlap at random poses.
  const bool rare_overlap =
      p.a == ShapeType::Point || p.b == ShapeType::Point || (test::is_thin(p.a) && test::is_thin(p.b));
  if (kCases >= 300 && p.a != ShapeType::HalfSpace && p.b != ShapeType::HalfSpace && !rare_overlap) {
    EXPECT_GT(hits, kCases / 100) << "too few overlapping cases";
    EXPECT_LT(hits, kCases - kCases / 100) << "too few separated cases";
  }
}

INSTANTIATE_TEST_SUITE_P(AllPairs, Invariants, testing::ValuesIn(all_pairs()), pair_name);

// The dispatch table is complete and consistent: every cell has its three functions, and a
// mirrored cell's (B, A) partner is not itself mirrored.
TEST(Invariants, DispatchTableIsComplete) {
  for (ShapeType a : test::all_shape_types()) {
    for (ShapeType b : test::all_shape_types()) {
      const narrow::PairFunctions& f = narrow::pair_functions(a, b);
      EXPECT_NE(f.intersect, nullptr) << to_string(a) << "-" << to_string(b);
      EXPECT_NE(f.distance, nullptr) << to_string(a) << "-" << to_string(b);
      EXPECT_NE(f.collide, nullptr) << to_string(a) << "-" << to_string(b);
      if (f.mirrored) {
        EXPECT_FALSE(narrow::pair_functions(b, a).mirrored) << to_string(a) << "-" << to_string(b);
      }
    }
  }
}

}  // namespace test_invariants
}  // namespace proxima
