/// @file test_d2_queries.cpp
/// Ray casts, containment, closest points and mass properties of the 2D shapes against the
/// long-double references of d2_reference.hpp, grid integration and closed forms.

#include <gtest/gtest.h>

#include <proxima/d2/mass_properties.hpp>
#include <proxima/d2/narrowphase.hpp>

#include <array>

#include "d2/d2_reference.hpp"
#include "sweep_size.hpp"

namespace proxima::d2 {
namespace {

using test::LD;
using test::RefPose;

using test::kConvexKinds;

Real query_tolerance() { return sizeof(Real) == 4 ? Real(1e-4) : Real(1e-9); }

RefPose random_pose(proxima::test::Random& rng) {
  return {rng.uniform(Real(-2), Real(2)), rng.uniform(Real(-2), Real(2)), rng.uniform(Real(-3.2), Real(3.2))};
}

TEST(D2Queries, RayCastsMatchTheFirstZeroOfTheSignedDistance) {
  proxima::test::Random rng(0xD2A7);
  int hits = 0;
  for (ShapeType type : kConvexKinds) {
    if (type == ShapeType::Point || type == ShapeType::Segment) continue;  // no area: see the named cases
    for (int i = 0; i < proxima::test::sweep_size(1000); ++i) {
      const test::RandomShape s = test::random_shape(rng, type, rng.uniform(Real(0.3), Real(2)));
      const RefPose pose = random_pose(rng);
      const Vec2 origin(rng.uniform(Real(-6), Real(6)), rng.uniform(Real(-6), Real(6)));
      const Vec2 target(pose.x + rng.uniform(Real(-1.5), Real(1.5)), pose.y + rng.uniform(Real(-1.5), Real(1.5)));
      const Ray ray{origin, target - origin};
      const LD expected = test::ray_entry(s.ref, pose, {origin.x, origin.y}, {ray.direction.x, ray.direction.y}, 2);
      const auto hit = raycast(s.shape, pose.pose(), ray, Real(2));
      const Real tol = query_tolerance() * Real(10) / std::max(Real(1e-3), glm::length(ray.direction));
      if (expected < 0) {
        // A miss, or a graze the reference's bisection cannot resolve.
        if (hit) {
          const LD gap = test::point_signed_distance(s.ref, pose, {hit->point.x, hit->point.y});
          ASSERT_LE(static_cast<Real>(gap), query_tolerance() * 10) << to_string(type) << " case " << i;
        }
        continue;
      }
      ASSERT_TRUE(hit.has_value()) << to_string(type) << " case " << i << " expected t "
                                   << static_cast<double>(expected);
      ++hits;
      ASSERT_NEAR(hit->t, static_cast<Real>(expected), tol) << to_string(type) << " case " << i;
      ASSERT_NEAR(glm::length(hit->normal), Real(1), Real(1e-5));
      if (hit->t > Real(0)) {  // the normal faces the ray and is the surface's outward normal
        ASSERT_LE(glm::dot(hit->normal, ray.direction), Real(0)) << to_string(type) << " case " << i;
        const SurfacePoint sp = closest_point(s.shape, pose.pose(), hit->point + Real(1e-2) * hit->normal);
        ASSERT_GT(glm::dot(sp.normal, hit->normal), Real(0.99)) << to_string(type) << " case " << i;
      }
    }
  }
  EXPECT_GT(hits, proxima::test::sweep_share(1000));
}

TEST(D2Queries, RaysThroughSegmentsAndPoints) {
  const Shape segment = Segment::create({Real(-1), Real(0)}, {Real(1), Real(0)}).value();
  auto hit = raycast(segment, Pose::identity(), Ray{{Real(0.5), Real(2)}, {0, Real(-1)}}, Real(10));
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->t, Real(2), Real(1e-6));
  EXPECT_NEAR(hit->normal.y, Real(1), Real(1e-6));
  hit = raycast(segment, Pose::identity(), Ray{{Real(0.5), Real(-2)}, {0, Real(1)}}, Real(10));  // two-sided
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->normal.y, Real(-1), Real(1e-6));
  EXPECT_FALSE(raycast(segment, Pose::identity(), Ray{{Real(1.5), Real(2)}, {0, Real(-1)}}, Real(10)));
  const Shape point = Point::create({Real(1), Real(1)}).value();
  hit = raycast(point, Pose::identity(), Ray{{0, 0}, {Real(2), Real(2)}}, Real(1));
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->t, Real(0.5));
  EXPECT_FALSE(raycast(point, Pose::identity(), Ray{{0, 0}, {Real(2), Real(2.5)}}, Real(1)));
}

TEST(D2Queries, RayFromInsideHitsAtZeroAndBadRaysMiss) {
  const Shape box = Polygon::box(1, 1).value();
  const auto hit = raycast(box, Pose::identity(), Ray{{0, 0}, {Real(3), 0}}, Real(1));
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->t, Real(0));
  EXPECT_NEAR(hit->normal.x, Real(-1), Real(1e-6));
  EXPECT_FALSE(raycast(box, Pose::identity(), Ray{{Real(5), 0}, {0, 0}}, Real(1)));
  EXPECT_FALSE(raycast(box, Pose::identity(), Ray{{Real(5), 0}, {Real(-1), 0}}, Real(-1)));
  EXPECT_FALSE(raycast(box, Pose::identity(), Ray{{Real(5), 0}, {Real(-1), 0}}, Real(3.9)));
  EXPECT_TRUE(raycast(box, Pose::identity(), Ray{{Real(5), 0}, {Real(-1), 0}}, Real(4)));
}

