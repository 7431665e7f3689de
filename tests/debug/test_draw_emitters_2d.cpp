// The 2D emitters checked against the geometry they draw, computed here from the shapes'
// definitions: a circle's outline points lie at its radius and its triangles' area is the
// inscribed polygon's; a polygon's edges are its vertices in order; a box's triangles cover
// 4 hx hy; a capsule's outline is at its radius from its segment; a chain's lines are its
// points and its normals point to the right of each segment; a manifold's normal starts at
// its contact points; a ray ends at its hit; a sweep places the shape at the impact time;
// a world draws each object at the world's pose in its kind's colour, with its contacts
// and impacts. Everything lies at z = 0.
#include <gtest/gtest.h>

#include <proxima/d2/narrowphase.hpp>
#include <proxima/d2/sprite_chains.hpp>
#include <proxima/debug/draw_contacts_2d.hpp>
#include <proxima/debug/draw_rays_2d.hpp>
#include <proxima/debug/draw_shapes_2d.hpp>
#include <proxima/debug/draw_sweeps_2d.hpp>
#include <proxima/debug/draw_world_2d.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

namespace proxima::test_draw_emitters_2d {

using namespace proxima::debug;

constexpr double kPi = std::numbers::pi;

Vec2 flat(const Vec3& p) { return {p.x, p.y}; }

double triangle_area(const DrawTriangle& t) {  // signed, > 0 counter-clockwise seen from +z
  return 0.5 * double((t.b.x - t.a.x) * (t.c.y - t.a.y) - (t.b.y - t.a.y) * (t.c.x - t.a.x));
}

double total_area(const DrawBuffer& buffer) {
  double area = 0;
  for (const DrawTriangle& t : buffer.triangles) {
    EXPECT_GT(triangle_area(t), -1e-9);
    area += triangle_area(t);
  }
  return area;
}

bool all_in_plane(const DrawBuffer& buffer) {
  const auto zero = [](const Vec3& p) { return p.z == Real(0); };
  return std::all_of(buffer.lines.begin(), buffer.lines.end(),
                     [&](const DrawLine& l) { return zero(l.from) && zero(l.to); }) &&
         std::all_of(buffer.triangles.begin(), buffer.triangles.end(),
                     [&](const DrawTriangle& t) { return zero(t.a) && zero(t.b) && zero(t.c); }) &&
         std::all_of(buffer.points.begin(), buffer.points.end(), [&](const DrawPoint& p) { return zero(p.position); });
}

double segment_distance(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 ab = b - a;
  const double t = std::clamp(double(glm::dot(p - a, ab) / glm::dot(ab, ab)), 0.0, 1.0);
  return double(glm::length(p - (a + Real(t) * ab)));
}

TEST(DrawEmitters2D, CircleOutlineLiesOnItsRadius) {
  const Real r = Real(1.5);
  const d2::Shape circle = d2::Circle::create(r, {Real(0.5), Real(-0.25)}).value();
  const d2::Pose pose = d2::Pose::from({Real(2), Real(3)}, Real(0.7));
  const Vec2 center = pose.apply({Real(0.5), Real(-0.25)});
  Shape2DDrawOptions options;
  options.segments = 40;
  DrawBuffer buffer;
  draw_shape_2d(buffer, circle, pose, Rgba{70, 130, 230, 255}, options);
  ASSERT_EQ(buffer.lines.size(), 40u);
  ASSERT_EQ(buffer.triangles.size(), 40u);
  EXPECT_TRUE(all_in_plane(buffer));
  const double sagitta = double(r) * (1 - std::cos(kPi / 40));
  for (const DrawLine& l : buffer.lines) {
    EXPECT_NEAR(glm::length(flat(l.from) - center), r, 1e-5);
    EXPECT_NEAR(glm::length(flat(l.to) - center), r, 1e-5);
    EXPECT_NEAR(glm::length((flat(l.from) + flat(l.to)) * Real(0.5) - center), double(r) - sagitta, 1e-5);
    EXPECT_EQ(l.color, outline_color(Rgba{70, 130, 230, 255}));
    EXPECT_EQ(l.tag, (DrawTag{DrawLayer::Shapes, 0}));
  }
  EXPECT_NEAR(total_area(buffer), 40 / 2.0 * double(r * r) * std::sin(2 * kPi / 40), 1e-4);  // inscribed 40-gon
}

TEST(DrawEmitters2D, PolygonEdgesAreItsVertices) {
  const std::vector<Vec2> points = {{0, 0}, {2, 0}, {3, 1}, {1, 2.5f}, {-0.5f, 1}};  // counter-clockwise
  const d2::Shape polygon = d2::Polygon::create(points).value();
  const d2::Pose pose = d2::Pose::from({Real(-1), Real(4)}, Real(-1.1));
  DrawBuffer buffer;
  draw_shape_2d(buffer, polygon, pose, Rgba{200, 100, 50, 255});
  ASSERT_EQ(buffer.lines.size(), points.size());
  for (const DrawLine& l : buffer.lines) {
    const auto at = std::find_if(points.begin(), points.end(),
                                 [&](const Vec2& p) { return glm::length(pose.apply(p) - flat(l.from)) < 1e-5f; });
    ASSERT_NE(at, points.end());
    const Vec2 next = points[std::size_t(at - points.begin() + 1) % points.size()];
    EXPECT_LT(glm::length(pose.apply(next) - flat(l.to)), 1e-5f);
  }
  // The shoelace area of the points.
  double shoelace = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Vec2 a = points[i], b = points[(i + 1) % points.size()];
    shoelace += 0.5 * double(a.x * b.y - a.y * b.x);
  }
  EXPECT_NEAR(total_area(buffer), shoelace, 1e-4);
}

