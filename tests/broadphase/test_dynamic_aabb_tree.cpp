// DynamicAabbTree: differential scenes against the O(n^2) reference, tree invariants under
// rotations and rebuilds, SAH improvement of rebuild(), parallel pair finding equal to serial,
// fat-box behaviour.
#include <gtest/gtest.h>

#include <proxima/broadphase/dynamic_aabb_tree.hpp>

#include "broadphase/broadphase_scenes.hpp"
#include "broadphase/tree_structure_checks.hpp"
#include "core/executor_set.hpp"

namespace proxima {
namespace test_dynamic_aabb_tree {

static_assert(BroadPhaseStructure<DynamicAabbTree>);

// The shared differential harness (brute-force reference) on every standard scene.
PROXIMA_BROADPHASE_DIFFERENTIAL_SUITE(
    DynamicAabbTreeScenes, [] { return DynamicAabbTree(); }, 12);

test::OnExecutor<DynamicAabbTree> threaded_batch_rebuild_tree() {
  DynamicAabbTreeConfig c;
  c.refit_fraction = Real(0.01);
  c.rebuild_degradation = Real(0);
  return test::OnExecutor(DynamicAabbTree(c), test::shared_pool(3));
}
PROXIMA_BROADPHASE_DIFFERENTIAL_SUITE(DynamicAabbTreeThreadedScenes, threaded_batch_rebuild_tree, 6);

TEST(DynamicAabbTree, StandardScenes) {
  test::run_standard_scenes([] { return DynamicAabbTree(); });
}

TEST(DynamicAabbTree, StandardScenesWithoutRotations) {
  DynamicAabbTreeConfig c;
  c.rotations = false;
  test::run_standard_scenes([c] { return DynamicAabbTree(c); });
}

TEST(DynamicAabbTree, StandardScenesThreadedAndBatchRebuild) {
  DynamicAabbTreeConfig c;
  c.refit_fraction = Real(0.01);       // nearly every batch refits the moving tree
  c.rebuild_degradation = Real(0.05);  // and often rebuilds it
  c.margin_fraction = Real(0);         // every motion leaves the fat box
  test::run_standard_scenes([c] { return test::OnExecutor(DynamicAabbTree(c), test::shared_pool(4)); });
}

TEST(DynamicAabbTree, StandardScenesRefitOnly) {
  DynamicAabbTreeConfig c;
  c.refit_fraction = Real(0);          // every batch refits
  c.rebuild_degradation = Real(1e30);  // never rebuilds for quality
  test::run_standard_scenes([c] { return DynamicAabbTree(c); });
}

TEST(DynamicAabbTree, RotationsKeepTreeValidOnAdversarialOrder) {
  // Boxes inserted in sorted order along a line make the worst insertion order; rotations
  // must keep every invariant and should keep the height far below n.
  int heights[2] = {0, 0};
  for (const bool rotations : {false, true}) {
    DynamicAabbTreeConfig c;
    c.rotations = rotations;
    DynamicAabbTree tree(c);
    for (ProxyId i = 0; i < 2000; ++i) {
      const Real x = static_cast<Real>(i);
      ASSERT_EQ(tree.insert(i, Aabb{Vec3(x, 0, 0), Vec3(x + Real(0.5), 1, 1)}, ProxyKind::Moving),
                BroadPhaseStatus::Ok);
      if (i % 97 == 0) {
        ASSERT_TRUE(tree.validate()) << i;
      }
    }
    ASSERT_TRUE(tree.validate());
    heights[rotations ? 1 : 0] = tree.height();
    std::vector<ProxyPair> pairs;
    tree.find_pairs(pairs);
    EXPECT_TRUE(pairs.empty());
  }
  EXPECT_LT(heights[1], 60);   // with rotations: near-logarithmic
  EXPECT_GT(heights[0], 500);  // without: the insertion order degrades the tree to a near list
}

TEST(DynamicAabbTree, RebuildLowersSahCost) {
  test::Random rng(21);
  DynamicAabbTreeConfig c;
  c.rotations = false;
  DynamicAabbTree tree(c);
  // A spatially sorted insertion order gives a poor incremental tree.
  std::vector<Aabb> boxes;
  for (int i = 0; i < 3000; ++i) {
    const Vec3 p = rng.vec3(-50, 50);
    boxes.push_back(Aabb{p - Vec3(0.5), p + Vec3(0.5)});
  }
  std::sort(boxes.begin(), boxes.end(), [](const Aabb& a, const Aabb& b) { return a.min.x < b.min.x; });
  for (std::size_t i = 0; i < boxes.size(); ++i) {
    ASSERT_EQ(tree.insert(static_cast<ProxyId>(i), boxes[i], i % 4 == 0 ? ProxyKind::Static : ProxyKind::Moving),
              BroadPhaseStatus::Ok);
  }
  std::vector<ProxyPair> before;
  tree.find_pairs(before);
  const Real cost_before = tree.sah_cost();
  tree.rebuild();
  ASSERT_TRUE(tree.validate());
  const Real cost_after = tree.sah_cost();
  EXPECT_LT(cost_after, cost_before);
  std::vector<ProxyPair> after;
  tree.find_pairs(after);
  EXPECT_EQ(after, before);
  EXPECT_EQ(tree.node_count(), 2 * boxes.size() - 2);  // two trees
}

TEST(DynamicAabbTree, ParallelEqualsSerial) {
  test::Random rng(31);
  DynamicAabbTree serial;
  DynamicAabbTree parallel;
  ThreadPool pool(4);
  std::vector<Aabb> boxes;
  for (ProxyId i = 0; i < 6000; ++i) {
    const Vec3 p = rng.vec3(-40, 40);
    const Aabb b{p - rng.vec3(0.1f, 1.2f), p + rng.vec3(0.1f, 1.2f)};
    const ProxyKind kind = i % 5 == 0 ? ProxyKind::Static : ProxyKind::Moving;
    ASSERT_EQ(serial.insert(i, b, kind), BroadPhaseStatus::Ok);
    ASSERT_EQ(parallel.insert(i, b, kind), BroadPhaseStatus::Ok);
    boxes.push_back(b);
  }
  std::vector<ProxyPair> a;
  std::vector<ProxyPair> b;
  for (int frame = 0; frame < 5; ++frame) {
    serial.find_pairs(a);
    parallel.find_pairs(b, pool);
    ASSERT_FALSE(a.empty());
    ASSERT_EQ(a, b) << frame;
    EXPECT_EQ(serial.stats().pairs_tested, parallel.stats().pairs_tested);
    std::vector<ProxyUpdate> updates;
    for (ProxyId i = 0; i < boxes.size(); ++i) {
      if (i % 5 == 0) continue;
      const Vec3 d = rng.vec3(-0.3f, 0.3f);
      boxes[i].min += d;
      boxes[i].max += d;
      updates.push_back({i, boxes[i]});
    }
    ASSERT_EQ(serial.update(updates), BroadPhaseStatus::Ok);
    ASSERT_EQ(parallel.update(updates), BroadPhaseStatus::Ok);
  }
  ThreadPool hardware;  // hardware concurrency
  parallel.find_pairs(b, hardware);
  serial.find_pairs(a);
  EXPECT_EQ(a, b);
}

TEST(DynamicAabbTree, ParallelEqualsSerialExplicitThreads) {
  DynamicAabbTree s;
  test::check_parallel_equals_serial(s, 62);
}

TEST(DynamicAabbTree, FatBoxAbsorbsSmallMotion) {
  DynamicAabbTree tree;  // margin 10 % of the largest edge
  const Aabb box{Vec3(0), Vec3(1, 2, 1)};
  ASSERT_EQ(tree.insert(3, box, ProxyKind::Moving), BroadPhaseStatus::Ok);
  ASSERT_EQ(tree.insert(4, box, ProxyKind::Static), BroadPhaseStatus::Ok);
  const Aabb fat = tree.fat_box(3);
  EXPECT_TRUE(fat.contains(box));
  EXPECT_EQ(fat.min, box.min - Vec3(Real(0.2)));
  EXPECT_EQ(tree.fat_box(4).min, box.min);  // static: no margin
  // A small move stays in the fat box: the leaf keeps its fat box.
  ASSERT_EQ(tree.update(3, Aabb{box.min + Vec3(0.1f), box.max + Vec3(0.1f)}), BroadPhaseStatus::Ok);
  EXPECT_EQ(tree.fat_box(3).min, fat.min);
  // A larger move leaves it: a new fat box around the new box.
  const Aabb moved{box.min + Vec3(5), box.max + Vec3(5)};
  ASSERT_EQ(tree.update(3, moved), BroadPhaseStatus::Ok);
  EXPECT_TRUE(tree.fat_box(3).contains(moved));
  EXPECT_FALSE(tree.fat_box(3).contains(box));
  EXPECT_TRUE(tree.validate());
  EXPECT_TRUE(tree.fat_box(99).min.x > tree.fat_box(99).max.x);  // unknown: empty
}

}  // namespace test_dynamic_aabb_tree
}  // namespace proxima
