/// @file test_d2_chain.cpp
/// Chains: validation, one-sidedness, the smooth-seam rule (a box sliding over 1,000 tile
/// seams), corners, and distance / rays against the segments taken one by one.

#include <gtest/gtest.h>

#include <proxima/d2/narrowphase.hpp>

#include <support/random.hpp>
#include <vector>

#include "sweep_size.hpp"

namespace proxima::d2 {
namespace {

/// A floor of `tiles` unit tiles at height 0 between x = 0 and x = tiles, running right to
/// left so its normal points up.
Chain tiled_floor(int tiles) {
  std::vector<Vec2> points;
  for (int i = tiles; i >= 0; --i) points.push_back({static_cast<Real>(i), Real(0)});
  return Chain::create(points, false).value();
}

TEST(D2Chain, ValidationNamesTheField) {
  const std::vector<Vec2> one = {{0, 0}};
  auto r = Chain::create(one, false);
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().field, "points");
  const std::vector<Vec2> repeated = {{0, 0}, {1, 0}, {1, 0}};
  r = Chain::create(repeated, false);
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().field, "points[2]");
  const std::vector<Vec2> closed_twice = {{0, 0}, {1, 0}, {1, 1}, {0, 0}};
  r = Chain::create(closed_twice, true);
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().field, "points[3]");
  const std::vector<Vec2> bad = {{0, 0}, {std::numeric_limits<Real>::infinity(), 0}};
  r = Chain::create(bad, false);
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().field, "points[1]");
}

TEST(D2Chain, SegmentsKnowTheirGhostVertices) {
  const std::vector<Vec2> square = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  const Chain loop = Chain::create(square, true).value();
  ASSERT_EQ(loop.segment_count(), 4);
  const ChainSegment s = loop.segment(0);
  EXPECT_TRUE(s.has_prev && s.has_next);
  EXPECT_EQ(s.ghost_prev, Vec2(0, 1));
  EXPECT_EQ(s.ghost_next, Vec2(1, 1));
  EXPECT_EQ(s.normal(), Vec2(0, -1));  // outward of a counter-clockwise loop
  const Chain open = Chain::create(square, false).value();
  ASSERT_EQ(open.segment_count(), 3);
  EXPECT_FALSE(open.segment(0).has_prev);
  EXPECT_FALSE(open.segment(2).has_next);
}

TEST(D2Chain, OnlyTheRightSideCollides) {
  const Shape floor = tiled_floor(4);
  const Shape box = Polygon::box(Real(0.5), Real(0.5)).value();
  Manifold above = collide(floor, Pose::identity(), box, Pose::from({Real(2.2), Real(0.45)}, 0));
  ASSERT_EQ(above.count, 2);
  EXPECT_NEAR(above.normal.y, Real(1), Real(1e-6));
  EXPECT_NEAR(above.points[0].depth, Real(0.05), Real(1e-5));
  // Below the floor (centre under it), nothing; a ray from below passes through.
  EXPECT_EQ(collide(floor, Pose::identity(), box, Pose::from({Real(2.2), Real(-0.45)}, 0)).count, 0);
  EXPECT_FALSE(raycast(floor, Pose::identity(), Ray{{Real(2), Real(-1)}, {0, Real(1)}}, Real(5)));
  const auto hit = raycast(floor, Pose::identity(), Ray{{Real(2.5), Real(1)}, {0, Real(-1)}}, Real(5));
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->t, Real(1), Real(1e-6));
  EXPECT_EQ(hit->part, 1);  // segments run right to left: x in [2, 3] is segment 1
  // Distance is two-sided: the box below is 0.05 from the floor.
  EXPECT_NEAR(distance(floor, Pose::identity(), box, Pose::from({Real(2.2), Real(-0.55)}, 0)).signed_distance,
              Real(0.05), Real(1e-5));
}