TEST(DrawEmitters2D, BoxTrianglesCoverItsArea) {
  const Real hx = Real(1.25), hy = Real(0.4);
  DrawBuffer buffer;
  draw_shape_2d(buffer, d2::Polygon::box(hx, hy, {Real(1), Real(2)}, Real(0.3)).value(),
                d2::Pose::from({Real(5), Real(-2)}, Real(2)), Rgba{});
  EXPECT_NEAR(total_area(buffer), 4 * double(hx * hy), 1e-5);
  // Rounded by r: the box, four r-wide strips and a disc, less what the arcs' chords cut off
  // (at most the disc less its inscribed polygon of 32 sides, the default).
  const Real r = Real(0.3);
  DrawBuffer rounded;
  draw_shape_2d(rounded, d2::Polygon::box(hx, hy, r).value(), d2::Pose::identity(), Rgba{});
  const double exact = 4 * double(hx * hy) + 4 * double(r * (hx + hy)) + kPi * double(r * r);
  const double chords = kPi * double(r * r) - 16 * double(r * r) * std::sin(2 * kPi / 32);
  EXPECT_LE(total_area(rounded), exact + 1e-5);
  EXPECT_GE(total_area(rounded), exact - chords - 1e-5);
}

TEST(DrawEmitters2D, CapsuleOutlineIsAtItsRadiusFromItsSegment) {
  const Vec2 a{Real(-1), Real(0.5)}, b{Real(2), Real(-0.5)};
  const Real r = Real(0.35);
  const d2::Pose pose = d2::Pose::from({Real(3), Real(1)}, Real(0.4));
  DrawBuffer buffer;
  draw_shape_2d(buffer, d2::Capsule::create(a, b, r).value(), pose, Rgba{});
  ASSERT_GE(buffer.lines.size(), 32u);
  for (const DrawLine& l : buffer.lines) {
    EXPECT_NEAR(segment_distance(pose.inverse_apply(flat(l.from)), a, b), r, 1e-5);
  }
  EXPECT_TRUE(all_in_plane(buffer));
}

