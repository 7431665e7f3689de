// AnyBroadPhase and the registry: every registered structure, through the virtual
// interface, against the brute-force reference on every standard scene; update_pairs deltas;
// unknown names rejected; every parallel structure's find_pairs(out, executor) identical to
// the serial run on every executor of the test set (serial, pools of 1, 2, 3 and 8 threads,
// a scrambled order).
#include <gtest/gtest.h>

#include <proxima/broadphase/any_broadphase.hpp>
#include <proxima/broadphase/brute_force.hpp>
#include <proxima/core/tolerance.hpp>

#include <limits>
#include <set>
#include <string>

#include "broadphase/broadphase_scenes.hpp"
#include "core/executor_set.hpp"

namespace proxima {
namespace test_any_broadphase {

TEST(AnyBroadPhase, RegistryNamesAreUniqueAndMake) {
  const auto names = broadphase_names();
  ASSERT_GE(names.size(), 4u);
  EXPECT_EQ(names.front(), "brute");
  std::set<std::string_view> unique(names.begin(), names.end());
  EXPECT_EQ(unique.size(), names.size());
  for (std::string_view name : names) {
    auto made = make_broadphase(name);
    ASSERT_TRUE(made.ok()) << name;
    EXPECT_EQ((*made)->name(), name);
    EXPECT_EQ((*made)->size(), 0u);
    EXPECT_TRUE((*made)->validate());
  }
}

TEST(AnyBroadPhase, UnknownNameNamesTheField) {
  auto made = make_broadphase("no_such_structure");
  ASSERT_FALSE(made.ok());
  EXPECT_EQ(made.error().field, "structure");
  EXPECT_NE(made.error().message.find("sap_oneshot"), std::string::npos);
}

TEST(AnyBroadPhase, EveryRegisteredStructureOnEveryScene) {
  for (std::string_view name : broadphase_names()) {
    for (const test::Scene& scene : test::standard_scenes()) {
      auto made = make_broadphase(name);
      ASSERT_TRUE(made.ok());
      std::unique_ptr<AnyBroadPhase> bp = std::move(made).value();
      EXPECT_TRUE(test::run_differential(*bp, scene, 5)) << name << " on " << scene.name;
    }
  }
}

// Fuzz findings (fuzz/corpus/broadphase_ops/regression_loose_tree_subnormal_ray,
// regression_aabb_tree_subnormal_spread): a ray with a subnormal direction component made the
// loose trees' slab test add -inf and +inf (its slack on an infinite t1), an invalid
// operation (a trap in the tests); a ray with a NaN origin reached that test's comparisons; a
// NaN max_t raised the flag in every structure's check of it; and the dynamic tree's rebuild
// binned boxes whose centres spread a subnormal width, its bin scale infinite, 0 * inf. Now
// a ray that is not finite (or a NaN max_t) finds nothing in every structure, as in the brute
// force, without the flag; a subnormal direction is a valid ray; the tree's rebuild does not
// split on such an axis.
TEST(AnyBroadPhase, RaysThatAreNotFiniteFindNothingAndSubnormalSpreadsRebuild) {
  const Real nan = std::numeric_limits<Real>::quiet_NaN();
  const Real inf = std::numeric_limits<Real>::infinity();
  const Real tiny = std::numeric_limits<Real>::denorm_min();
  for (std::string_view name : broadphase_names()) {
    auto made = make_broadphase(name);
    ASSERT_TRUE(made.ok());
    AnyBroadPhase& bp = **made;
    for (ProxyId id = 0; id < 40; ++id) {
      const Vec3 c(Real(id % 2) * tiny, Real(0), Real(0));  // centres a subnormal apart
      ASSERT_EQ(bp.insert(id, {c - Vec3(1), c + Vec3(1)}, ProxyKind::Moving, {}), BroadPhaseStatus::Ok) << name;
    }
    bp.rebuild();
    EXPECT_TRUE(bp.validate()) << name;
    for (const Ray& ray : {Ray{Vec3(nan, 0, 0), Vec3(1, 0, 0)}, Ray{Vec3(-5, 0, 0), Vec3(nan, 1, 0)},
                           Ray{Vec3(inf, 0, 0), Vec3(1, 0, 0)}, Ray{Vec3(-5, 0, 0), Vec3(inf, 0, 0)}}) {
      std::size_t hits = 0;
      bp.query_ray(ray, Real(10), [&](ProxyId, Real) { return ++hits, Real(10); });
      EXPECT_EQ(hits, 0u) << name;
    }
    std::size_t hits = 0;
    bp.query_ray(Ray{Vec3(-5, 0, 0), Vec3(1, 0, 0)}, nan, [&](ProxyId, Real) { return ++hits, Real(10); });
    EXPECT_EQ(hits, 0u) << name;
    // Along y with a subnormal x: the boxes' x slabs give t = -inf and +inf.
    bp.query_ray(Ray{Vec3(Real(0.5), -5, 0), Vec3(tiny, 1, 0)}, Real(10),
                 [&](ProxyId, Real) { return ++hits, Real(10); });
    EXPECT_EQ(hits, 40u) << name;
    hits = 0;
    bp.query_ray(Ray{Vec3(Real(3), -5, 0), Vec3(tiny, 1, 0)}, Real(10),
                 [&](ProxyId, Real) { return ++hits, Real(10); });
    EXPECT_EQ(hits, 0u) << name;
    bp.query_ray(Ray{Vec3(-5, 0, 0), Vec3(1, 0, 0)}, Real(10), [&](ProxyId, Real) { return ++hits, Real(10); });
    EXPECT_EQ(hits, 40u) << name;
  }
}

// Named regression: multi-box pruning converted cell coordinates of a box reaching
// kMaxCoordinate (a half-space's box in a collision world) to int before clamping them
// (undefined, a floating-point trap under the test main).
TEST(AnyBroadPhase, BoxesReachingTheCoordinateLimitPairLikeTheBruteForce) {
  const Real m = kMaxCoordinate;
  for (std::string_view name : broadphase_names()) {
    std::unique_ptr<AnyBroadPhase> bp = std::move(make_broadphase(name)).value();
    BruteForceBroadPhase reference;
    const Aabb ground{Vec3(-m, -m, -m), Vec3(m, m, Real(-6.5))};
    ASSERT_EQ(bp->insert(0, ground, ProxyKind::Static), BroadPhaseStatus::Ok) << name;
    reference.insert(0, ground, ProxyKind::Static);
    for (ProxyId i = 1; i < 50; ++i) {
      const Vec3 lo(Real(i % 7) - 3, Real(i % 5) - 2, Real(i % 11) - 7);
      ASSERT_EQ(bp->insert(i, Aabb{lo, lo + Vec3(1)}, ProxyKind::Moving), BroadPhaseStatus::Ok) << name;
      reference.insert(i, Aabb{lo, lo + Vec3(1)}, ProxyKind::Moving);
    }
    std::vector<ProxyPair> got, want;
    bp->find_pairs(got);
    reference.find_pairs(want);
    EXPECT_EQ(got, want) << name;
  }
}

TEST(AnyBroadPhase, UpdatePairsReportsDeltasAndThreadsAgree) {
  for (std::string_view name : broadphase_names()) {
    auto bp = std::move(make_broadphase(name)).value();
    ASSERT_EQ(bp->insert(0, {Vec3(0), Vec3(1)}, ProxyKind::Moving), BroadPhaseStatus::Ok);
    ASSERT_EQ(bp->insert(1, {Vec3(1), Vec3(2)}, ProxyKind::Moving), BroadPhaseStatus::Ok);  // touching corner
    ASSERT_EQ(bp->insert(2, {Vec3(5), Vec3(6)}, ProxyKind::Static), BroadPhaseStatus::Ok);
    const PairDelta& d1 = bp->update_pairs();
    EXPECT_EQ(d1.begun, (std::vector<ProxyPair>{{0, 1}})) << name;
    EXPECT_TRUE(d1.ended.empty());
    ASSERT_EQ(bp->update(1, {Vec3(4.5f), Vec3(5.5f)}), BroadPhaseStatus::Ok);
    const PairDelta& d2 = bp->update_pairs(test::shared_pool(4));
    EXPECT_EQ(d2.begun, (std::vector<ProxyPair>{{1, 2}})) << name;
    EXPECT_EQ(d2.ended, (std::vector<ProxyPair>{{0, 1}})) << name;
    EXPECT_EQ(bp->pairs(), (std::vector<ProxyPair>{{1, 2}}));
    ASSERT_EQ(bp->remove(2), BroadPhaseStatus::Ok);
    EXPECT_EQ(bp->update_pairs().ended, (std::vector<ProxyPair>{{1, 2}})) << name;
  }
}

TEST(AnyBroadPhase, ParallelStructuresEqualSerialOnEveryExecutor) {
  std::vector<test::NamedExecutor> executors = test::test_executors();
  for (std::string_view name : broadphase_names()) {
    for (const test::SceneLayout layout : {test::SceneLayout::Uniform, test::SceneLayout::Clustered}) {
      auto bp = std::move(make_broadphase(name)).value();
      if (!bp->parallel()) continue;
      test::Scene scene;
      scene.name = "parallel";
      scene.seed = 90 + std::uint64_t(layout);
      scene.layout = layout;
      scene.count = 6000;
      scene.extent = Real(30);
      scene.min_size = Real(0.5);
      scene.max_size = Real(3);
      scene.cluster_radius = Real(12);
      scene.static_fraction = 0.3;
      scene.filters = true;
      test::SceneGenerator gen(scene);
      for (ProxyId id = 0; id < 6000; ++id)
        ASSERT_EQ(bp->insert(id, gen.box(), gen.kind(), gen.filter()), BroadPhaseStatus::Ok);
      std::vector<ProxyPair> serial;
      std::vector<ProxyPair> parallel;
      for (int frame = 0; frame < 2; ++frame) {
        bp->find_pairs(serial);
        ASSERT_GT(serial.size(), 1000u) << name;
        for (test::NamedExecutor& e : executors) {
          bp->find_pairs(parallel, *e.executor);
          ASSERT_EQ(parallel, serial) << name << " on " << e.name << ", frame " << frame;
        }
        for (ProxyId k = 0; k < 6000; k += 2) ASSERT_EQ(bp->update(k, gen.box()), BroadPhaseStatus::Ok);
      }
    }
  }
}

}  // namespace test_any_broadphase
}  // namespace proxima
