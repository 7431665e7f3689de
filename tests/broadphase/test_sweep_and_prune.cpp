// Sweep-and-prune structures (sap, sap_oneshot, mbp) against the brute-force reference on
// every standard scene (the differential harness), plus parallel output identical to serial
// on every executor of the test set.
#include <gtest/gtest.h>

#include <proxima/broadphase/brute_force.hpp>
#include <proxima/broadphase/sweep_and_prune.hpp>

#include <vector>

#include "broadphase/broadphase_scenes.hpp"
#include "core/executor_set.hpp"

namespace proxima {
namespace test_sweep_and_prune {

PROXIMA_BROADPHASE_DIFFERENTIAL_SUITE(
    SweepAndPruneScenes, [] { return SweepAndPrune(); }, 16);
PROXIMA_BROADPHASE_DIFFERENTIAL_SUITE(
    SortedSweepScenes, [] { return SortedSweep(); }, 16);
PROXIMA_BROADPHASE_DIFFERENTIAL_SUITE(
    MultiBoxPruningScenes, [] { return MultiBoxPruning(); }, 16);

// A flat world (every box at the same height, spread over x and z) of a few thousand boxes:
// the case box pruning over a grid exists for; many cells, compared with the reference.
TEST(MultiBoxPruning, FlatWorldMatchesReference) {
  test::Scene scene;
  scene.name = "flat";
  scene.seed = 5;
  scene.count = 6000;
  scene.extent = Real(300);
  scene.min_size = Real(1);
  scene.max_size = Real(6);
  test::SceneGenerator gen(scene);
  MultiBoxPruning mbp;
  BruteForceBroadPhase ref;
  for (ProxyId id = 0; id < 6000; ++id) {
    Aabb b = gen.box();
    b.min.y = Real(0);
    b.max.y = Real(1);
    const ProxyKind kind = id % 5 == 0 ? ProxyKind::Static : ProxyKind::Moving;
    ASSERT_EQ(mbp.insert(id, b, kind), BroadPhaseStatus::Ok);
    ASSERT_EQ(ref.insert(id, b, kind), BroadPhaseStatus::Ok);
  }
  std::vector<ProxyPair> got, want;
  mbp.find_pairs(got);
  ref.find_pairs(want);
  EXPECT_EQ(got, want);
  EXPECT_GT(want.size(), 100u);
  mbp.find_pairs(got, test::shared_pool(4));
  EXPECT_EQ(got, want);
}

template <class S>
void check_parallel_identical(std::uint64_t seed) {
  test::Scene scene;
  scene.name = "parallel";
  scene.seed = seed;
  scene.count = 20000;
  scene.extent = Real(120);
  scene.static_fraction = 0.3;
  scene.filters = true;
  test::SceneGenerator gen(scene);
  S s;
  BruteForceBroadPhase ref;
  for (ProxyId id = 0; id < 20000; ++id) {
    const Aabb b = gen.box();
    const ProxyKind kind = gen.kind();
    const ProxyFilter f = gen.filter();
    ASSERT_EQ(s.insert(id, b, kind, f), BroadPhaseStatus::Ok);
    if (id < 3000) {
      ASSERT_EQ(ref.insert(id, b, kind, f), BroadPhaseStatus::Ok);
    }
  }
  std::vector<ProxyPair> serial, parallel;
  std::vector<test::NamedExecutor> executors = test::test_executors();
  for (int frame = 0; frame < 3; ++frame) {
    s.find_pairs(serial);
    for (test::NamedExecutor& e : executors) {
      s.find_pairs(parallel, *e.executor);
      EXPECT_EQ(parallel, serial) << "executor " << e.name;
    }
    for (ProxyId id = 0; id < 20000; id += 3) ASSERT_EQ(s.update(id, gen.moved(gen.box())), BroadPhaseStatus::Ok);
  }
  // The first 3000 proxies alone against the reference, on a pool.
  S small;
  for (ProxyId id : ref.ids())
    ASSERT_EQ(small.insert(id, ref.box(id), ref.kind(id), ref.filter(id)), BroadPhaseStatus::Ok);
  std::vector<ProxyPair> want;
  ref.find_pairs(want);
  small.find_pairs(parallel, test::shared_pool(4));
  EXPECT_EQ(parallel, want);
}

TEST(SortedSweep, ParallelOutputIdenticalToSerial) { check_parallel_identical<SortedSweep>(21); }
TEST(SweepAndPrune, ParallelOutputIdenticalToSerial) { check_parallel_identical<SweepAndPrune>(22); }
TEST(MultiBoxPruning, ParallelOutputIdenticalToSerial) { check_parallel_identical<MultiBoxPruning>(23); }

// Sweep axis follows the variance of the centres; rebuild re-chooses it.
TEST(SweepAndPrune, AxisByVariance) {
  SweepAndPrune sap;
  for (ProxyId i = 0; i < 100; ++i) {
    const Real z = static_cast<Real>(i) * Real(3);
    ASSERT_EQ(sap.insert(i, {Vec3(0, 0, z), Vec3(1, 1, z + 1)}, ProxyKind::Moving), BroadPhaseStatus::Ok);
  }
  std::vector<ProxyPair> out;
  sap.find_pairs(out);
  EXPECT_EQ(sap.axis(), 2);
  EXPECT_TRUE(out.empty());
  EXPECT_LT(sap.stats().pairs_tested, 100u);  // the sweep prunes everything
}

}  // namespace test_sweep_and_prune
}  // namespace proxima