TEST(DrawEmitters2D, SegmentIsALineAndPointAMarker) {
  const Vec2 a{Real(1), Real(1)}, b{Real(4), Real(-2)};
  const d2::Pose pose = d2::Pose::from({Real(1), Real(0)}, Real(kPi / 2));
  DrawBuffer buffer;
  draw_shape_2d(buffer, d2::Segment::create(a, b).value(), pose, Rgba{1, 2, 3, 255});
  draw_shape_2d(buffer, d2::Point::create({Real(2), Real(0)}).value(), pose, Rgba{4, 5, 6, 255});
  ASSERT_EQ(buffer.lines.size(), 1u);
  EXPECT_LT(glm::length(flat(buffer.lines[0].from) - Vec2(0, 1)), 1e-5f);  // (1, 1) turned a quarter, moved
  EXPECT_LT(glm::length(flat(buffer.lines[0].to) - Vec2(3, 4)), 1e-5f);
  ASSERT_EQ(buffer.points.size(), 1u);
  EXPECT_LT(glm::length(flat(buffer.points[0].position) - Vec2(1, 2)), 1e-5f);
  EXPECT_TRUE(buffer.triangles.empty());
}

TEST(DrawEmitters2D, ChainLinesAreItsPointsAndNormalsPointRight) {
  const std::vector<Vec2> points = {{4, 0}, {2, 0}, {1, 1}, {0, 1}};  // right to left: solid below
  const d2::Pose pose = d2::Pose::from({Real(0), Real(2)}, Real(0));
  DrawBuffer buffer;
  draw_shape_2d(buffer, d2::Chain::create(points, false).value(), pose, Rgba{});
  ASSERT_EQ(buffer.lines.size(), 2 * (points.size() - 1));
  for (std::size_t i = 0; i + 1 < points.size(); ++i) {
    const DrawLine& segment = buffer.lines[i];
    EXPECT_EQ(flat(segment.from), pose.apply(points[i]));
    EXPECT_EQ(flat(segment.to), pose.apply(points[i + 1]));
    const DrawLine& normal = buffer.lines[points.size() - 1 + i];
    EXPECT_EQ(normal.tag.layer, DrawLayer::Normals);
    const Vec2 d = points[i + 1] - points[i];
    const Vec2 right = Vec2(d.y, -d.x) / glm::length(d);
    EXPECT_LT(glm::length(flat(normal.from) - pose.apply((points[i] + points[i + 1]) * Real(0.5))), 1e-6f);
    EXPECT_LT(glm::length(flat(normal.to) - flat(normal.from) - Real(0.2) * right), 1e-6f);
  }
  DrawBuffer loop;
  draw_shape_2d(loop, d2::Chain::create(points, true).value(), pose, Rgba{});
  EXPECT_EQ(loop.lines.size(), 2 * points.size());
}

TEST(DrawEmitters2D, SpriteChainsAreDrawnSegmentBySegment) {
  const std::vector<std::string> rows = {"0110", "1111", "1001"};
  const d2::SpriteMask mask = d2::SpriteMask::from_rows(rows).value();
  const std::vector<d2::Chain> chains = d2::sprite_chains(mask, 0, Real(0.5)).value();
  ASSERT_FALSE(chains.empty());
  const d2::Pose pose = d2::Pose::from({Real(10), Real(0)}, Real(0));
  Shape2DDrawOptions options;
  options.chain_normal_length = Real(0);
  DrawBuffer buffer;
  draw_sprite_chains(buffer, chains, pose, Rgba{}, options);
  std::size_t segments = 0;
  for (const d2::Chain& c : chains) segments += std::size_t(c.segment_count());
  ASSERT_EQ(buffer.lines.size(), segments);
  for (const DrawLine& l : buffer.lines) {
    // Pixel corners: multiples of 0.5 from the mask's centre (2, 1.5 pixels), moved by 10.
    const Vec2 p = (flat(l.from) - Vec2(10, 0)) / Real(0.5) + Vec2(2, 1.5f);
    EXPECT_NEAR(p.x, std::round(p.x), 1e-5);
    EXPECT_NEAR(p.y, std::round(p.y), 1e-5);
  }
}

