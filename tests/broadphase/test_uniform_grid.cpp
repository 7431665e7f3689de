// UniformGrid, SpatialHash and HierarchicalGrid against an O(n^2) reference on random scenes
// (similar, varying, touching, points, huge, clustered), with moves, removals and queries;
// rejections; threads; specific cases (touching pairs across cell borders, fixed cell sizes).
#include <gtest/gtest.h>

#include <proxima/broadphase/uniform_grid.hpp>
#include <proxima/geometry/raycast.hpp>

#include <limits>
#include <map>

#include "broadphase/broadphase_scenes.hpp"
#include "broadphase/structure_checks.hpp"
#include "core/executor_set.hpp"

namespace proxima {
namespace test_uniform_grid {

// The shared differential harness: every standard scene against the brute-force reference.
PROXIMA_BROADPHASE_DIFFERENTIAL_SUITE(
    UniformGridDifferential, [] { return UniformGrid(); }, 12);
PROXIMA_BROADPHASE_DIFFERENTIAL_SUITE(
    SpatialHashDifferential, [] { return SpatialHash(); }, 12);
PROXIMA_BROADPHASE_DIFFERENTIAL_SUITE(
    HierarchicalGridDifferential, [] { return HierarchicalGrid(); }, 12);
PROXIMA_BROADPHASE_DIFFERENTIAL_SUITE(
    ThreadedHashDifferential, [] { return test::OnExecutor(SpatialHash(), test::shared_pool(2)); }, 6);

template <class S>
class CellStructureTest : public testing::Test {};

using CellStructures = testing::Types<UniformGrid, SpatialHash, HierarchicalGrid>;
TYPED_TEST_SUITE(CellStructureTest, CellStructures);

TYPED_TEST(CellStructureTest, RandomScenesMatchReference) {
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

TYPED_TEST(CellStructureTest, FixedCellSizes) {
  for (const Real cell : {Real(0.05), Real(0.7), Real(3), Real(40)}) {
    TypeParam s(cell);
    test::run_random_scene(s, test::SceneKind::Similar, 77, 200, 3);
    TypeParam t(cell);
    test::run_random_scene(t, test::SceneKind::Touching, 78, 200, 3);
    if (testing::Test::HasFailure()) return;
  }
}

TYPED_TEST(CellStructureTest, TwoThreadsSameResult) {
  TypeParam one;
  TypeParam two;
  test::Random rng(5);
  for (ProxyId id = 0; id < 5000; ++id) {
    const Aabb box = test::random_box(rng, test::SceneKind::Varying, Real(30));
    ASSERT_EQ(one.insert(id, box, ProxyKind::Moving, {}), BroadPhaseStatus::Ok);
    ASSERT_EQ(two.insert(id, box, ProxyKind::Moving, {}), BroadPhaseStatus::Ok);
  }
  std::vector<ProxyPair> a;
  std::vector<ProxyPair> b;
  one.find_pairs(a);
  two.find_pairs(b, test::shared_pool(2));
  EXPECT_GT(a.size(), 100u);
  EXPECT_EQ(a, b);
  EXPECT_TRUE(std::is_sorted(a.begin(), a.end()));
}

TYPED_TEST(CellStructureTest, Rejections) {
  TypeParam s;
  test::expect_rejections(s);
}

TYPED_TEST(CellStructureTest, TouchingAcrossCellBorders) {
  // Unit cubes on an integer lattice with cell size 1: every face, edge and corner contact
  // lies exactly on a cell border. 4^3 cubes: 27-neighbourhood pairs.
  TypeParam s(Real(1));
  ProxyId id = 0;
  for (int x = 0; x < 4; ++x) {
    for (int y = 0; y < 4; ++y) {
      for (int z = 0; z < 4; ++z) {
        const Vec3 lo{Real(x), Real(y), Real(z)};
        ASSERT_EQ(s.insert(id++, {lo, lo + Vec3(1)}, ProxyKind::Moving, {}), BroadPhaseStatus::Ok);
      }
    }
  }
  std::vector<ProxyPair> pairs;
  s.find_pairs(pairs);
  // Pairs of lattice points at Chebyshev distance 1 in a 4x4x4 block.
  std::size_t expected = 0;
  for (int a = 0; a < 64; ++a) {
    for (int b = a + 1; b < 64; ++b) {
      const int dx = std::abs(a / 16 - b / 16);
      const int dy = std::abs(a / 4 % 4 - b / 4 % 4);
      const int dz = std::abs(a % 4 - b % 4);
      if (std::max({dx, dy, dz}) <= 1) ++expected;
    }
  }
  EXPECT_EQ(pairs.size(), expected);
  EXPECT_TRUE(s.validate());
}

TYPED_TEST(CellStructureTest, QueryStopsEarly) {
  TypeParam s;
  for (ProxyId id = 0; id < 50; ++id) {
    ASSERT_EQ(s.insert(id, {Vec3(0), Vec3(1)}, ProxyKind::Moving, {}), BroadPhaseStatus::Ok);
  }
  s.rebuild();
  int calls = 0;
  s.query_aabb({Vec3(0), Vec3(1)}, [&](ProxyId) { return ++calls < 3; });
  EXPECT_EQ(calls, 3);
  calls = 0;
  s.query_ray({Vec3(-1, Real(0.5), Real(0.5)), Vec3(1, 0, 0)}, Real(10), [&](ProxyId, Real t) {
    EXPECT_EQ(t, Real(1));
    ++calls;
    return Real(0);
  });
  EXPECT_EQ(calls, 1);
}

TYPED_TEST(CellStructureTest, StaticStaticNeverPairs) {
  TypeParam s;
  ASSERT_EQ(s.insert(1, {Vec3(0), Vec3(1)}, ProxyKind::Static, {}), BroadPhaseStatus::Ok);
  ASSERT_EQ(s.insert(2, {Vec3(0), Vec3(1)}, ProxyKind::Static, {}), BroadPhaseStatus::Ok);
  std::vector<ProxyPair> pairs{{7, 8}};
  s.find_pairs(pairs);
  EXPECT_TRUE(pairs.empty());
  ASSERT_EQ(s.insert(0, {Vec3(1), Vec3(2)}, ProxyKind::Moving, {}), BroadPhaseStatus::Ok);
  s.find_pairs(pairs);
  EXPECT_EQ(pairs, (std::vector<ProxyPair>{{0, 1}, {0, 2}}));
}

TYPED_TEST(CellStructureTest, SubnormalBoxesGiveAFiniteCell) {
  // Boxes whose extents are subnormal numbers chose a cell whose inverse was infinite, and
  // an offset of 0 times it raised the invalid flag (the broadphase_ops fuzz finding
  // double-8888db6b). The cell stays at least the smallest normal number.
  const Real d = std::numeric_limits<Real>::denorm_min();
  TypeParam s;
  ASSERT_EQ(s.insert(0, {Vec3(0), Vec3(d)}, ProxyKind::Moving, {}), BroadPhaseStatus::Ok);
  ASSERT_EQ(s.insert(1, {Vec3(0), Vec3(d)}, ProxyKind::Moving, {}), BroadPhaseStatus::Ok);
  ASSERT_EQ(s.insert(2, {Vec3(2 * d), Vec3(3 * d)}, ProxyKind::Moving, {}), BroadPhaseStatus::Ok);
  ASSERT_EQ(s.insert(3, {Vec3(0), Vec3(3 * d)}, ProxyKind::Moving, {}), BroadPhaseStatus::Ok);
  std::vector<ProxyPair> pairs;
  s.find_pairs(pairs);
  EXPECT_EQ(pairs, (std::vector<ProxyPair>{{0, 1}, {0, 3}, {1, 3}, {2, 3}}));
  EXPECT_TRUE(s.validate());
}

TEST(HierarchicalGrid, HugeAmongSmall) {
  // One huge static box among many tiny moving ones: every tiny box pairs with it.
  HierarchicalGrid s;
  ASSERT_EQ(s.insert(0, {Vec3(-1000), Vec3(1000)}, ProxyKind::Static, {}), BroadPhaseStatus::Ok);
  test::Random rng(9);
  for (ProxyId id = 1; id <= 500; ++id) {
    const Vec3 c = rng.vec3(-900, 900);
    ASSERT_EQ(s.insert(id, Aabb::from_center_half_extents(c, Vec3(Real(0.01))), ProxyKind::Moving, {}),
              BroadPhaseStatus::Ok);
  }
  std::vector<ProxyPair> pairs;
  s.find_pairs(pairs);
  EXPECT_GE(pairs.size(), 500u);
  for (ProxyId id = 1; id <= 500; ++id) EXPECT_EQ(pairs[id - 1], (ProxyPair{0, id}));
  EXPECT_TRUE(s.validate());
}

TEST(UniformGrid, BoundsGrow) {
  UniformGrid s;
  ASSERT_EQ(s.insert(0, {Vec3(0), Vec3(1)}, ProxyKind::Moving, {}), BroadPhaseStatus::Ok);
  ASSERT_EQ(s.insert(1, {Vec3(Real(0.5)), Vec3(Real(1.5))}, ProxyKind::Moving, {}), BroadPhaseStatus::Ok);
  std::vector<ProxyPair> pairs;
  s.find_pairs(pairs);
  EXPECT_EQ(pairs.size(), 1u);
  // Both leave the first bounds far away, still touching.
  ASSERT_EQ(s.update(0, {Vec3(500), Vec3(501)}), BroadPhaseStatus::Ok);
  ASSERT_EQ(s.update(1, {Vec3(501), Vec3(502)}), BroadPhaseStatus::Ok);
  s.find_pairs(pairs);
  EXPECT_EQ(pairs, (std::vector<ProxyPair>{{0, 1}}));
  EXPECT_TRUE(s.validate());
}

TEST(SpatialHash, SteadyStateKeepsCapacity) {
  SpatialHash s;
  test::Random rng(3);
  std::vector<Aabb> boxes;
  for (ProxyId id = 0; id < 2000; ++id) {
    boxes.push_back(test::random_box(rng, test::SceneKind::Similar, Real(25)));
    ASSERT_EQ(s.insert(id, boxes.back(), ProxyKind::Moving, {}), BroadPhaseStatus::Ok);
  }
  std::vector<ProxyPair> pairs;
  // Boxes oscillating between two positions: after the first two frames every buffer has
  // its final capacity, and later frames allocate nothing.
  std::size_t bytes = 0;
  for (int frame = 0; frame < 6; ++frame) {
    if (frame == 2) bytes = s.memory_bytes();
    const Real step = frame % 2 == 0 ? Real(0.25) : Real(-0.25);
    for (ProxyId id = 0; id < 2000; ++id) {
      boxes[id].min += Vec3(step);
      boxes[id].max += Vec3(step);
      ASSERT_EQ(s.update(id, boxes[id]), BroadPhaseStatus::Ok);
    }
    s.find_pairs(pairs);
  }
  EXPECT_EQ(s.memory_bytes(), bytes);
}

TEST(UniformGrid, RayMarchMatchesEveryBoxItEnters) {
  // Built grid: rays march the cells. Every box geometry::ray_aabb says the segment enters,
  // each once with its t, against an O(n) loop; rays along cell borders and axes, from inside
  // and outside, finite and infinite; the closest-hit protocol; far fewer boxes tested than n.
  using test::SceneKind;
  for (const SceneKind kind : {SceneKind::Similar, SceneKind::Varying, SceneKind::Touching, SceneKind::Huge}) {
    UniformGrid s;
    test::Random rng(std::uint64_t(kind) + 7);
    std::vector<Aabb> boxes;
    for (ProxyId id = 0; id < 4000; ++id) {
      boxes.push_back(test::random_box(rng, kind, Real(80)));
      ASSERT_EQ(s.insert(id, boxes.back(), ProxyKind::Moving, {}), BroadPhaseStatus::Ok);
    }
    std::vector<ProxyPair> pairs;
    s.find_pairs(pairs);
    std::uint64_t tested = 0;
    for (int q = 0; q < 300; ++q) {
      Vec3 origin = rng.vec3(Real(-20), Real(100));
      const Real speed = Real(rng.integer(0, 1) == 0 ? 30 : 200);
      Vec3 direction = rng.unit_vector() * speed;
      if (q % 5 == 1) {  // along an axis
        direction = Vec3(0);
        direction[q % 3] = Real(q % 2 == 0 ? 150 : -150);
      }
      if (q % 5 == 2) origin = glm::floor(origin);                             // on cell borders
      if (q % 5 == 3) origin = boxes[std::size_t(q) % boxes.size()].center();  // inside a box
      const Real max_t = q % 7 == 0 ? kRealMax : Real(1);
      const Ray ray{origin, direction};
      std::map<ProxyId, Real> want;
      for (ProxyId id = 0; id < boxes.size(); ++id) {
        if (const auto hit = geometry::ray_aabb(ray, max_t, boxes[id])) want[id] = hit->t;
      }
      std::map<ProxyId, Real> got;
      const BroadPhaseStats st = s.query_ray(ray, max_t, [&](ProxyId id, Real t) {
        EXPECT_FALSE(got.count(id)) << "reported twice: " << id;
        got[id] = t;
        return Real(-1);
      });
      EXPECT_EQ(got, want) << "query " << q;
      tested += st.pairs_tested;
      // Closest hit: the callback clips the ray to each hit.
      Real best = max_t;
      for (const auto& [id, t] : want) best = std::min(best, t);
      Real closest = max_t;
      s.query_ray(ray, max_t, [&](ProxyId, Real t) {
        closest = std::min(closest, t);
        return t;
      });
      EXPECT_EQ(closest, best) << "query " << q;
    }
    EXPECT_LT(tested, std::uint64_t(300) * boxes.size() / 4) << "the march should test few boxes";
  }
}

}  // namespace test_uniform_grid
}  // namespace proxima
