// Warm-started hull queries give the cold answers: random hull pairs (8 to 300 vertices,
// so both the scan and the hill-climbing support run) move along small coherent paths;
// each frame is queried cold and with one PairCache per pair carried across frames.
// Checks: the warm and cold distances agree within the tolerance; intersect agrees with
// itself and with the sign of the distance outside the tolerance band around contact
// (inside it either answer is right); and for separated pairs the warm distance equals the
// gap between the two hulls' supporting planes along its own normal, computed here by a
// scan over every vertex (a lower bound of the true distance: equality proves optimality).

#include <gtest/gtest.h>

#include <proxima/core/tolerance.hpp>
#include <proxima/narrowphase/narrowphase.hpp>
#include <proxima/shapes/convex_hull.hpp>

#include <cmath>
#include <string>
#include <vector>

#include "support/random.hpp"

namespace proxima {
namespace test_hull_warm_start {

ConvexHull random_hull(test::Random& rng, int n) {
  std::vector<Vec3> pts;
  const Real az = rng.uniform(Real(0.3), Real(1.5));
  const Real ay = rng.uniform(Real(0.3), Real(1.5));
  const Real ax = rng.uniform(Real(0.3), Real(1.5));
  const Vec3 axes(ax, ay, az);
  for (int i = 0; i < n; ++i) pts.push_back(rng.unit_vector() * axes);
  auto hull = ConvexHull::create(pts);
  EXPECT_TRUE(hull.ok());
  return hull.value();
}

// Largest dot product of the hull (world frame) with the world direction d.
Real world_support(const ConvexHull& h, const Transform& pose, const Vec3& d) {
  Real best = -kRealMax;
  for (const Vec3& v : h.vertices()) best = std::max(best, glm::dot(pose.apply(v), d));
  return best;
}

TEST(HullWarmStart, WarmEqualsColdAlongCoherentPaths) {
  test::Random rng(321);
  int compared = 0;
  int boolean_band = 0;
  for (int pair = 0; pair < 60; ++pair) {
    const int na = pair % 3 == 0 ? 8 : (pair % 3 == 1 ? 40 : 300);
    const int nb = pair % 2 == 0 ? 32 : 130;
    const ConvexHull a = random_hull(rng, na);
    const ConvexHull b = random_hull(rng, nb);
    const Transform pose_a = rng.pose(Real(0.5));
    Transform pose_b = rng.pose(Real(0.5));
    const Real apart = rng.uniform(Real(0.5), Real(3));
    pose_b.position = pose_a.position + rng.unit_vector() * apart;
    const Vec3 velocity = rng.unit_vector() * Real(0.02);
    const Vec3 spin_axis = rng.unit_vector();
    PairCache bool_cache;
    PairCache dist_cache;
    PairRequest request;
    for (int frame = 0; frame < 40; ++frame) {
      pose_b.position += velocity;
      pose_b.rotation = glm::normalize(glm::angleAxis(Real(0.01), spin_axis) * pose_b.rotation);
      const bool cold_hit = intersect(a, pose_a, b, pose_b, request);
      const bool warm_hit = intersect(a, pose_a, b, pose_b, request, &bool_cache);
      const DistanceResult cold = distance(a, pose_a, b, pose_b, request);
      const DistanceResult warm = distance(a, pose_a, b, pose_b, request, &dist_cache);
      const Real tol = linear_tolerance(Real(8));
      const std::string what = "pair " + std::to_string(pair) + " frame " + std::to_string(frame);
      ASSERT_TRUE(std::isfinite(cold.signed_distance) && std::isfinite(warm.signed_distance)) << what;
      EXPECT_NEAR(warm.signed_distance, cold.signed_distance, Real(4) * tol) << what;
      if (std::abs(cold.signed_distance) > Real(4) * tol) {
        EXPECT_EQ(warm_hit, cold_hit) << what << " d=" << cold.signed_distance;
        EXPECT_EQ(cold_hit, cold.signed_distance <= Real(0)) << what << " d=" << cold.signed_distance;
      } else {
        ++boolean_band;
      }
      if (warm.signed_distance > Real(4) * tol) {
        // The warm distance is no more than the true one (it is |v| of GJK, an upper bound,
        // but must not fall below the supporting-plane bound along its own normal).
        const Vec3 n = warm.normal;
        const Real gap = -world_support(b, pose_b, -n) - world_support(a, pose_a, n);
        EXPECT_LE(gap, warm.signed_distance + Real(4) * tol) << what;
        EXPECT_GE(gap, warm.signed_distance - Real(4) * tol) << what;
      }
      ++compared;
    }
  }
  EXPECT_EQ(compared, 60 * 40);
  EXPECT_LT(boolean_band, compared / 10);
}

}  // namespace test_hull_warm_start
}  // namespace proxima
