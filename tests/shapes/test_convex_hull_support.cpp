// ConvexHull::support_index against a brute-force scan written here: for hulls from 4 to
// 200 vertices (random clouds on and in a sphere, and prisms whose cap faces make exact
// ties), the answer's dot product equals the largest over every vertex; up to
// kLinearScanMaxVertices (the vectorised scan) the answer is also the first vertex of
// largest dot product, the documented tie rule. Directions: random, the coordinate axes
// (ties on prisms), and zero (vertex 0).
#include <gtest/gtest.h>

#include <proxima/core/tolerance.hpp>
#include <proxima/shapes/convex_hull.hpp>

#include <cmath>
#include <span>
#include <string>
#include <vector>

#include "brute_support.hpp"
#include "support/random.hpp"

namespace proxima {
namespace test_convex_hull_support {

using test::brute_support;

void check_hull(const ConvexHull& hull, test::Random& rng, const std::string& what) {
  const std::span<const Vec3> v = hull.vertices();
  const bool scan = v.size() <= ConvexHull::kLinearScanMaxVertices;
  std::vector<Vec3> dirs;
  for (int i = 0; i < 200; ++i) dirs.push_back(rng.unit_vector());
  for (int a = 0; a < 3; ++a) {
    for (const Real s : {Real(1), Real(-1)}) {
      Vec3 d(Real(0));
      d[a] = s;
      dirs.push_back(d);
    }
  }
  std::uint32_t hint = 0;
  for (const Vec3& d : dirs) {
    Real best_dot = Real(0);
    static_cast<void>(brute_support(v, d, best_dot));
    const std::uint32_t got = hull.support_index(d, hint);
    ASSERT_LT(got, v.size()) << what;
    // Relative to the hull's own reference point the dot products may differ in the last
    // bit from those of the raw vertices: compare with a tolerance at the hull's size.
    EXPECT_NEAR(glm::dot(v[got], d), best_dot, Real(8) * kEpsilon * hull.scale()) << what;
    if (scan) {
      // The scan works on the same shifted vertices in both orders: exact first index.
      Real shifted_best = Real(0);
      std::vector<Vec3> sv(v.begin(), v.end());
      const Vec3 ref = hull.local_aabb().center();
      for (Vec3& p : sv) p -= ref;
      EXPECT_EQ(got, brute_support(sv, d, shifted_best)) << what << " d=" << d.x << "," << d.y << "," << d.z;
    }
    hint = got;
  }
  EXPECT_EQ(hull.support_index(Vec3(Real(0))), 0u) << what << " zero direction";
}

TEST(ConvexHullSupport, MatchesBruteForceAtEverySize) {
  test::Random rng(2024);
  for (int n = 4; n <= 200; n += (n < 80 ? 1 : 7)) {
    std::vector<Vec3> pts;
    for (int i = 0; i < n; ++i) pts.push_back(rng.vector_of_length(Real(0.5), Real(2)));
    const auto hull = ConvexHull::create(pts);
    ASSERT_TRUE(hull.ok()) << n;
    check_hull(hull.value(), rng, "cloud n=" + std::to_string(n));
  }
}

TEST(ConvexHullSupport, PrismTiesGiveTheFirstVertex) {
  test::Random rng(7);
  for (int k = 3; k <= 60; k += 3) {
    std::vector<Vec3> pts;
    for (int i = 0; i < k; ++i) {
      const Real a = Real(6.283185307179586) * Real(i) / Real(k);
      pts.emplace_back(std::cos(a), std::sin(a), Real(1));
      pts.emplace_back(std::cos(a), std::sin(a), Real(-1));
    }
    const auto hull = ConvexHull::create(pts);
    ASSERT_TRUE(hull.ok()) << k;
    check_hull(hull.value(), rng, "prism k=" + std::to_string(k));
  }
}

}  // namespace test_convex_hull_support
}  // namespace proxima