TEST(DrawEmitters2D, BoundsAreTheShapesRectangle) {
  DrawBuffer buffer;
  draw_bounds_2d(buffer, d2::Circle::create(Real(2)).value(), d2::Pose::from({Real(1), Real(-3)}, Real(1)), Rgba{});
  ASSERT_EQ(buffer.boxes.size(), 1u);
  EXPECT_EQ(buffer.boxes[0].center, Vec3(1, -3, 0));
  EXPECT_EQ(buffer.boxes[0].half_extents, Vec3(2, 2, 0));
  EXPECT_EQ(buffer.boxes[0].tag, (DrawTag{DrawLayer::Bounds, 0}));
}

TEST(DrawEmitters2D, ManifoldNormalsStartAtTheContactPoints) {
  const d2::Shape box = d2::Polygon::box(Real(1), Real(1)).value();
  const d2::Manifold manifold = d2::collide(box, d2::Pose::identity(), box, d2::Pose::from({0, Real(1.9)}, 0));
  ASSERT_EQ(manifold.count, 2);
  DrawBuffer buffer;
  draw_manifold_2d(buffer, manifold);
  ASSERT_EQ(buffer.points.size(), 4u);
  ASSERT_EQ(buffer.lines.size(), 4u);
  ASSERT_EQ(buffer.texts.size(), 2u);
  EXPECT_TRUE(all_in_plane(buffer));
  for (std::size_t i = 0; i < 2; ++i) {
    const d2::ContactPoint& p = manifold.points[i];
    EXPECT_EQ(flat(buffer.points[2 * i].position), p.point_a);
    EXPECT_EQ(flat(buffer.points[2 * i + 1].position), p.point_b);
    // The boxes overlap by 0.1 along y: the witnesses on y = 0.9 and y = 1, x = +-1.
    EXPECT_NEAR(std::abs(p.point_a.x), 1, 1e-5);
    const DrawLine& normal = buffer.lines[2 * i + 1];
    EXPECT_EQ(normal.tag.layer, DrawLayer::Normals);
    EXPECT_LT(glm::length(flat(normal.from) - (p.point_a + p.point_b) * Real(0.5)), 1e-6f);
    EXPECT_LT(glm::length(flat(normal.to) - flat(normal.from) - Vec2(0, 0.25f)), 1e-5f);
    EXPECT_NE(buffer.texts[i].text.find("depth=0.1"), std::string::npos) << buffer.texts[i].text;
  }
}

TEST(DrawEmitters2D, RayEndsAtItsHit) {
  const d2::Shape circle = d2::Circle::create(Real(1)).value();
  const d2::Ray ray{{Real(-5), Real(0)}, {Real(1), Real(0)}};
  DrawBuffer hit;
  draw_ray_2d(hit, ray, Real(100), d2::raycast(circle, d2::Pose::identity(), ray, Real(100)));
  ASSERT_EQ(hit.lines.size(), 2u);
  EXPECT_NEAR(hit.lines[0].to.x, -1, 1e-5);
  ASSERT_EQ(hit.points.size(), 1u);
  EXPECT_NEAR(hit.lines[1].to.x, -1.25, 1e-5);  // the outward normal
  DrawBuffer miss;
  draw_ray_2d(miss, d2::Ray{{Real(-5), Real(3)}, {Real(2), Real(0)}}, Real(4), std::nullopt);
  ASSERT_EQ(miss.lines.size(), 1u);
  EXPECT_EQ(miss.lines[0].to, Vec3(3, 3, 0));
  EXPECT_TRUE(miss.points.empty());
}

