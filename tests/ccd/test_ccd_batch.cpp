// Batched times of impact and shape casts (src/ccd/ccd_batch.cpp): for seeded mixed
// queries (spheres, boxes, capsules, a mesh and a compound; translations and rotations),
// every executor and thread count (serial, pools of 1, 2, 3 and 8 threads) gives exactly
// the results of the single-query functions, bit for bit; the hit count matches; a bad
// query anywhere rejects the whole call with its index in the field and writes nothing.
#include <gtest/gtest.h>

#include <proxima/ccd/ccd_batch.hpp>
#include <proxima/shapes/box.hpp>
#include <proxima/shapes/capsule.hpp>
#include <proxima/shapes/compound.hpp>
#include <proxima/shapes/sphere.hpp>

#include <cmath>
#include <cstring>
#include <vector>

#include "support/random.hpp"

namespace proxima {
namespace test_ccd_batch {

struct Scene {
  Sphere sphere = Sphere::create(Real(0.3)).value();
  Box box = Box::create(Vec3(Real(0.5), Real(0.8), Real(0.2))).value();
  Capsule capsule = Capsule::create(Real(0.2), Real(0.6)).value();
  Compound compound =
      Compound::create({{Shape(Box::create(Vec3(Real(0.3))).value()), Transform::identity()},
                        {Shape(Sphere::create(Real(0.4)).value()), {Vec3(Real(1), Real(0), Real(0)), kIdentityQuat}}})
          .value();
  ShapeRef pick(int i) const {
    switch (i % 4) {
      case 0: return sphere;
      case 1: return box;
      case 2: return capsule;
      default: return compound;
    }
  }
};

std::vector<ToiQuery> toi_queries(const Scene& scene, int count) {
  test::Random rng(1207);
  std::vector<ToiQuery> q;
  for (int i = 0; i < count; ++i) {
    Motion ma{rng.pose(Real(3)), {}};
    ma.end = {ma.start.position + rng.vec3(Real(-4), Real(4)), i % 3 == 0 ? ma.start.rotation : rng.rotation()};
    Motion mb{rng.pose(Real(3)), {}};
    mb.end = {mb.start.position, i % 2 == 0 ? mb.start.rotation : rng.rotation()};
    q.push_back({scene.pick(i), ma, scene.pick(i / 4), mb});
  }
  return q;
}

std::vector<CastQuery> cast_queries(const Scene& scene, int count) {
  test::Random rng(1208);
  std::vector<CastQuery> q;
  for (int i = 0; i < count; ++i) {
    q.push_back({scene.pick(i), rng.pose(Real(3)), rng.vec3(Real(-5), Real(5)), scene.pick(i / 4), rng.pose(Real(3))});
  }
  return q;
}

template <class T>
bool same_bits(const T& a, const T& b) {
  return std::memcmp(&a, &b, sizeof(T)) == 0;
}

TEST(CcdBatch, TimesOfImpactEqualTheSingleQueriesForEveryThreadCount) {
  const Scene scene;
  const std::vector<ToiQuery> queries = toi_queries(scene, 400);
  std::vector<ToiResult> expected;
  std::size_t hits = 0;
  for (const ToiQuery& q : queries) {
    expected.push_back(time_of_impact(q.a, q.motion_a, q.b, q.motion_b).value());
    hits += expected.back().status == CcdStatus::Hit || expected.back().status == CcdStatus::InitiallyOverlapping;
  }
  EXPECT_GT(hits, std::size_t(20));
  EXPECT_LT(hits, queries.size());
  for (std::size_t threads : {std::size_t(0), std::size_t(1), std::size_t(2), std::size_t(3), std::size_t(8)}) {
    std::vector<ToiResult> got(queries.size());
    ThreadPool pool(threads == 0 ? 1 : threads);
    Executor& executor = threads == 0 ? static_cast<Executor&>(serial_executor()) : pool;
    const auto n = time_of_impact_batch(queries, got, {}, executor);
    ASSERT_TRUE(n.ok());
    EXPECT_EQ(*n, hits) << threads << " threads";
    for (std::size_t i = 0; i < queries.size(); ++i) {
      ASSERT_TRUE(same_bits(got[i].toi, expected[i].toi) && got[i].status == expected[i].status &&
                  same_bits(got[i].normal, expected[i].normal) && got[i].iterations == expected[i].iterations)
          << "query " << i << ", " << threads << " threads";
    }
  }
}

TEST(CcdBatch, ShapeCastsEqualTheSingleQueriesForEveryThreadCount) {
  const Scene scene;
  const std::vector<CastQuery> queries = cast_queries(scene, 400);
  std::vector<CastResult> expected;
  for (const CastQuery& q : queries)
    expected.push_back(shape_cast(q.a, q.pose_a, q.translation, q.b, q.pose_b).value());
  for (std::size_t threads : {std::size_t(1), std::size_t(2), std::size_t(8)}) {
    std::vector<CastResult> got(queries.size());
    ThreadPool pool(threads);
    ASSERT_TRUE(shape_cast_batch(queries, got, {}, pool).ok());
    for (std::size_t i = 0; i < queries.size(); ++i) {
      ASSERT_TRUE(same_bits(got[i].t, expected[i].t) && got[i].status == expected[i].status &&
                  same_bits(got[i].point, expected[i].point))
          << "query " << i << ", " << threads << " threads";
    }
  }
}

TEST(CcdBatch, ABadQueryRejectsTheCallAndWritesNothing) {
  const Scene scene;
  std::vector<ToiQuery> queries = toi_queries(scene, 20);
  queries[12].motion_b.end.rotation = Quat(Real(2), Real(0), Real(0), Real(0));
  std::vector<ToiResult> results(queries.size());
  for (ToiResult& r : results) r.toi = Real(-7);
  const auto n = time_of_impact_batch(queries, results);
  ASSERT_FALSE(n.ok());
  EXPECT_EQ(n.error().field, "queries[12].motion_b.end.rotation");
  for (const ToiResult& r : results) EXPECT_EQ(r.toi, Real(-7));

  std::vector<ToiResult> short_results(3);
  EXPECT_EQ(time_of_impact_batch(toi_queries(scene, 4), short_results).error().field, "results");
  ToiOptions bad;
  bad.tolerance = Real(-1);
  EXPECT_EQ(time_of_impact_batch(toi_queries(scene, 4), std::span<ToiResult>(results).first(4), bad).error().field,
            "options.tolerance");

  std::vector<CastQuery> casts = cast_queries(scene, 10);
  casts[7].translation.y = std::nan("");
  std::vector<CastResult> cast_results(casts.size());
  const auto c = shape_cast_batch(casts, cast_results);
  ASSERT_FALSE(c.ok());
  EXPECT_EQ(c.error().field, "queries[7].translation.y");
}

}  // namespace test_ccd_batch
}  // namespace proxima
