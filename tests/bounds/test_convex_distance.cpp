// GJK distance between convex hulls of point sets, against Frank-Wolfe bounds computed
// independently (a certified upper and lower bound) and analytic cases; witness points
// must realise the distance and lie in their hulls.
#include <gtest/gtest.h>

#include <proxima/bounds/convex_distance.hpp>
#include <proxima/core/tolerance.hpp>

#include <vector>

#include "bounds/test_bounds_reference.hpp"
#include "support/random.hpp"
#include "sweep_size.hpp"

namespace proxima {
namespace test_convex_distance {

std::vector<test::D3> to_d(const std::vector<Vec3>& v) {
  std::vector<test::D3> out;
  for (const Vec3& p : v) out.push_back(test::D3(p));
  return out;
}

// Support value of a point set (independent of the library).
Real support_value(const std::vector<Vec3>& s, const Vec3& d) {
  Real best = -kRealMax;
  for (const Vec3& p : s) best = std::max(best, glm::dot(p, d));
  return best;
}

TEST(ConvexDistance, MatchesFrankWolfeBounds) {
  test::Random rng(801);
  int compared = 0;
  for (int i = 0; i < test::sweep_size(3000); ++i) {
    const int variant = i % 4;
    const Real scale = variant == 1 ? Real(1e-4) : (variant == 2 ? Real(1e4) : Real(1));
    const Vec3 offset = variant == 3 ? Vec3(Real(1e4), Real(2e3), Real(-1e4)) : Vec3(0);
    std::vector<Vec3> a, b;
    const int na = rng.integer(1, 12), nb = rng.integer(1, 12);
    const Vec3 ca = rng.vec3(-2, 2), cb = rng.vec3(-2, 2);
    for (int k = 0; k < na; ++k) a.push_back((ca + rng.vec3(-1, 1)) * scale + offset);
    for (int k = 0; k < nb; ++k) b.push_back((cb + rng.vec3(-1, 1)) * scale + offset);
    const ConvexDistance d = convex_distance(a, b);
    const test::DistanceBounds fw = test::frank_wolfe_distance(to_d(a), to_d(b), 20000, 1e-7 * double(scale));
    const double tol =
        1e-5 * double(scale) + 64 * double(kEpsilon) * double(glm::length(offset) + 4 * scale) + (fw.upper - fw.lower);
    EXPECT_GE(double(d.distance), fw.lower - tol) << i;
    EXPECT_LE(double(d.distance), fw.upper + tol) << i;
    // Witnesses realise the distance and lie in their hulls (no support value exceeded).
    EXPECT_NEAR(double(glm::length(d.on_a - d.on_b)), double(d.distance), tol) << i;
    for (int k = 0; k < 20; ++k) {
      const Vec3 u = rng.unit_vector();
      EXPECT_LE(glm::dot(d.on_a, u), support_value(a, u) + Real(tol)) << i;
      EXPECT_LE(glm::dot(d.on_b, u), support_value(b, u) + Real(tol)) << i;
    }
    ++compared;
  }
  EXPECT_EQ(compared, test::sweep_size(3000));
}

TEST(ConvexDistance, AnalyticCases) {
  const std::vector<Vec3> p{{0, 0, 0}};
  const std::vector<Vec3> q{{3, 4, 0}};
  EXPECT_NEAR(convex_distance(p, q).distance, Real(5), Real(1e-5));
  EXPECT_EQ(convex_distance(p, p).distance, Real(0));
  // Point above the middle of a square.
  const std::vector<Vec3> square{{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
  const std::vector<Vec3> above{{Real(0.3), Real(-0.2), 2}};
  EXPECT_NEAR(convex_distance(square, above).distance, Real(2), Real(1e-5));
  // Skew segments at distance 1.
  const std::vector<Vec3> s1{{-1, 0, 0}, {1, 0, 0}};
  const std::vector<Vec3> s2{{0, -1, 1}, {0, 1, 1}};
  const ConvexDistance d = convex_distance(s1, s2);
  EXPECT_NEAR(d.distance, Real(1), Real(1e-5));
  EXPECT_NEAR(glm::length(d.on_a), Real(0), Real(1e-5));
  // Parallel segments, overlapping ranges.
  const std::vector<Vec3> s3{{Real(-0.5), 2, 0}, {3, 2, 0}};
  EXPECT_NEAR(convex_distance(s1, s3).distance, Real(2), Real(1e-5));
  // Interpenetrating tetrahedra: 0.
  const std::vector<Vec3> t1{{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {0, 0, 2}};
  const std::vector<Vec3> t2{{Real(0.2), Real(0.2), Real(0.2)}, {3, 3, 3}, {-1, 3, 3}, {3, -1, 3}};
  EXPECT_EQ(convex_distance(t1, t2).distance, Real(0));
  EXPECT_TRUE(convex_cores_overlap(t1, Real(0), t2, Real(0)));
  // Radii: spheres at distance 5 with radii 2 + 3 touch.
  EXPECT_TRUE(convex_cores_overlap(p, Real(2), q, Real(3)));
  EXPECT_FALSE(convex_cores_overlap(p, Real(2), q, Real(2.99)));
  // Coincident, duplicated and coplanar inputs.
  const std::vector<Vec3> dup{{1, 1, 1}, {1, 1, 1}, {1, 1, 1}};
  EXPECT_NEAR(convex_distance(dup, p).distance, std::sqrt(Real(3)), Real(1e-5));
  EXPECT_NEAR(convex_distance(square, square).distance, Real(0), Real(1e-6));
  // Empty input: a defined answer.
  EXPECT_EQ(convex_distance({}, p).distance, Real(0));
}

}  // namespace test_convex_distance
}  // namespace proxima