TEST(DrawEmitters2D, SweepPlacesTheShapeAtTheImpactTime) {
  const d2::Shape ball = d2::Circle::create(Real(0.5)).value();
  const d2::Shape wall = d2::Segment::create({0, Real(-2)}, {0, Real(2)}).value();
  const d2::Motion motion_a = d2::Motion::translating(d2::Pose::from({Real(-3), 0}, 0), {Real(6), 0});
  const d2::Motion motion_b = d2::Motion::translating(d2::Pose::identity(), {0, 0});
  const d2::ToiResult toi = d2::time_of_impact(ball, motion_a, wall, motion_b).value();
  ASSERT_EQ(toi.status, d2::CcdStatus::Hit);
  EXPECT_NEAR(toi.toi, 2.5 / 6, 1e-3);
  DrawBuffer buffer;
  draw_time_of_impact_2d(buffer, ball, motion_a, wall, motion_b, toi);
  const auto n = std::size_t(TessellationOptions{}.segments);  // the sweep's segments per turn
  ASSERT_EQ(buffer.triangles.size(), 3 * n);
  // The fan of the copy at the impact time starts at the circle's centre.
  EXPECT_NEAR(buffer.triangles[n].a.x, -3 + 6 * toi.toi, 1e-4);
  EXPECT_EQ(buffer.triangles[n].tag, (DrawTag{DrawLayer::Sweeps, 0}));
  EXPECT_EQ(buffer.triangles[0].color.a, 255 / 3);
  // A: 3 outlines of n lines and a path of 16; B: 3 lines and 16; the normal.
  EXPECT_EQ(buffer.lines.size(), 3 * n + 16 + 3 + 16 + 1);
  ASSERT_EQ(buffer.points.size(), 1u);
  EXPECT_NEAR(buffer.points[0].position.x, 0, 1e-2);
  EXPECT_TRUE(all_in_plane(buffer));
}

TEST(DrawEmitters2D, WorldObjectsAtTheirPosesWithContactsAndImpacts) {
  d2::CollisionWorld world = d2::CollisionWorld::create().value();
  std::vector<d2::ObjectDesc> objects;
  const auto add = [&](const d2::ObjectDesc& desc) {
    objects.push_back(desc);
    return world.add(desc).value();
  };
  add({d2::Polygon::box(Real(5), Real(0.5)).value(), d2::Pose::identity(), d2::ObjectKind::Static});
  const d2::ObjectHandle crate =
      add({d2::Polygon::box(Real(0.5), Real(0.5)).value(), d2::Pose::from({0, Real(0.9)}, 0)});
  d2::ObjectDesc sensor{d2::Circle::create(Real(1)).value(), d2::Pose::from({Real(4), Real(3)}, 0)};
  sensor.sensor = true;
  add(sensor);
  add({d2::Segment::create({Real(10), Real(4)}, {Real(10), Real(6)}).value(), d2::Pose::identity(),
       d2::ObjectKind::Static});
  d2::ObjectDesc bullet{d2::Circle::create(Real(0.05)).value(), d2::Pose::from({Real(5), Real(5)}, 0)};
  bullet.ccd = d2::CcdMode::Bullet;
  const d2::ObjectHandle shot = add(bullet);
  const d2::ObjectHandle gone = add({d2::Circle::create(Real(0.3)).value(), d2::Pose::from({Real(-4), Real(4)}, 0)});
  ASSERT_FALSE(world.step());
  ASSERT_FALSE(world.move(crate, d2::Pose::from({Real(0.25), Real(0.9)}, 0)));
  ASSERT_FALSE(world.move(shot, d2::Pose::from({Real(15), Real(5)}, 0)));
  ASSERT_FALSE(world.remove(gone));
  ASSERT_FALSE(world.step());
  ASSERT_EQ(world.manifolds().size(), 1u);
  ASSERT_EQ(world.events().impacts.size(), 1u);
  World2DDrawOptions options;
  options.bounds = true;
  DrawBuffer buffer;
  draw_world_2d(buffer, world, options);
  // Fans: the ground box 4, the crate 4, the sensor 32, the bullet 32; the segment is a line.
  ASSERT_EQ(buffer.triangles.size(), 4 + 4 + 32 + 32u);
  EXPECT_EQ(buffer.triangles[0].color, object_color(objects[0]));
  EXPECT_EQ(buffer.triangles[4].color, object_color(objects[1]));
  EXPECT_EQ(buffer.triangles[8].color.a, 96);  // the sensor
  EXPECT_NE(object_color(objects[0]), object_color(objects[1]));
  EXPECT_EQ(flat(buffer.triangles[4].a), Vec2(Real(0.25), Real(0.9)));  // the crate where the world has it
  EXPECT_EQ(buffer.boxes.size(), 5u);                                   // the removed object is skipped
  const d2::Manifold& m = world.manifolds()[0].manifold;
  const d2::ImpactEvent& impact = world.events().impacts[0];
  ASSERT_EQ(buffer.points.size(), 2 * std::size_t(m.count) + 1);
  EXPECT_EQ(flat(buffer.points.back().position), impact.point);
  EXPECT_NEAR(impact.point.x, 10, 1e-3);
  EXPECT_TRUE(all_in_plane(buffer));
}

