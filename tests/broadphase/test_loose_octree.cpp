// LooseOctree and LooseQuadtree against the brute-force reference (shared differential
// scenes) and an O(n^2) loop (random scenes with moves, removals and queries); rejections;
// specific cases: placement depth by size, root growth, pruning of empty nodes, boxes stacked
// in z for the quadtree.
#include <gtest/gtest.h>

#include <proxima/broadphase/loose_octree.hpp>

#include "broadphase/broadphase_scenes.hpp"
#include "broadphase/structure_checks.hpp"

namespace proxima {
namespace test_loose_octree {

PROXIMA_BROADPHASE_DIFFERENTIAL_SUITE(
    LooseOctreeDifferential, [] { return LooseOctree(); }, 12);
PROXIMA_BROADPHASE_DIFFERENTIAL_SUITE(
    LooseQuadtreeDifferential, [] { return LooseQuadtree(); }, 12);

template <class S>
class LooseTreeTest : public testing::Test {};

using LooseTrees = testing::Types<LooseOctree, LooseQuadtree>;
TYPED_TEST_SUITE(LooseTreeTest, LooseTrees);

TYPED_TEST(LooseTreeTest, RandomScenesMatchReference) {
  using test::SceneKind;
  for (const SceneKind kind : {SceneKind::Similar, SceneKind::Varying, SceneKind::Touching, SceneKind::Points,
                               SceneKind::Huge, SceneKind::Clustered}) {
    for (std::uint64_t seed = 1; seed <= 3; ++seed) {
      TypeParam s;
      test::run_random_scene(s, kind, seed * 100 + std::uint64_t(kind), 300, 6);
      if (testing::Test::HasFailure()) return;
    }
  }
}

TYPED_TEST(LooseTreeTest, RebuildKeepsPairs) {
  TypeParam s;
  test::Random rng(11);
  for (ProxyId id = 0; id < 1000; ++id) {
    ASSERT_EQ(s.insert(id, test::random_box(rng, test::SceneKind::Varying, Real(40)), ProxyKind::Moving, {}),
              BroadPhaseStatus::Ok);
  }
  std::vector<ProxyPair> before;
  std::vector<ProxyPair> after;
  s.find_pairs(before);
  s.rebuild();
  EXPECT_TRUE(s.validate());
  s.find_pairs(after);
  EXPECT_EQ(before, after);
}

TYPED_TEST(LooseTreeTest, ThreadedPairsEqualAnO2Loop) {
  test::expect_threaded_pairs_match_o2_loop([] { return TypeParam(); });
}

TYPED_TEST(LooseTreeTest, Rejections) {
  TypeParam s;
  test::expect_rejections(s);
}

TYPED_TEST(LooseTreeTest, EmptyNodesArePruned) {
  TypeParam s;
  test::Random rng(4);
  for (ProxyId id = 0; id < 500; ++id) {
    ASSERT_EQ(s.insert(id, test::random_box(rng, test::SceneKind::Varying, Real(50)), ProxyKind::Moving, {}),
              BroadPhaseStatus::Ok);
  }
  EXPECT_GT(s.node_count(), 10u);
  for (ProxyId id = 0; id < 499; ++id) ASSERT_EQ(s.remove(id), BroadPhaseStatus::Ok);
  EXPECT_TRUE(s.validate());
  // One box left: the chain from the root to its node, nothing else.
  EXPECT_EQ(s.node_count(), std::size_t(s.depth()) + 1);
  ASSERT_EQ(s.remove(499), BroadPhaseStatus::Ok);
  EXPECT_TRUE(s.validate());
}

// Found by the fuzz target broadphase_ops (fuzz/corpus/broadphase_ops/regression_octree_empty_root):
// the last box removed leaves an empty root; a box outside it then grew the tree above that
// root, which stayed as an empty leaf (validate() failed).
TYPED_TEST(LooseTreeTest, EmptyRootIsNotKeptWhenAFarBoxArrives) {
  TypeParam s;
  ASSERT_EQ(s.insert(0, {Vec3(Real(-2), Real(-5), Real(-3)), Vec3(Real(1), Real(-4), Real(-2))}, ProxyKind::Moving, {}),
            BroadPhaseStatus::Ok);
  ASSERT_EQ(s.remove(0), BroadPhaseStatus::Ok);
  EXPECT_TRUE(s.validate());
  ASSERT_EQ(s.insert(46, {Vec3(Real(6), Real(-1.75), Real(0.25)), Vec3(Real(13), Real(2.5), Real(3.25))},
                     ProxyKind::Moving, {}),
            BroadPhaseStatus::Ok);
  EXPECT_TRUE(s.validate());
  std::size_t found = 0;
  s.query_point(Vec3(Real(10), Real(0), Real(1)), [&](ProxyId id) { return found += (id == 46), true; });
  EXPECT_EQ(found, 1u);
}

TYPED_TEST(LooseTreeTest, RootGrowsTowardsFarBoxes) {
  TypeParam s;
  ASSERT_EQ(s.insert(0, {Vec3(0), Vec3(1)}, ProxyKind::Moving, {}), BroadPhaseStatus::Ok);
  ASSERT_EQ(s.insert(1, {Vec3(Real(1e5)), Vec3(Real(1e5) + 1)}, ProxyKind::Moving, {}), BroadPhaseStatus::Ok);
  ASSERT_EQ(s.insert(2, {Vec3(Real(-3e4)), Vec3(Real(1e5) + 1)}, ProxyKind::Moving, {}), BroadPhaseStatus::Ok);
  std::vector<ProxyPair> pairs;
  s.find_pairs(pairs);
  EXPECT_EQ(pairs, (std::vector<ProxyPair>{{0, 2}, {1, 2}}));
  EXPECT_TRUE(s.validate());
}

TYPED_TEST(LooseTreeTest, SmallBoxesSitDeeperThanLargeOnes) {
  TypeParam s;
  ASSERT_EQ(s.insert(0, {Vec3(-64), Vec3(64)}, ProxyKind::Static, {}), BroadPhaseStatus::Ok);
  const int shallow = s.depth();
  for (ProxyId id = 1; id < 9; ++id) {
    const Vec3 c(Real(id) * 10 - 45);
    ASSERT_EQ(s.insert(id, Aabb::from_center_half_extents(c, Vec3(Real(0.25))), ProxyKind::Moving, {}),
              BroadPhaseStatus::Ok);
  }
  // Half extent 0.25 against a root of half 64: about log2(64 / 0.25) = 8 levels deeper.
  EXPECT_GE(s.depth(), shallow + 6);
  std::vector<ProxyPair> pairs;
  s.find_pairs(pairs);
  EXPECT_EQ(pairs.size(), 8u);
  EXPECT_TRUE(s.validate());
}

TEST(LooseQuadtree, BoxesStackedInZ) {
  // Same x, y footprint, disjoint in z: the quadtree keeps them in one node and the z test
  // separates them; pairs only between z-neighbours that touch.
  LooseQuadtree s;
  for (ProxyId id = 0; id < 20; ++id) {
    const Real z = Real(id);
    ASSERT_EQ(s.insert(id, {Vec3(0, 0, z), Vec3(1, 1, z + 1)}, ProxyKind::Moving, {}), BroadPhaseStatus::Ok);
  }
  std::vector<ProxyPair> pairs;
  s.find_pairs(pairs);
  ASSERT_EQ(pairs.size(), 19u);
  for (ProxyId id = 0; id < 19; ++id) EXPECT_EQ(pairs[id], (ProxyPair{id, id + 1}));
  EXPECT_EQ(s.node_count(), std::size_t(s.depth()) + 1);
}

}  // namespace test_loose_octree
}  // namespace proxima
