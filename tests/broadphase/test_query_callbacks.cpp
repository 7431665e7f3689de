// The queries of every concrete structure as templates on the callback, returning their
// counters: a move-only callable is accepted (no std::function behind it), stats() keeps the
// last find_pairs' counters whatever the queries do, and const queries from several threads
// at once give the serial answers (they mutate nothing).

#include <gtest/gtest.h>

#include <proxima/broadphase/any_broadphase.hpp>
#include <proxima/broadphase/brute_force.hpp>
#include <proxima/broadphase/bsp_tree.hpp>
#include <proxima/broadphase/dynamic_aabb_tree.hpp>
#include <proxima/broadphase/kd_tree.hpp>
#include <proxima/broadphase/loose_octree.hpp>
#include <proxima/broadphase/region_quadtree.hpp>
#include <proxima/broadphase/sweep_and_prune.hpp>
#include <proxima/broadphase/uniform_grid.hpp>

#include <algorithm>
#include <memory>
#include <thread>
#include <type_traits>
#include <vector>

#include "broadphase/broadphase_scenes.hpp"

namespace proxima {
namespace test_query_callbacks {

template <class S>
class QueryCallbackTest : public testing::Test {};

using Structures =
    testing::Types<BruteForceBroadPhase, SweepAndPrune, SortedSweep, MultiBoxPruning, UniformGrid, SpatialHash,
                   HierarchicalGrid, LooseOctree, LooseQuadtree, RegionQuadtree, KdTree, BspTree, DynamicAabbTree>;
TYPED_TEST_SUITE(QueryCallbackTest, Structures);

/// 800 proxies of a uniform scene (a quarter static), found once.
template <class S>
void fill(S& s) {
  test::Scene scene;
  scene.seed = 5;
  scene.count = 800;
  scene.extent = Real(40);
  scene.static_fraction = 0.25;
  test::SceneGenerator gen(scene);
  for (ProxyId id = 0; id < 800; ++id) ASSERT_EQ(s.insert(id, gen.box(), gen.kind()), BroadPhaseStatus::Ok);
  std::vector<ProxyPair> pairs;
  s.find_pairs(pairs);
}

/// The ids a box query, a point query and a clipped ray query report, each sorted.
template <class S>
std::vector<std::vector<ProxyId>> answers(const S& s, int q) {
  const Real c = Real(q % 13) * Real(5) - Real(30);
  std::vector<std::vector<ProxyId>> got(3);
  s.query_aabb({Vec3(c), Vec3(c + Real(8))}, [&](ProxyId id) {
    got[0].push_back(id);
    return true;
  });
  s.query_point(Vec3(c, -c, Real(1)), [&](ProxyId id) {
    got[1].push_back(id);
    return true;
  });
  s.query_ray({Vec3(-50, c, -c), Vec3(1, Real(0.01), Real(0.02))}, Real(100), [&](ProxyId id, Real t) {
    got[2].push_back(id);
    return t + Real(20);  // clips the ray 20 units past each hit
  });
  for (auto& ids : got) std::sort(ids.begin(), ids.end());
  return got;
}

/// An overlap callback that cannot be copied (std::function could not hold it).
struct MoveOnlyCounter {
  std::unique_ptr<int> count = std::make_unique<int>(0);
  bool operator()(ProxyId) {
    ++*count;
    return true;
  }
};

TYPED_TEST(QueryCallbackTest, MoveOnlyCallablesAndCountersByValue) {
  TypeParam s;
  fill(s);
  const BroadPhaseStats after_pairs = s.stats();
  MoveOnlyCounter on_overlap;
  const BroadPhaseStats box = s.query_aabb({Vec3(-10), Vec3(10)}, on_overlap);
  const BroadPhaseStats point = s.query_point(Vec3(0), on_overlap);
  int rays = 0;
  const BroadPhaseStats ray =
      s.query_ray({Vec3(-50, 0, 0), Vec3(1, 0, 0)}, Real(100), [&, only = std::unique_ptr<int>()](ProxyId, Real) {
        ++rays;
        return Real(-1);
      });
  const int reported = *on_overlap.count;
  static_assert(!std::is_copy_constructible_v<MoveOnlyCounter>);
  EXPECT_GT(reported, 0);
  EXPECT_GT(rays, 0);
  EXPECT_GE(box.pairs_tested + point.pairs_tested, std::uint64_t(reported));
  EXPECT_GE(ray.pairs_tested, std::uint64_t(rays));
  const BroadPhaseStats now = s.stats();
  EXPECT_EQ(now.nodes_visited, after_pairs.nodes_visited);
  EXPECT_EQ(now.pairs_tested, after_pairs.pairs_tested);
  EXPECT_EQ(now.pairs_found, after_pairs.pairs_found);
}

TYPED_TEST(QueryCallbackTest, ConcurrentConstQueriesGiveTheSerialAnswers) {
  TypeParam s;
  fill(s);
  const TypeParam& view = s;
  std::vector<std::vector<std::vector<ProxyId>>> want;
  for (int q = 0; q < 40; ++q) want.push_back(answers(view, q));
  std::vector<int> mismatches(4, 0);
  std::vector<std::thread> threads;
  for (int t = 0; t < 4; ++t) {
    threads.emplace_back([&, t] {
      for (int round = 0; round < 5; ++round) {
        for (int q = 0; q < 40; ++q) mismatches[std::size_t(t)] += answers(view, q) == want[std::size_t(q)] ? 0 : 1;
      }
    });
  }
  for (std::thread& th : threads) th.join();
  for (int t = 0; t < 4; ++t) EXPECT_EQ(mismatches[std::size_t(t)], 0) << "thread " << t;
}

TEST(AnyBroadPhaseQueries, ReturnTheStructuresCounters) {
  for (std::string_view name : broadphase_names()) {
    auto bp = std::move(make_broadphase(name)).value();
    fill(*bp);
    int calls = 0;
    const BroadPhaseStats st = bp->query_aabb({Vec3(-10), Vec3(10)}, [&](ProxyId) { return ++calls < 5; });
    EXPECT_EQ(calls, 5) << name;
    EXPECT_GE(st.pairs_tested, 5u) << name;
  }
}

}  // namespace test_query_callbacks
}  // namespace proxima