// plane_pose against the 2D pose itself: over angles around the whole turn (both branches of
// the half-angle formulas, and the half turn), the quaternion is unit, turns about +z only,
// and maps local points where the 2D pose maps them.
TEST(DrawEmitters2D, PlanePoseTurnsAboutZAsThe2DPose) {
  for (int k = -400; k <= 400; ++k) {
    const Real angle = Real(k) * std::numbers::pi_v<Real> / Real(400);
    const d2::Pose pose = d2::Pose::from({Real(3), Real(-2)}, angle);
    const Transform t = plane_pose(pose);
    EXPECT_NEAR(glm::length(t.rotation), 1, 1e-6) << angle;
    EXPECT_EQ(t.rotation.x, 0);
    EXPECT_EQ(t.rotation.y, 0);
    for (const Vec2 p : {Vec2(1, 0), Vec2(0, 1), Vec2(Real(-0.5), Real(2))}) {
      const Vec3 mapped = t.apply(Vec3(p.x, p.y, 0));
      const Vec2 expected = pose.apply(p);
      EXPECT_NEAR(mapped.x, expected.x, 1e-5) << angle;
      EXPECT_NEAR(mapped.y, expected.y, 1e-5) << angle;
      EXPECT_EQ(mapped.z, 0);
    }
  }
}

// tessellate_2d: every kind with area is a fan whose signed area (seen from +z) is the
// shape's up to the chords of its round parts; a point, a bare segment and a chain have none.
TEST(DrawEmitters2D, FlatMeshesHaveTheShapesArea) {
  const auto area = [](const DrawMesh& m) {
    double a = 0;
    for (std::size_t i = 0; i + 2 < m.indices.size(); i += 3) {
      const Vec3 p = m.positions[m.indices[i]], q = m.positions[m.indices[i + 1]], r = m.positions[m.indices[i + 2]];
      const double t = 0.5 * (double(q.x - p.x) * double(r.y - p.y) - double(q.y - p.y) * double(r.x - p.x));
      EXPECT_GT(t, 0);
      a += t;
    }
    return a;
  };
  const std::vector<Vec2> tri = {{0, 0}, {2, 0}, {0, 1}};
  EXPECT_NEAR(area(tessellate_2d(d2::Polygon::create(tri, Real(0)).value(), 32)), 1, 1e-6);
  EXPECT_NEAR(area(tessellate_2d(d2::Polygon::box(Real(1.5), Real(0.5)).value(), 32)), 3, 1e-6);
  const double pi = std::numbers::pi;
  // A circle of radius 2: the inscribed 256-gon; a capsule: its box plus an inscribed circle.
  EXPECT_NEAR(area(tessellate_2d(d2::Circle::create(Real(2)).value(), 256)), 0.5 * 256 * 4 * std::sin(2 * pi / 256),
              1e-4);
  const double capsule = area(tessellate_2d(d2::Capsule::create({-1, 0}, {1, 0}, Real(0.5)).value(), 256));
  EXPECT_NEAR(capsule, 2 * 1 + 0.5 * 256 * 0.25 * std::sin(2 * pi / 256), 1e-4);
  EXPECT_TRUE(tessellate_2d(d2::Point::create({1, 1}).value(), 32).indices.empty());
  EXPECT_TRUE(tessellate_2d(d2::Segment::create({0, 0}, {1, 0}).value(), 32).indices.empty());
  const std::vector<Vec2> ground = {{0, 0}, {1, 0}, {2, 1}};
  EXPECT_TRUE(tessellate_2d(d2::Chain::create(ground, false).value(), 32).indices.empty());
}

}  // namespace proxima::test_draw_emitters_2d
