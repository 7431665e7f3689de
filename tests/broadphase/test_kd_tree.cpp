// KdTree: differential scenes against brute force and an O(n^2) loop, refit versus rebuild
// policy, invariants after every step.
#include <gtest/gtest.h>

#include <proxima/broadphase/kd_tree.hpp>

#include "broadphase/broadphase_scenes.hpp"
#include "broadphase/structure_checks.hpp"
#include "broadphase/tree_structure_checks.hpp"

namespace proxima {
namespace test_kd_tree {

static_assert(BroadPhaseStructure<KdTree>);

PROXIMA_BROADPHASE_DIFFERENTIAL_SUITE(
    KdTreeScenes, [] { return KdTree(); }, 12);

KdTree single_record_leaves() {
  KdTreeConfig c;
  c.leaf_size = 1;
  c.rebuild_overlap = Real(0);  // rebuild at any degradation
  return KdTree(c);
}
PROXIMA_BROADPHASE_DIFFERENTIAL_SUITE(KdTreeSingleLeafScenes, single_record_leaves, 6);

TEST(KdTree, StandardScenes) {
  test::run_standard_scenes([] { return KdTree(); });
}

TEST(KdTree, StandardScenesLargeLeaves) {
  KdTreeConfig c;
  c.leaf_size = 32;
  c.rebuild_overlap = Real(10);  // never rebuild for quality: refit only
  test::run_standard_scenes([c] { return KdTree(c); });
}

TEST(KdTree, SmallMotionRefitsLargeMotionRebuilds) {
  test::Random rng(41);
  KdTree tree;
  std::vector<Aabb> boxes;
  for (ProxyId i = 0; i < 2000; ++i) {
    const Vec3 p = rng.vec3(-50, 50);
    boxes.push_back({p - Vec3(0.5), p + Vec3(0.5)});
    ASSERT_EQ(tree.insert(i, boxes.back(), ProxyKind::Moving), BroadPhaseStatus::Ok);
  }
  std::vector<ProxyPair> pairs;
  tree.find_pairs(pairs);  // builds
  const std::size_t built = tree.rebuild_count();
  EXPECT_EQ(built, 1u);
  EXPECT_LE(tree.depth(), 12);
  // Tiny jitter: refit keeps the tree.
  for (int frame = 0; frame < 5; ++frame) {
    for (ProxyId i = 0; i < boxes.size(); ++i) {
      const Vec3 d = rng.vec3(-0.01f, 0.01f);
      boxes[i].min += d;
      boxes[i].max += d;
      ASSERT_EQ(tree.update(i, boxes[i]), BroadPhaseStatus::Ok);
    }
    tree.find_pairs(pairs);
    ASSERT_TRUE(tree.validate());
  }
  EXPECT_EQ(tree.rebuild_count(), built);
  // Every box teleported: the slabs overlap everywhere, so the tree is rebuilt.
  for (ProxyId i = 0; i < boxes.size(); ++i) {
    const Vec3 p = rng.vec3(-50, 50);
    boxes[i] = {p - Vec3(0.5), p + Vec3(0.5)};
    ASSERT_EQ(tree.update(i, boxes[i]), BroadPhaseStatus::Ok);
  }
  ASSERT_TRUE(tree.validate());
  tree.find_pairs(pairs);
  EXPECT_EQ(tree.rebuild_count(), built + 1);
  ASSERT_TRUE(tree.validate());
}

TEST(KdTree, ParallelEqualsSerial) {
  KdTree s;
  test::check_parallel_equals_serial(s, 61);
}

TEST(KdTree, ThreadedPairsEqualAnO2Loop) {
  test::expect_threaded_pairs_match_o2_loop([] { return KdTree(); });
}

}  // namespace test_kd_tree
}  // namespace proxima
