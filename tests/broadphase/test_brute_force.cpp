// BruteForceBroadPhase against a naive triple loop written here (every pair of proxies, the
// closed overlap test axis by axis, kinds and filters), plus its rejected calls and queries.
#include <gtest/gtest.h>

#include <proxima/broadphase/brute_force.hpp>

#include <algorithm>
#include <limits>
#include <vector>

#include "broadphase/broadphase_scenes.hpp"

namespace proxima {
namespace test_brute_force {

struct Naive {
  ProxyId id;
  Aabb box;
  ProxyKind kind;
  ProxyFilter filter;
};

std::vector<ProxyPair> naive_pairs(const std::vector<Naive>& all) {
  std::vector<ProxyPair> out;
  for (std::size_t i = 0; i < all.size(); ++i) {
    for (std::size_t j = i + 1; j < all.size(); ++j) {
      const Naive& a = all[i];
      const Naive& b = all[j];
      if (a.kind == ProxyKind::Static && b.kind == ProxyKind::Static) continue;
      if ((a.filter.layer & b.filter.mask) == 0 || (b.filter.layer & a.filter.mask) == 0) continue;
      bool overlap = true;
      for (int axis = 0; axis < 3; ++axis) {
        if (a.box.min[axis] > b.box.max[axis] || b.box.min[axis] > a.box.max[axis]) overlap = false;
      }
      if (overlap) out.push_back({std::min(a.id, b.id), std::max(a.id, b.id)});
    }
  }
  std::sort(out.begin(), out.end());
  return out;
}

TEST(BruteForce, MatchesNaiveLoopOnEveryScene) {
  for (const test::Scene& scene : test::standard_scenes()) {
    test::SceneGenerator gen(scene);
    BruteForceBroadPhase bp;
    std::vector<Naive> all;
    const int n = std::max(scene.count, 50);
    for (int i = 0; i < n; ++i) {
      Naive p{static_cast<ProxyId>(i * 3 + 1), gen.box(), gen.kind(), gen.filter()};
      ASSERT_EQ(bp.insert(p.id, p.box, p.kind, p.filter), BroadPhaseStatus::Ok);
      all.push_back(p);
    }
    std::vector<ProxyPair> got;
    for (int frame = 0; frame < 4; ++frame) {
      for (Naive& p : all) {
        if (p.kind == ProxyKind::Moving) {
          p.box = gen.moved(p.box);
          ASSERT_EQ(bp.update(p.id, p.box), BroadPhaseStatus::Ok);
        }
      }
      // Remove a few (swap-with-last paths) and check.
      if (frame == 2) {
        for (int k = 0; k < 5 && !all.empty(); ++k) {
          const std::size_t at = all.size() / 3;
          ASSERT_EQ(bp.remove(all[at].id), BroadPhaseStatus::Ok);
          all.erase(all.begin() + static_cast<std::ptrdiff_t>(at));
        }
      }
      ASSERT_TRUE(bp.validate());
      bp.find_pairs(got);
      EXPECT_EQ(got, naive_pairs(all)) << scene.name << " frame " << frame;
      EXPECT_EQ(bp.stats().pairs_found, got.size());
    }
  }
}

TEST(BruteForce, TouchingAndZeroSizeBoxesPair) {
  BruteForceBroadPhase bp;
  ASSERT_EQ(bp.insert(0, {Vec3(0), Vec3(1)}, ProxyKind::Moving), BroadPhaseStatus::Ok);
  ASSERT_EQ(bp.insert(1, {Vec3(1, 0, 0), Vec3(2, 1, 1)}, ProxyKind::Moving), BroadPhaseStatus::Ok);     // face
  ASSERT_EQ(bp.insert(2, Aabb::from_point(Vec3(2, 1, 1)), ProxyKind::Static), BroadPhaseStatus::Ok);    // corner
  ASSERT_EQ(bp.insert(3, Aabb::from_point(Vec3(2, 1, 1)), ProxyKind::Static), BroadPhaseStatus::Ok);    // static-static
  ASSERT_EQ(bp.insert(4, {Vec3(1.5f, 2, 0), Vec3(3, 3, 1)}, ProxyKind::Moving), BroadPhaseStatus::Ok);  // apart
  std::vector<ProxyPair> got;
  bp.find_pairs(got);
  const std::vector<ProxyPair> want{{0, 1}, {1, 2}, {1, 3}};
  EXPECT_EQ(got, want);
}

TEST(BruteForce, RejectedCallsChangeNothing) {
  BruteForceBroadPhase bp;
  const Aabb good{Vec3(0), Vec3(1)};
  ASSERT_EQ(bp.insert(5, good, ProxyKind::Moving), BroadPhaseStatus::Ok);
  Aabb nan_box = good;
  nan_box.min.y = std::numeric_limits<Real>::quiet_NaN();
  Aabb inverted = good;
  inverted.min.z = Real(2);
  EXPECT_EQ(bp.insert(6, nan_box, ProxyKind::Moving), BroadPhaseStatus::NotFinite);
  EXPECT_EQ(bp.insert(6, inverted, ProxyKind::Moving), BroadPhaseStatus::InvalidBox);
  EXPECT_EQ(bp.insert(5, good, ProxyKind::Moving), BroadPhaseStatus::DuplicateId);
  EXPECT_EQ(bp.update(5, nan_box), BroadPhaseStatus::NotFinite);
  EXPECT_EQ(bp.update(7, good), BroadPhaseStatus::UnknownId);
  EXPECT_EQ(bp.remove(7), BroadPhaseStatus::UnknownId);
  const std::vector<ProxyUpdate> batch{{5, {Vec3(3), Vec3(4)}}, {9, good}};
  EXPECT_EQ(bp.update(std::span<const ProxyUpdate>(batch)), BroadPhaseStatus::UnknownId);
  EXPECT_EQ(bp.size(), 1u);
  EXPECT_FALSE(bp.contains(6));
  EXPECT_EQ(bp.box(5).min, good.min);
  EXPECT_EQ(bp.box(5).max, good.max);
  EXPECT_TRUE(bp.validate());
}

TEST(BruteForce, RayQueryClipsAndStops) {
  BruteForceBroadPhase bp;
  for (ProxyId i = 0; i < 5; ++i) {
    const Real x = Real(2) * static_cast<Real>(i) + Real(1);
    ASSERT_EQ(bp.insert(i, {Vec3(x, -1, -1), Vec3(x + 1, 1, 1)}, ProxyKind::Static), BroadPhaseStatus::Ok);
  }
  const Ray ray{Vec3(0), Vec3(10, 0, 0)};
  std::vector<ProxyId> seen;
  bp.query_ray(ray, Real(1), [&](ProxyId id, Real t) {
    seen.push_back(id);
    EXPECT_EQ(t, (Real(2) * static_cast<Real>(id) + Real(1)) / Real(10));
    return Real(-1);
  });
  EXPECT_EQ(seen.size(), 5u);
  int calls = 0;
  bp.query_ray(ray, Real(0.35), [&](ProxyId, Real) {
    ++calls;
    return Real(0.2);
  });
  EXPECT_EQ(calls, 1);  // t = 0.1 clips to 0.2; the box at t = 0.3 is beyond
}

TEST(BruteForce, HarnessRunsOnTheReferenceItself) {
  for (const test::Scene& scene : test::standard_scenes()) {
    EXPECT_TRUE(test::run_differential<BruteForceBroadPhase>(scene, 6)) << scene.name;
  }
}

}  // namespace test_brute_force
}  // namespace proxima