/// The sliding test: a box (slightly sunk, slightly turned, as a solver leaves it) moves right
/// over every seam of a 1,000-tile floor; every contact normal of every segment must point
/// up (never against the motion). The same floor built from separate two-sided segments
/// does catch: the check can fail.
TEST(D2Chain, ABoxSlidingOverAThousandSeamsNeverCatches) {
  const int tiles = 1000;
  const Shape floor = tiled_floor(tiles);
  const Shape box = Polygon::box(Real(0.4), Real(0.25)).value();
  std::vector<Manifold> manifolds;
  int contacts = 0, caught_by_segments = 0;
  const int steps = proxima::test::sweep_size(tiles * 8);
  for (int k = 0; k < steps; ++k) {
    const Real x = Real(0.5) + static_cast<Real>(k) * Real(0.124);
    const Real sink = Real(0.01) + Real(0.005) * std::sin(static_cast<Real>(k));
    const Pose pose = Pose::from({x, Real(0.25) - sink}, Real(0.002) * std::sin(Real(0.7) * static_cast<Real>(k)));
    manifolds.clear();
    collide_all(floor, Pose::identity(), box, pose, Real(0), manifolds);
    ASSERT_FALSE(manifolds.empty()) << "step " << k;
    for (const Manifold& m : manifolds) {
      contacts += m.count;
      ASSERT_GT(m.normal.y, Real(0.99)) << "step " << k << " segment " << m.part_a << " normal " << m.normal.x;
    }
    // The naive floor: the segment under the seam as a plain segment.
    const int seam = static_cast<int>(std::floor(x + Real(0.4)));
    if (seam >= 1 && seam < tiles) {
      const Shape plain = Segment::create({static_cast<Real>(seam) + 1, 0}, {static_cast<Real>(seam), 0}).value();
      const Manifold m = collide(plain, Pose::identity(), box, pose);
      caught_by_segments += m.count > 0 && m.normal.y < Real(0.9);
    }
  }
  EXPECT_GT(contacts, steps);
  EXPECT_GT(caught_by_segments, 0) << "the plain segments should catch at some seam";
}

TEST(D2Chain, ConvexCornerAdmitsTheNormalsBetweenItsSegments) {
  // A ledge: floor (right to left) then down a wall; the corner at (0, 0) is convex.
  const std::vector<Vec2> ledge = {{Real(3), 0}, {0, 0}, {0, Real(-3)}};
  const Shape chain = Chain::create(ledge, false).value();
  const Shape circle = Circle::create(Real(0.5)).value();
  const Manifold m = collide(chain, Pose::identity(), circle, Pose::from({Real(-0.3), Real(0.3)}, 0));
  ASSERT_EQ(m.count, 1);
  EXPECT_NEAR(m.normal.x, -std::sqrt(Real(0.5)), Real(1e-5));
  EXPECT_NEAR(m.normal.y, std::sqrt(Real(0.5)), Real(1e-5));
  EXPECT_NEAR(m.points[0].depth, Real(0.5) - std::sqrt(Real(0.18)), Real(1e-5));
}

TEST(D2Chain, ConcaveCornerGivesEachSegmentItsOwnNormal) {
  // A floor meeting a wall on its left: corner at (0, 0), concave from above.
  const std::vector<Vec2> corner = {{Real(3), 0}, {0, 0}, {0, Real(3)}};
  const Shape chain = Chain::create(corner, false).value();
  const Shape box = Polygon::box(Real(0.5), Real(0.5)).value();
  std::vector<Manifold> ms;
  collide_all(chain, Pose::identity(), box, Pose::from({Real(0.49), Real(0.48)}, 0), Real(0), ms);
  ASSERT_EQ(ms.size(), 2u);
  for (const Manifold& m : ms) {
    const bool floor_normal = m.normal.y > Real(0.999);
    const bool wall_normal = m.normal.x > Real(0.999);
    EXPECT_TRUE(floor_normal || wall_normal) << m.normal.x << " " << m.normal.y;
  }
}

TEST(D2Chain, DistanceAndRaysEqualTheNearestSegment) {
  proxima::test::Random rng(0xC4A1);
  std::vector<Vec2> points;
  for (int i = 0; i < 12; ++i) points.push_back({static_cast<Real>(i), rng.uniform(Real(-1), Real(1))});
  const Chain chain = Chain::create(points, false).value();
  const Shape shape = chain;
  const Shape circle = Circle::create(Real(0.3)).value();
  for (int i = 0; i < proxima::test::sweep_size(2000); ++i) {
    const Pose pose = Pose::from({rng.uniform(Real(-1), Real(12)), rng.uniform(Real(-3), Real(3))}, 0);
    Real best = kRealMax;
    for (int s = 0; s < chain.segment_count(); ++s) {
      const Shape seg = Segment::create(chain.segment(s).a, chain.segment(s).b).value();
      best = std::min(best, distance(seg, Pose::identity(), circle, pose).signed_distance);
    }
    ASSERT_NEAR(distance(shape, Pose::identity(), circle, pose).signed_distance, best, Real(1e-5)) << "case " << i;
  }
}

}  // namespace
}  // namespace proxima::d2
