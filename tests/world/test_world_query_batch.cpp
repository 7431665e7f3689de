// CollisionWorld's batched scene queries (raycast_batch, line_of_sight_batch,
// closest_point_batch) against the single queries called in a loop (themselves checked
// against brute force in test_world_queries.cpp): bit-identical answers for the serial
// executor and thread pools of 1, 2, 3 and 8 threads; counts; bad items named, nothing
// written.
#include <gtest/gtest.h>

#include <cstring>
#include <sweep_size.hpp>

#include "world/world_scene.hpp"

namespace proxima::test {
namespace test_world_query_batch {

struct Items {
  std::vector<WorldRay> rays;
  std::vector<WorldSegment> segments;
  std::vector<Vec3> points;
};

Items make_items(Random& rng, int count) {
  Items items;
  for (int i = 0; i < count; ++i) {
    items.rays.push_back({rng.vec3(-kExtent, kExtent), rng.vector_of_length(Real(1), Real(4)), Real(3)});
    const Vec3 from = rng.vec3(-kExtent, kExtent);
    items.segments.push_back({from, i % 10 == 0 ? from : from + rng.vector_of_length(Real(0.5), Real(6))});
    items.points.push_back(rng.vec3(-kExtent, kExtent));
  }
  return items;
}

// Byte equality of two answers (every field, padding included: both are value-initialised).
template <class T>
bool same_bytes(const T& a, const T& b) {
  return std::memcmp(&a, &b, sizeof(T)) == 0;
}

TEST(WorldQueryBatch, BatchesEqualTheSingleQueriesForEveryExecutor) {
  CollisionWorld world = make_world();
  Random rng(77);
  std::vector<Mover> movers = populate(world, rng, sweep_size(300), kExtent);
  for (int f = 0; f < 5; ++f) {
    advance(world, movers, kExtent);
    ASSERT_FALSE(world.step(Real(1) / Real(60)).has_value());
  }
  const Items items = make_items(rng, sweep_size(400));
  const std::size_t n = items.rays.size();
  QueryFilter filter;
  filter.ignore = world.objects()[3];

  // The single queries, in item order.
  std::vector<WorldHit> want_hits(n);
  std::vector<std::uint8_t> want_visible(n);
  std::vector<WorldClosest> want_nearest(n);
  std::size_t hits = 0, visible = 0, found = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const auto r = world.raycast(Ray{items.rays[i].origin, items.rays[i].direction}, items.rays[i].max_t, filter);
    if (!r->empty()) want_hits[i] = r->front(), ++hits;
    want_visible[i] = *world.line_of_sight(items.segments[i].from, items.segments[i].to, filter) ? 1 : 0;
    visible += want_visible[i];
    const auto c = world.closest_point(items.points[i], Real(1.5), filter);
    if (c->has_value()) want_nearest[i] = **c, ++found;
  }
  ASSERT_GT(hits, n / 10);
  ASSERT_LT(hits, n);
  ASSERT_GT(visible, n / 10);
  ASSERT_LT(visible, n);
  ASSERT_GT(found, n / 10);

  ThreadPool one(1), two(2), three(3), eight(8);
  for (Executor* executor : std::initializer_list<Executor*>{&serial_executor(), &one, &two, &three, &eight}) {
    const std::size_t threads = executor->concurrency();
    std::vector<WorldHit> got_hits(n);
    std::vector<std::uint8_t> got_visible(n, 7);
    std::vector<WorldClosest> got_nearest(n);
    EXPECT_EQ(*world.raycast_batch(items.rays, got_hits, filter, *executor), hits) << threads;
    EXPECT_EQ(*world.line_of_sight_batch(items.segments, got_visible, filter, *executor), visible) << threads;
    EXPECT_EQ(*world.closest_point_batch(items.points, Real(1.5), got_nearest, filter, *executor), found) << threads;
    for (std::size_t i = 0; i < n; ++i) {
      EXPECT_TRUE(same_bytes(got_hits[i], want_hits[i])) << "ray " << i << ", " << threads << " threads";
      EXPECT_EQ(got_visible[i], want_visible[i]) << "segment " << i << ", " << threads << " threads";
      EXPECT_TRUE(same_bytes(got_nearest[i], want_nearest[i])) << "point " << i << ", " << threads << " threads";
    }
  }
}

TEST(WorldQueryBatch, BadItemsAreNamedAndNothingIsWritten) {
  CollisionWorld world = make_world();
  Random rng(78);
  populate(world, rng, 50, kExtent);
  ASSERT_FALSE(world.step(Real(1) / Real(60)).has_value());
  Items items = make_items(rng, 10);
  const WorldHit sentinel{ObjectHandle{1, 2}, 99, Real(5), Vec3(1), Vec3(0, 1, 0), {}};
  std::vector<WorldHit> hits(10, sentinel);

  std::vector<WorldHit> short_hits(9);
  EXPECT_EQ(world.raycast_batch(items.rays, short_hits).error().field, "hits");
  items.rays[7].direction = Vec3(0);
  EXPECT_EQ(world.raycast_batch(items.rays, hits).error().field, "rays[7].direction");
  items.rays[7].direction = Vec3(1, 0, 0);
  items.rays[4].max_t = Real(-1);
  EXPECT_EQ(world.raycast_batch(items.rays, hits).error().field, "rays[4].max_t");
  items.rays[2].origin.y = std::numeric_limits<Real>::quiet_NaN();
  EXPECT_EQ(world.raycast_batch(items.rays, hits).error().field, "rays[2].origin");
  for (const WorldHit& h : hits) EXPECT_TRUE(same_bytes(h, sentinel));

  std::vector<std::uint8_t> visible(10, 7);
  items.segments[5].to.z = std::numeric_limits<Real>::infinity();
  EXPECT_EQ(world.line_of_sight_batch(items.segments, visible).error().field, "segments[5].to");
  EXPECT_EQ(world.line_of_sight_batch(items.segments, std::span<std::uint8_t>(visible).first(3)).error().field,
            "visible");
  for (std::uint8_t v : visible) EXPECT_EQ(v, 7);

  std::vector<WorldClosest> nearest(10);
  nearest[0].signed_distance = Real(42);
  items.points[9].x = std::numeric_limits<Real>::infinity();
  EXPECT_EQ(world.closest_point_batch(items.points, Real(1), nearest).error().field, "points[9]");
  items.points[9].x = Real(0);
  EXPECT_EQ(world.closest_point_batch(items.points, Real(-1), nearest).error().field, "max_distance");
  EXPECT_EQ(nearest[0].signed_distance, Real(42));

  // Empty batches answer nothing.
  EXPECT_EQ(*world.raycast_batch({}, {}), 0u);
}

}  // namespace test_world_query_batch
}  // namespace proxima::test
