// The dispatch table: every cell filled, mirrored cells flagged exactly for A after B, and
// every query on (B, A) equal to the mirrored query on (A, B) for every pair of shape types.
#include <gtest/gtest.h>

#include <proxima/narrowphase/narrowphase.hpp>

#include <cmath>
#include <limits>
#include <vector>

#include "support/random.hpp"

namespace proxima {
namespace {

std::vector<Shape> one_of_each() {
  std::vector<Shape> s;
  s.emplace_back(Point::create().value());
  s.emplace_back(Segment::create(Vec3(-0.5, 0, 0), Vec3(0.5, 0.1, 0)).value());
  s.emplace_back(Triangle::create(Vec3(-0.5, -0.4, 0), Vec3(0.6, -0.3, 0.05), Vec3(0, 0.6, 0)).value());
  s.emplace_back(Sphere::create(Real(0.5)).value());
  s.emplace_back(Capsule::create(Real(0.3), Real(0.4)).value());
  s.emplace_back(Box::create(Vec3(0.4, 0.3, 0.5)).value());
  s.emplace_back(Cylinder::create(Real(0.4), Real(0.5)).value());
  s.emplace_back(Cone::create(Real(0.4), Real(0.5)).value());
  s.emplace_back(Ellipsoid::create(Vec3(0.5, 0.3, 0.4)).value());
  std::vector<Vec3> pts{{-0.5, -0.4, -0.3}, {0.5, -0.4, -0.2}, {0, 0.5, -0.3}, {0.1, 0, 0.6}, {0.3, 0.3, 0.3}};
  s.emplace_back(ConvexHull::create(pts).value());
  s.emplace_back(HalfSpace::create(Vec3(0, 0, 1), Real(0)).value());
  return s;
}

TEST(Dispatch, EveryCellFilledAndMirroredFlagged) {
  for (int i = 0; i < kShapeTypeCount; ++i) {
    for (int j = 0; j < kShapeTypeCount; ++j) {
      const PairFunctions& f = pair_functions(static_cast<ShapeType>(i), static_cast<ShapeType>(j));
      EXPECT_NE(f.intersect, nullptr);
      EXPECT_NE(f.distance, nullptr);
      EXPECT_NE(f.collide, nullptr);
      EXPECT_EQ(f.mirrored, i > j) << i << " " << j;
      EXPECT_EQ(f.analytic, pair_functions(static_cast<ShapeType>(j), static_cast<ShapeType>(i)).analytic);
    }
  }
}

TEST(Dispatch, MirroringHoldsForEveryPair) {
  const std::vector<Shape> shapes = one_of_each();
  ASSERT_EQ(static_cast<int>(shapes.size()), kShapeTypeCount);
  test::Random rng(20261121);
  for (int i = 0; i < kShapeTypeCount; ++i) {
    for (int j = 0; j < kShapeTypeCount; ++j) {
      for (int trial = 0; trial < 12; ++trial) {
        const Transform pa = rng.pose(Real(0.8));
        const Transform pb = rng.pose(Real(0.8));
        const ShapeRef a(shapes[std::size_t(i)]);
        const ShapeRef b(shapes[std::size_t(j)]);
        const DistanceResult ab = distance(a, pa, b, pb);
        const DistanceResult ba = distance(b, pb, a, pa);
        ASSERT_TRUE(std::isfinite(ab.signed_distance)) << i << " " << j;
        // Same routine up to the swap when one of the two cells is the mirror of the other;
        // for A == B both are direct calls with swapped arguments, equal within tolerance.
        const Real tol = i == j ? Real(1e-3) : Real(0);
        EXPECT_NEAR(ab.signed_distance, ba.signed_distance, tol)
            << i << " " << j << " status " << int(ab.status) << "/" << int(ba.status) << " method " << int(ab.method)
            << "/" << int(ba.method);
        if (i != j) {
          EXPECT_EQ(ab.point_a, ba.point_b);
          EXPECT_EQ(ab.point_b, ba.point_a);
          EXPECT_EQ(ab.normal, -ba.normal);
          EXPECT_EQ(ab.status, ba.status);
          EXPECT_EQ(ab.method, ba.method);
        }
        EXPECT_EQ(intersect(a, pa, b, pb), intersect(b, pb, a, pa)) << i << " " << j;
        const ContactManifold mab = collide(a, pa, b, pb);
        const ContactManifold mba = collide(b, pb, a, pa);
        EXPECT_EQ(mab.count, mba.count);
        if (i != j) {
          EXPECT_EQ(mab.normal, -mba.normal);
          for (int k = 0; k < mab.count && k < mba.count; ++k) {
            EXPECT_EQ(mab.points[std::size_t(k)].point_a, mba.points[std::size_t(k)].point_b);
            EXPECT_EQ(mab.points[std::size_t(k)].feature_id, mirror_feature_id(mba.points[std::size_t(k)].feature_id));
          }
        }
      }
    }
  }
}

TEST(Dispatch, NonFinitePoseGivesInvalidInputEverywhere) {
  const std::vector<Shape> shapes = one_of_each();
  Transform bad;
  {
    test::ScopedNoFpTraps no_traps;
    bad.position.x = std::numeric_limits<Real>::quiet_NaN();
  }
  for (int i = 0; i < kShapeTypeCount; ++i) {
    for (int j = 0; j < kShapeTypeCount; ++j) {
      const ShapeRef a(shapes[std::size_t(i)]);
      const ShapeRef b(shapes[std::size_t(j)]);
      const DistanceResult d = distance(a, bad, b, Transform{});
      EXPECT_EQ(d.status, PairStatus::InvalidInput) << i << " " << j;
      EXPECT_FALSE(intersect(a, Transform{}, b, bad)) << i << " " << j;
      const ContactManifold m = collide(a, bad, b, Transform{});
      EXPECT_EQ(m.count, 0);
      EXPECT_EQ(m.status, PairStatus::InvalidInput);
    }
  }
}

TEST(Dispatch, SeparatedAndOverlappingSpheresThroughEveryEntryPoint) {
  const Sphere s = Sphere::create(Real(1)).value();
  const Box box = Box::create(Vec3(1)).value();
  Transform far;
  far.position = Vec3(5, 0, 0);
  EXPECT_FALSE(intersect(s, Transform{}, box, far));
  const DistanceResult d = distance(s, Transform{}, box, far);
  EXPECT_NEAR(d.signed_distance, 3, 1e-4);
  EXPECT_NEAR(d.normal.x, 1, 1e-4);
  Transform near;
  near.position = Vec3(1.5, 0, 0);
  EXPECT_TRUE(intersect(s, Transform{}, box, near));
  EXPECT_NEAR(distance(box, near, s, Transform{}).signed_distance, -0.5, 1e-4);
  EXPECT_EQ(collide(s, Transform{}, box, near).count >= 1, true);
}

}  // namespace
}  // namespace proxima
