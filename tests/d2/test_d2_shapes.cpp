/// @file test_d2_shapes.cpp
/// Validated construction of the 2D shapes (errors name their field), the polygon hull, the
/// Shape type and bounds, and 2D poses.

#include <gtest/gtest.h>

#include <proxima/d2/shape.hpp>

#include <limits>
#include <support/random.hpp>
#include <vector>

#include "sweep_size.hpp"

namespace proxima::d2 {
namespace {

constexpr Real kInf = std::numeric_limits<Real>::infinity();

TEST(D2Shapes, BadInputNamesTheField) {
  EXPECT_EQ(Circle::create(Real(0)).error().field, "radius");
  EXPECT_EQ(Circle::create(Real(1), {kInf, 0}).error().field, "center");
  EXPECT_EQ(Segment::create({0, 0}, {0, 0}).error().code, ErrorCode::Degenerate);
  EXPECT_EQ(Segment::create({0, 0}, {kInf, 0}).error().field, "vertices[1]");
  EXPECT_EQ(Capsule::create({0, 0}, {1, 0}, Real(-1)).error().field, "radius");
  EXPECT_EQ(Polygon::box(Real(0), Real(1)).error().field, "half_extents.x");
  EXPECT_EQ(Polygon::box(Real(1), Real(1), Real(-0.5)).error().field, "radius");
  const std::vector<Vec2> two = {{0, 0}, {1, 0}};
  EXPECT_EQ(Polygon::create(two).error().code, ErrorCode::TooFew);
  const std::vector<Vec2> line = {{0, 0}, {1, 1}, {2, 2}, {3, 3}};
  EXPECT_EQ(Polygon::create(line).error().code, ErrorCode::Degenerate);
  const std::vector<Vec2> bad = {{0, 0}, {1, 0}, {0, std::numeric_limits<Real>::quiet_NaN()}};
  EXPECT_EQ(Polygon::create(bad).error().field, "points[2]");
  std::vector<Vec2> many;
  for (int i = 0; i < 17; ++i) many.push_back({std::cos(Real(0.3695) * i), std::sin(Real(0.3695) * i)});
  EXPECT_EQ(Polygon::create(many).error().code, ErrorCode::OutOfRange);
  EXPECT_EQ(Pose::create({0, 0}, kInf).error().field, "angle");
  EXPECT_EQ(Pose::create({kInf, 0}, 0).error().field, "position");
}

TEST(D2Shapes, PolygonIsTheHullOfItsPoints) {
  // A square given in scrambled order with an interior point and a point on an edge.
  const std::vector<Vec2> points = {{1, 1}, {-1, -1}, {0, 0}, {1, -1}, {0, -1}, {-1, 1}};
  const Polygon p = Polygon::create(points).value();
  ASSERT_EQ(p.count(), 4);
  for (int i = 0; i < 4; ++i) {
    const Vec2 a = p.vertex(i), b = p.vertex((i + 1) % 4);
    EXPECT_GT(cross(b - a, p.vertex((i + 2) % 4) - b), Real(0)) << "counter-clockwise";
    EXPECT_NEAR(glm::dot(p.normal(i), b - a), Real(0), Real(1e-6));
    EXPECT_NEAR(glm::length(p.normal(i)), Real(1), Real(1e-6));
    EXPECT_GT(glm::dot(p.normal(i), a - p.centroid()), Real(0)) << "outward";
  }
  EXPECT_NEAR(p.centroid().x, Real(0), Real(1e-6));
}

TEST(D2Shapes, RandomHullsKeepEveryInputInside) {
  proxima::test::Random rng(0x2D4011);
  for (int i = 0; i < proxima::test::sweep_size(2000); ++i) {
    std::vector<Vec2> points(static_cast<std::size_t>(rng.integer(3, 30)));
    for (Vec2& p : points) p = {rng.uniform(Real(-5), Real(5)), rng.uniform(Real(-5), Real(5))};
    const auto polygon = Polygon::create(points);
    if (!polygon) {
      ASSERT_EQ(polygon.error().field, "points") << "case " << i;
      continue;
    }
    const ConvexCore& core = polygon->core();
    for (const Vec2& p : points) {
      for (int e = 0; e < core.count; ++e) {
        ASSERT_LE(glm::dot(core.normals[e], p - core.vertices[e]), Real(1e-4)) << "case " << i;
      }
    }
  }
}

TEST(D2Shapes, ShapeKnowsItsKindAndBounds) {
  const Shape circle = Circle::create(Real(1), {Real(1), 0}).value();
  EXPECT_EQ(circle.type(), ShapeType::Circle);
  EXPECT_TRUE(circle.is_convex());
  const Aabb box = circle.world_aabb(Pose::from({0, Real(2)}, kPi / 2));
  EXPECT_NEAR(box.min.x, Real(-1), Real(1e-6));
  EXPECT_NEAR(box.max.y, Real(4), Real(1e-6));
  const Shape turned = Polygon::box(Real(1), Real(1)).value();
  const Aabb b2 = turned.world_aabb(Pose::from({0, 0}, kPi / 4));
  EXPECT_NEAR(b2.max.x, std::sqrt(Real(2)), Real(1e-6));
  const std::vector<Vec2> pts = {{0, 0}, {2, 0}, {2, 1}};
  const Shape chain = Chain::create(pts, false).value();
  EXPECT_EQ(chain.type(), ShapeType::Chain);
  EXPECT_FALSE(chain.is_convex());
  EXPECT_EQ(chain.world_aabb(Pose::identity()).max, Vec2(2, 1));
  EXPECT_STREQ(to_string(ShapeType::Capsule), "capsule");
}

TEST(D2Pose, ComposesAndInverts) {
  const Pose a = Pose::from({1, 2}, Real(0.3)), b = Pose::from({-3, Real(0.5)}, Real(-1.1));
  const Vec2 p(Real(0.7), Real(-0.2));
  const Vec2 direct = a.apply(b.apply(p));
  const Vec2 composed = (a * b).apply(p);
  EXPECT_NEAR(direct.x, composed.x, Real(1e-5));
  EXPECT_NEAR(direct.y, composed.y, Real(1e-5));
  const Vec2 back = a.inverse().apply(a.apply(p));
  EXPECT_NEAR(back.x, p.x, Real(1e-5));
  const Vec2 rel = relative(a, b).apply(p);
  const Vec2 expected = a.inverse_apply(b.apply(p));
  EXPECT_NEAR(rel.x, expected.x, Real(1e-5));
  EXPECT_NEAR(rel.y, expected.y, Real(1e-5));
}

}  // namespace
}  // namespace proxima::d2
