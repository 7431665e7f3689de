// CollisionWorld's scene queries against brute force over every object (no broad phase):
// ray casts (closest, any, all), line of sight, overlaps of a geometry, a box and a point,
// sweeps and the closest object; query filters; answers after a long-running scene.
#include <gtest/gtest.h>

#include <proxima/ccd/shape_cast.hpp>

#include <sweep_size.hpp>

#include "world/world_scene.hpp"

namespace proxima::test {
namespace test_world_queries {

struct Scene {
  CollisionWorld world = make_world();
  std::vector<Mover> movers;
};

Scene make_scene(std::uint64_t seed, int count) {
  Scene s;
  Random rng(seed);
  s.movers = populate(s.world, rng, count, kExtent);
  EXPECT_FALSE(s.world.step(Real(1) / Real(60)).has_value());
  return s;
}

std::vector<ObjectHandle> handles_of(const std::vector<WorldOverlap>& v) {
  std::vector<ObjectHandle> out;
  for (const WorldOverlap& o : v) out.push_back(o.object);
  return out;
}

/// Checks every query kind on `world` against brute force for `queries` random queries.
void check_queries(const CollisionWorld& world, Random& rng, int queries) {
  const std::vector<ObjectHandle> all = world.objects();
  for (int q = 0; q < queries; ++q) {
    // Rays: closest hit equals the brute-force minimum; all hits are the brute-force set.
    const Ray ray{rng.vec3(-kExtent, kExtent), rng.vector_of_length(Real(1), Real(4))};
    Real best = std::numeric_limits<Real>::infinity();
    std::vector<ObjectHandle> hit_set;
    for (ObjectHandle h : all) {
      const ObjectDesc d = *world.object(h);
      if (auto hit = raycast(d.geometry, d.pose, ray, Real(3))) {
        best = std::min(best, hit->t);
        hit_set.push_back(h);
      }
    }
    const auto closest = world.raycast(ray, Real(3));
    ASSERT_TRUE(closest.ok());
    if (hit_set.empty()) {
      EXPECT_TRUE(closest->empty());
    } else {
      ASSERT_EQ(closest->size(), 1u);
      EXPECT_EQ(closest->front().t, best);
    }
    auto every = world.raycast(ray, Real(3), {}, QueryMode::All);
    std::vector<ObjectHandle> got;
    for (const WorldHit& h : *every) got.push_back(h.object);
    std::sort(got.begin(), got.end());
    EXPECT_EQ(got, hit_set);
    EXPECT_EQ(world.raycast(ray, Real(3), {}, QueryMode::Any)->size(), hit_set.empty() ? 0u : 1u);
    EXPECT_EQ(*world.line_of_sight(ray.origin, ray.at(Real(3))), hit_set.empty());

    // Overlap of a geometry, a box and a point.
    const Shape probe = random_geometry(rng, Real(1.5));
    const Transform pose{rng.vec3(-kExtent, kExtent), rng.rotation()};
    const Aabb box{pose.position - Vec3(1), pose.position + Vec3(Real(1.5))};
    const Box box_shape = *Box::create(Vec3(Real(1.25)));
    const Transform box_pose{pose.position + Vec3(Real(0.25)), kIdentityQuat};
    std::vector<ObjectHandle> want_geometry, want_box, want_point;
    for (ObjectHandle h : all) {
      const ObjectDesc d = *world.object(h);
      if (intersect(probe, pose, d.geometry, d.pose)) want_geometry.push_back(h);
      if (intersect(box_shape, box_pose, d.geometry, d.pose)) want_box.push_back(h);
      if (intersect(*Point::create(), Transform{pose.position, kIdentityQuat}, d.geometry, d.pose))
        want_point.push_back(h);
    }
    EXPECT_EQ(handles_of(*world.overlap(probe, pose)), want_geometry);
    EXPECT_EQ(handles_of(*world.overlap_box(box)), want_box);
    EXPECT_EQ(handles_of(*world.overlap_point(pose.position)), want_point);

    // Sweep of a convex probe; closest object.
    const Shape mover = *Capsule::create(Real(0.3), Real(0.4));
    const Vec3 translation = rng.vector_of_length(Real(1), Real(5));
    Real first = Real(2);
    for (ObjectHandle h : all) {
      const ObjectDesc d = *world.object(h);
      auto r = shape_cast(mover, pose, translation, d.geometry, d.pose);
      if (r.ok() && (r->status == CcdStatus::Hit || r->status == CcdStatus::InitiallyOverlapping))
        first = std::min(first, r->t);
    }
    auto swept = world.sweep(mover, pose, translation);
    ASSERT_TRUE(swept.ok());
    if (first > 1) {
      EXPECT_TRUE(swept->empty());
    } else {
      ASSERT_EQ(swept->size(), 1u);
      EXPECT_EQ(swept->front().t, first);
    }
    Real nearest = std::numeric_limits<Real>::infinity();
    for (ObjectHandle h : all) {
      const ObjectDesc d = *world.object(h);
      nearest = std::min(
          nearest,
          distance(*Point::create(), Transform{pose.position, kIdentityQuat}, d.geometry, d.pose).signed_distance);
    }
    auto near = world.closest_point(pose.position, Real(2));
    ASSERT_TRUE(near.ok());
    if (nearest > Real(2)) {
      EXPECT_FALSE(near->has_value());
    } else {
      ASSERT_TRUE(near->has_value());
      EXPECT_EQ((*near)->signed_distance, nearest);
    }
  }
}

TEST(WorldQueries, EveryQueryMatchesTheBruteForce) {
  Scene s = make_scene(21, sweep_size(150));
  Random rng(22);
  check_queries(s.world, rng, sweep_size(300));
}

TEST(WorldQueries, AnswersStayRightInALongRunningScene) {
  Scene s = make_scene(23, sweep_size(100));
  for (int f = 0; f < sweep_size(300); ++f) {
    advance(s.world, s.movers, kExtent);
    ASSERT_FALSE(s.world.step(Real(1) / Real(60)).has_value());
  }
  Random rng(24);
  check_queries(s.world, rng, sweep_size(100));
}

TEST(WorldQueries, FiltersMasksGroupsAndTheIgnoredObject) {
  CollisionWorld world = make_world();
  ObjectDesc d;
  d.geometry = *Sphere::create(Real(0.5));
  d.pose = Transform{Vec3(2, 0, 0), kIdentityQuat};
  d.filter = CollisionFilter{1ull << 50, ~0ull, 3};
  const ObjectHandle far = *world.add(d);
  d.pose = Transform{Vec3(1, 0, 0), kIdentityQuat};
  d.filter = CollisionFilter{1, ~0ull, 0};
  const ObjectHandle near = *world.add(d);
  const Ray ray{Vec3(-5, 0, 0), Vec3(1, 0, 0)};
  EXPECT_EQ(world.raycast(ray, 100)->front().object, near);
  QueryFilter ignore_near;
  ignore_near.ignore = near;
  EXPECT_EQ(world.raycast(ray, 100, ignore_near)->front().object, far);
  QueryFilter mask;
  mask.mask = 1ull << 50;
  EXPECT_EQ(world.raycast(ray, 100, mask)->front().object, far);
  mask.group = 3;
  EXPECT_TRUE(world.raycast(ray, 100, mask)->empty());
  EXPECT_NEAR(world.raycast(ray, 100)->front().t, Real(5.5), Real(1e-5));
}

}  // namespace test_world_queries
}  // namespace proxima::test
