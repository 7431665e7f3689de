// BspTree: differential scenes against brute force and an O(n^2) loop, oblique planes on
// diagonal static geometry, moving proxies among static walls, invariants after every step.
#include <gtest/gtest.h>

#include <proxima/broadphase/bsp_tree.hpp>

#include "broadphase/broadphase_scenes.hpp"
#include "broadphase/structure_checks.hpp"
#include "broadphase/tree_structure_checks.hpp"

namespace proxima {
namespace test_bsp_tree {

static_assert(BroadPhaseStructure<BspTree>);

PROXIMA_BROADPHASE_DIFFERENTIAL_SUITE(
    BspTreeScenes, [] { return BspTree(); }, 12);

BspTree small_leaves_eager_rebuild() {
  BspTreeConfig c;
  c.leaf_size = 1;
  c.rebuild_edits = Real(0);  // rebuild at nearly every find_pairs
  return BspTree(c);
}
PROXIMA_BROADPHASE_DIFFERENTIAL_SUITE(BspTreeEagerScenes, small_leaves_eager_rebuild, 6);

TEST(BspTree, StandardScenes) {
  test::run_standard_scenes([] { return BspTree(); });
}

TEST(BspTree, StandardScenesNeverRebuilt) {
  BspTreeConfig c;
  c.rebuild_edits = Real(1e6);  // only explicit rebuilds and overflowing leaves
  c.rebuild_work = Real(1e6);
  test::run_standard_scenes([c] { return BspTree(c); });
}

// Static boxes along two diagonal walls (x = y and x = -y) with moving boxes flying through.
TEST(BspTree, DiagonalWallsUseObliquePlanes) {
  test::Random rng(51);
  BspTree bsp;
  test::RefScene scene;
  ProxyId id = 0;
  for (int i = 0; i < 400; ++i) {
    const Real s = rng.uniform(-60, 60);
    const Vec3 c = i % 2 == 0 ? Vec3(s, s, rng.uniform(-5, 5)) : Vec3(s, -s, rng.uniform(-5, 5));
    const Aabb box{c - Vec3(0.6f), c + Vec3(0.6f)};
    scene[id] = {box, ProxyKind::Static, {}};
    ASSERT_EQ(bsp.insert(id++, box, ProxyKind::Static), BroadPhaseStatus::Ok);
  }
  std::vector<Vec3> velocity;
  for (int i = 0; i < 100; ++i) {
    const Vec3 c = rng.vec3(-60, 60);
    const Aabb box{c - Vec3(1), c + Vec3(1)};
    scene[id] = {box, ProxyKind::Moving, {}};
    velocity.push_back(rng.vec3(-1.5f, 1.5f));
    ASSERT_EQ(bsp.insert(id++, box, ProxyKind::Moving), BroadPhaseStatus::Ok);
  }
  bsp.rebuild();
  ASSERT_TRUE(bsp.validate());
  EXPECT_GT(bsp.oblique_plane_count(), 0u);
  std::vector<ProxyPair> got;
  for (int frame = 0; frame < 30; ++frame) {
    bsp.find_pairs(got);
    ASSERT_EQ(got, test::reference_pairs(scene)) << frame;
    ASSERT_TRUE(bsp.validate());
    for (int i = 0; i < 100; ++i) {
      const ProxyId m = static_cast<ProxyId>(400 + i);
      scene[m].box.min += velocity[static_cast<std::size_t>(i)];
      scene[m].box.max += velocity[static_cast<std::size_t>(i)];
      ASSERT_EQ(bsp.update(m, scene[m].box), BroadPhaseStatus::Ok);
    }
    ASSERT_TRUE(bsp.validate());
  }
  test::Random qrng(52);
  test::check_queries(bsp, scene, qrng, Real(60), 40);
}

TEST(BspTree, ParallelEqualsSerial) {
  BspTree s;
  test::check_parallel_equals_serial(s, 61);
}

TEST(BspTree, ThreadedPairsEqualAnO2Loop) {
  test::expect_threaded_pairs_match_o2_loop([] { return BspTree(); });
}

}  // namespace test_bsp_tree
}  // namespace proxima
