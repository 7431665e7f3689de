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

using test::TypePair;

std::vector<TypePair> all_pairs() {
  return test::type_pairs(kConvexShapeTypeCount, [](ShapeType, ShapeType) { return true; });
}

class Invariants : public testing::TestWithParam<TypePair> {};

// Cases per pair: several hundred in release, fewer in unoptimised builds.
#ifdef NDEBUG
constexpr int kCases = 300;
#else
constexpr int kCases = 60;
#endif

TEST_P(Invariants, ConventionHoldsAtRandomPoses) {
  const TypePair p = GetParam();
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

INSTANTIATE_TEST_SUITE_P(AllPairs, Invariants, testing::ValuesIn(all_pairs()), test::type_pair_name);

// Named cases of the sweep above that the sanitizer build (clang) drew while the sweep's
// random draws were still arguments of one call, evaluated left to right there (seed, case
// index and pair in each name's comment). Each is a penetrating pair on which the witnesses
// were not the extremes along the reported normal: `point_a - point_b` a few degrees off it.
// A pose written with float's 9 digits: its rotation is unit to float precision, so the
// double build normalises it (unnormalised, it scales the pose by 1 +- 1e-7).
Transform pose_at(Real px, Real py, Real pz, Real qx, Real qy, Real qz, Real qw) {
  const Quat q(qw, qx, qy, qz);
  return Transform{Vec3(px, py, pz), sizeof(Real) == 4 ? q : glm::normalize(q)};
}

void expect_case_holds(const Shape& a, const Transform& pose_a, const Shape& b, const Transform& pose_b) {
  test::PairChecker checker;
  checker.check(a, pose_a, b, pose_b, "named case");
  std::string detail;
  for (const std::string& m : checker.messages()) detail += "\n  " + m;
  EXPECT_EQ(checker.failed_cases(), 0) << checker.summary() << detail;
}

// cylinder_point, seed 11400714819323199239, case 168.
TEST(Invariants, PenetratingCylinderPointWitnessesAlongTheNormal) {
  const Shape a = Cylinder::create(Real(0.234891653), Real(0.43138805)).value();
  const Shape b = Point::create().value();
  expect_case_holds(a,
                    pose_at(Real(0.163918957), Real(0.477707863), Real(0.0526624881), Real(-0.812584162),
                            Real(-0.574059725), Real(0.00482989149), Real(0.100692943)),
                    b,
                    pose_at(Real(0.33881399), Real(0.53607893), Real(0.389382184), Real(0.597603083), Real(0.718969882),
                            Real(-0.0613401681), Real(0.34955743)));
}

// cylinder_sphere, seed 11400714819323199232, case 152.
TEST(Invariants, PenetratingCylinderSphereWitnessesAlongTheNormal) {
  const Shape a = Cylinder::create(Real(0.266970128), Real(0.515582025)).value();
  const Shape b = Sphere::create(Real(0.400624603)).value();
  expect_case_holds(a,
                    pose_at(Real(-0.0747481287), Real(-0.0742161721), Real(0.0680137202), Real(-0.53657794),
                            Real(-0.179250434), Real(0.0390798189), Real(-0.823666334)),
                    b,
                    pose_at(Real(0.0917934254), Real(-0.0925482288), Real(0.273165762), Real(0.138753787),
                            Real(0.363699079), Real(-0.371205628), Real(0.843016446)));
}

// triangle_cone, seed 11400714819323198744, case 211.
TEST(Invariants, PenetratingTriangleConeWitnessesAlongTheNormal) {
  const Shape a = Triangle::create(Vec3(Real(-0.180859894), Real(-0.157164052), Real(0.00203177356)),
                                   Vec3(Real(-0.207829699), Real(0.43431443), Real(0.518991709)),
                                   Vec3(Real(0.903351247), Real(0.117090374), Real(-0.0198749155)))
                      .value();
  const Shape b = Cone::create(Real(0.59872061), Real(1.11695445)).value();
  expect_case_holds(a,
                    pose_at(Real(0.386148214), Real(-0.238055617), Real(-0.111065365), Real(-0.0409402214),
                            Real(0.978061378), Real(0.0983644426), Real(0.179009303)),
                    b,
                    pose_at(Real(0.813615203), Real(0.14112699), Real(0.107882202), Real(0.178019911),
                            Real(0.410289198), Real(-0.881062925), Real(0.153948307)));
}

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