TEST(D2Queries, ContainmentAndClosestPointsMatchTheReference) {
  proxima::test::Random rng(0xD2C7);
  for (ShapeType type : kConvexKinds) {
    for (int i = 0; i < proxima::test::sweep_size(3000); ++i) {
      const test::RandomShape s = test::random_shape(rng, type, rng.uniform(Real(0.3), Real(2)));
      const RefPose pose = random_pose(rng);
      const Vec2 q(pose.x + rng.uniform(Real(-3), Real(3)), pose.y + rng.uniform(Real(-3), Real(3)));
      const LD expected = test::point_signed_distance(s.ref, pose, {q.x, q.y});
      const SurfacePoint sp = closest_point(s.shape, pose.pose(), q);
      ASSERT_NEAR(sp.signed_distance, static_cast<Real>(expected), query_tolerance())
          << to_string(type) << " case " << i;
      ASSERT_NEAR(static_cast<Real>(test::point_signed_distance(s.ref, pose, {sp.point.x, sp.point.y})), Real(0),
                  query_tolerance())
          << to_string(type) << " case " << i;
      ASSERT_NEAR(glm::length(q - sp.point), std::abs(sp.signed_distance), query_tolerance())
          << to_string(type) << " case " << i;
      if (std::abs(expected) > query_tolerance()) {
        ASSERT_EQ(contains(s.shape, pose.pose(), q), expected < 0) << to_string(type) << " case " << i;
      }
    }
  }
}

/// Area, centroid and polar moment by midpoint-rule integration over a grid of n x n cells
/// covering the shape's rectangle (reference point containment).
test::LD grid_moments(const test::RefShape& s, const Aabb& box, int n, test::LD& cx, test::LD& cy, test::LD& polar) {
  const LD w = (box.max.x - box.min.x) / n, h = (box.max.y - box.min.y) / n;
  LD area = 0, sx = 0, sy = 0, sxx = 0;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      const test::P p{box.min.x + (i + LD(0.5)) * w, box.min.y + (j + LD(0.5)) * h};
      if (test::point_signed_distance(s, RefPose{}, p) > 0) continue;
      area += w * h;
      sx += w * h * p.x;
      sy += w * h * p.y;
      sxx += w * h * (p.x * p.x + p.y * p.y);
    }
  }
  cx = sx / area;
  cy = sy / area;
  polar = sxx - area * (cx * cx + cy * cy);
  return area;
}

TEST(D2MassProperties, MatchGridIntegration) {
  proxima::test::Random rng(0xD2A55);
  for (ShapeType type :
       {ShapeType::Circle, ShapeType::Capsule, ShapeType::Polygon, ShapeType::Polygon, ShapeType::Polygon}) {
    for (int i = 0; i < 2; ++i) {
      const test::RandomShape s = test::random_shape(rng, type, Real(1));
      const MassProperties m = mass_properties(s.shape.core(), Real(2));
      LD cx, cy, polar;
      const LD area = grid_moments(s.ref, s.shape.world_aabb(Pose::identity()), 400, cx, cy, polar);
      EXPECT_NEAR(m.area, static_cast<Real>(area), Real(6e-3) * m.area) << to_string(type) << " " << i;
      EXPECT_NEAR(m.mass, Real(2) * m.area, Real(1e-5) * m.mass);
      EXPECT_NEAR(m.centroid.x, static_cast<Real>(cx), Real(6e-3)) << to_string(type) << " " << i;
      EXPECT_NEAR(m.centroid.y, static_cast<Real>(cy), Real(6e-3)) << to_string(type) << " " << i;
      EXPECT_NEAR(m.inertia, Real(2) * static_cast<Real>(polar), Real(1.2e-2) * m.inertia)
          << to_string(type) << " " << i;
    }
  }
}

TEST(D2MassProperties, ClosedForms) {
  const Real pi = kPi;
  MassProperties m = mass_properties(Circle::create(Real(2), {Real(1), 0}).value().core());
  EXPECT_NEAR(m.area, pi * 4, Real(1e-5));
  EXPECT_NEAR(m.centroid.x, Real(1), Real(1e-6));
  EXPECT_NEAR(m.inertia, Real(0.5) * m.mass * 4, Real(1e-4));
  m = mass_properties(Polygon::box(Real(1), Real(2)).value().core(), Real(3));
  EXPECT_NEAR(m.mass, Real(24), Real(1e-5));
  EXPECT_NEAR(m.inertia, Real(24) * (Real(4) + Real(16)) / Real(12), Real(1e-4));
  // A capsule: a 2 x 1 rectangle and a disc of radius 0.5 (two half discs at +-1).
  m = mass_properties(Capsule::create({Real(-1), 0}, {Real(1), 0}, Real(0.5)).value().core());
  const Real rect = 2, disc = pi / 4, half = disc / 2, offset = Real(4) * Real(0.5) / (Real(3) * pi);
  const Real half_own = half * Real(0.25) / Real(2) - half * offset * offset;
  const Real expected = rect * (Real(4) + Real(1)) / Real(12) + 2 * (half_own + half * (1 + offset) * (1 + offset));
  EXPECT_NEAR(m.area, rect + disc, Real(1e-5));
  EXPECT_NEAR(m.inertia, expected, Real(1e-4));
  m = mass_properties(Segment::create({0, 0}, {Real(2), 0}).value().core());
  EXPECT_EQ(m.area, Real(0));
  EXPECT_EQ(m.centroid.x, Real(1));
}

}  // namespace
}  // namespace proxima::d2
