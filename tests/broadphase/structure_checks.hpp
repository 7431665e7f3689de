#pragma once
// Checks of a broad-phase structure against an O(n^2) loop over the same proxies, written
// here independently of every structure: random scenes (similar sizes, widely varying
// sizes, exactly touching integer boxes, points, huge boxes, statics, filters), updates,
// removals, and box / point / ray queries. Used by the grid and octree tests.
#include <gtest/gtest.h>

#include <proxima/broadphase/broadphase.hpp>
#include <proxima/broadphase/proxy_table.hpp>
#include <proxima/core/tolerance.hpp>
#include <proxima/geometry/raycast.hpp>

#include <algorithm>
#include <map>
#include <set>
#include <vector>

#include "core/executor_set.hpp"
#include "support/random.hpp"

namespace proxima::test {

/// A plain list of proxies, the reference.
struct ReferenceScene {
  struct Proxy {
    Aabb box;
    ProxyKind kind = ProxyKind::Moving;
    ProxyFilter filter;
  };
  std::map<ProxyId, Proxy> proxies;

  std::vector<ProxyPair> pairs() const {
    std::vector<ProxyPair> out;
    for (auto a = proxies.begin(); a != proxies.end(); ++a) {
      for (auto b = std::next(a); b != proxies.end(); ++b) {
        const Proxy& p = a->second;
        const Proxy& q = b->second;
        if (p.kind == ProxyKind::Static && q.kind == ProxyKind::Static) continue;
        if (!can_pair(p.filter, q.filter)) continue;
        if (p.box.overlaps(q.box)) out.push_back({a->first, b->first});
      }
    }
    return out;
  }
  std::set<ProxyId> overlapping(const Aabb& box) const {
    std::set<ProxyId> out;
    for (const auto& [id, p] : proxies) {
      if (p.box.overlaps(box)) out.insert(id);
    }
    return out;
  }
};

/// Kinds of random scenes.
enum class SceneKind { Similar, Varying, Touching, Points, Huge, Clustered };

inline Aabb random_box(Random& rng, SceneKind kind, Real world) {
  switch (kind) {
    case SceneKind::Similar: {
      const Vec3 c = rng.vec3(0, world);
      const Real hz = rng.uniform(Real(0.3), Real(1));
      const Real hy = rng.uniform(Real(0.3), Real(1));
      const Real hx = rng.uniform(Real(0.3), Real(1));
      const Vec3 h(hx, hy, hz);
      return Aabb::from_center_half_extents(c, h);
    }
    case SceneKind::Varying: {
      const Vec3 c = rng.vec3(-world, world);
      const Real scale = std::pow(Real(2), Real(rng.integer(-4, 6)));
      const Vec3 h = rng.vec3(Real(0.1), Real(1)) * scale;
      return Aabb::from_center_half_extents(c, h);
    }
    case SceneKind::Touching: {
      const int lz = rng.integer(0, 12);
      const int ly = rng.integer(0, 12);
      const int lx = rng.integer(0, 12);
      const Vec3 lo = Vec3(Real(lx), Real(ly), Real(lz));
      const int sz = rng.integer(0, 3);
      const int sy = rng.integer(0, 3);
      const int sx = rng.integer(0, 3);
      const Vec3 size = Vec3(Real(sx), Real(sy), Real(sz));
      return {lo, lo + size};
    }
    case SceneKind::Points: {
      const int pz = rng.integer(0, 6);
      const int py = rng.integer(0, 6);
      const int px = rng.integer(0, 6);
      const Vec3 p = Vec3(Real(px), Real(py), Real(pz));
      return rng.integer(0, 3) == 0 ? Aabb{p, p + Vec3(1)} : Aabb::from_point(p);
    }
    case SceneKind::Huge: {
      if (rng.integer(0, 30) == 0) {
        const Vec3 c = rng.vec3(0, world);
        return Aabb::from_center_half_extents(c, Vec3(world * rng.uniform(Real(0.2), Real(1.5))));
      }
      return random_box(rng, SceneKind::Similar, world);
    }
    case SceneKind::Clustered: {
      const Vec3 offset = rng.vec3(0, 3);
      const Vec3 c = Vec3(Real(rng.integer(0, 3)) * world) + offset;
      return Aabb::from_center_half_extents(c, rng.vec3(Real(0.05), Real(0.5)));
    }
  }
  return {};
}

inline ProxyFilter random_filter(Random& rng) {
  if (rng.integer(0, 3) != 0) return {};
  return {1u << rng.integer(0, 2), std::uint32_t(rng.integer(1, 7))};
}

/// Compares every query of `s` with the reference.
template <class S>
void expect_queries_match(const S& s, const ReferenceScene& ref, Random& rng, Real world) {
  for (int q = 0; q < 8; ++q) {
    const Vec3 c = rng.vec3(-world * Real(0.2), world * Real(1.2));
    const Aabb box = Aabb::from_center_half_extents(c, rng.vec3(0, world * Real(0.3)));
    std::multiset<ProxyId> got;
    s.query_aabb(box, [&](ProxyId id) {
      got.insert(id);
      return true;
    });
    const std::set<ProxyId> want = ref.overlapping(box);
    EXPECT_EQ(std::vector<ProxyId>(got.begin(), got.end()), std::vector<ProxyId>(want.begin(), want.end()));
    if (!ref.proxies.empty()) {
      auto it = ref.proxies.begin();
      std::advance(it, rng.integer(0, int(ref.proxies.size()) - 1));
      const Vec3 p = it->second.box.center();
      std::multiset<ProxyId> got_point;
      s.query_point(p, [&](ProxyId id) {
        got_point.insert(id);
        return true;
      });
      const std::set<ProxyId> want_point = ref.overlapping(Aabb::from_point(p));
      EXPECT_EQ(std::vector<ProxyId>(got_point.begin(), got_point.end()),
                std::vector<ProxyId>(want_point.begin(), want_point.end()));
    }
    // Ray: every box the segment enters, each once with geometry::ray_aabb's t.
    const Ray ray{rng.vec3(-world * Real(0.2), world * Real(1.2)), rng.unit_vector() * world};
    std::map<ProxyId, Real> got_ray;
    s.query_ray(ray, Real(1), [&](ProxyId id, Real t) {
      EXPECT_FALSE(got_ray.count(id));
      got_ray[id] = t;
      return Real(-1);
    });
    std::map<ProxyId, Real> want_ray;
    for (const auto& [id, p] : ref.proxies) {
      if (const auto hit = geometry::ray_aabb(ray, Real(1), p.box)) want_ray[id] = hit->t;
    }
    EXPECT_EQ(got_ray, want_ray);
  }
}

/// find_pairs(out, executor) on every executor of the test set (serial, pools of 1, 2, 3 and 8
/// threads, a scrambled order) against an O(n^2) loop on 3000 boxes (varying sizes,
/// clusters, touching boxes; static boxes and filters included): enough boxes for the
/// structures' parallel splits.
template <class Make>
void expect_threaded_pairs_match_o2_loop(Make make) {
  for (const SceneKind kind : {SceneKind::Varying, SceneKind::Clustered, SceneKind::Touching}) {
    auto s = make();
    Random rng(std::uint64_t(kind) + 40);
    std::vector<::proxima::detail::ProxyRecord> records;
    for (ProxyId id = 0; id < 3000; ++id) {
      ::proxima::detail::ProxyRecord r;
      r.box = random_box(rng, kind, Real(60));
      r.kind = rng.integer(0, 4) == 0 ? ProxyKind::Static : ProxyKind::Moving;
      r.filter = random_filter(rng);
      records.push_back(r);
      ASSERT_EQ(s.insert(id, r.box, r.kind, r.filter), BroadPhaseStatus::Ok);
    }
    std::vector<ProxyPair> want;
    for (ProxyId a = 0; a < records.size(); ++a) {
      for (ProxyId b = a + 1; b < records.size(); ++b) {
        if (records[a].box.overlaps(records[b].box) && ::proxima::detail::may_pair(records[a], records[b]))
          want.push_back({a, b});
      }
    }
    for (NamedExecutor& e : test_executors()) {
      std::vector<ProxyPair> got;
      s.find_pairs(got, *e.executor);
      EXPECT_EQ(got, want) << "executor " << e.name;
    }
  }
}

/// Random scene, several frames of moves, inserts and removals; every frame's pairs and the
/// queries are compared with the reference.
template <class S>
void run_random_scene(S& s, SceneKind kind, std::uint64_t seed, int count, int frames) {
  Random rng(seed);
  ReferenceScene ref;
  const Real world =
      kind == SceneKind::Touching || kind == SceneKind::Points ? Real(12) : Real(2) * std::cbrt(Real(count)) + 2;
  ProxyId next = 0;
  for (int i = 0; i < count; ++i) {
    const Aabb box = random_box(rng, kind, world);
    const ProxyKind pk = rng.integer(0, 4) == 0 ? ProxyKind::Static : ProxyKind::Moving;
    const ProxyFilter f = random_filter(rng);
    const ProxyId id = next;
    next += ProxyId(rng.integer(1, 2));  // ids with gaps
    ASSERT_EQ(s.insert(id, box, pk, f), BroadPhaseStatus::Ok);
    ref.proxies[id] = {box, pk, f};
  }
  std::vector<ProxyPair> got;
  for (int frame = 0; frame < frames; ++frame) {
    if (frame > 0) {
      // Move about half, remove and add a few, batch-update some.
      std::vector<ProxyUpdate> batch;
      for (auto& [id, p] : ref.proxies) {
        const int r = rng.integer(0, 5);
        if (r <= 2) {
          p.box = random_box(rng, kind, world);
          ASSERT_EQ(s.update(id, p.box), BroadPhaseStatus::Ok);
        } else if (r == 3) {
          p.box = random_box(rng, kind, world);
          batch.push_back({id, p.box});
        }
      }
      ASSERT_EQ(s.update(std::span<const ProxyUpdate>(batch)), BroadPhaseStatus::Ok);
      for (int k = 0; k < count / 20 + 1 && !ref.proxies.empty(); ++k) {
        auto it = ref.proxies.begin();
        std::advance(it, rng.integer(0, int(ref.proxies.size()) - 1));
        ASSERT_EQ(s.remove(it->first), BroadPhaseStatus::Ok);
        ref.proxies.erase(it);
        const Aabb box = random_box(rng, kind, world);
        ASSERT_EQ(s.insert(next, box, ProxyKind::Moving, {}), BroadPhaseStatus::Ok);
        ref.proxies[next++] = {box, ProxyKind::Moving, {}};
      }
    }
    if (frame % 3 == 2) {
      // Queries on an unbuilt structure (after updates) must be right too.
      expect_queries_match(s, ref, rng, world);
    }
    s.find_pairs(got);
    EXPECT_TRUE(s.validate());
    EXPECT_EQ(s.size(), ref.proxies.size());
    const std::vector<ProxyPair> want = ref.pairs();
    ASSERT_EQ(got.size(), want.size()) << "seed " << seed << " frame " << frame;
    ASSERT_TRUE(got == want) << "seed " << seed << " frame " << frame;
    EXPECT_EQ(s.stats().pairs_found, want.size());
    expect_queries_match(s, ref, rng, world);
    if (testing::Test::HasFailure()) return;
  }
}

/// Rejected calls change nothing.
template <class S>
void expect_rejections(S& s) {
  const Aabb good{Vec3(0), Vec3(1)};
  ASSERT_EQ(s.insert(3, good, ProxyKind::Moving, {}), BroadPhaseStatus::Ok);
  ASSERT_EQ(s.insert(4, {Vec3(Real(0.5)), Vec3(2)}, ProxyKind::Moving, {}), BroadPhaseStatus::Ok);
  EXPECT_EQ(s.insert(3, good, ProxyKind::Moving, {}), BroadPhaseStatus::DuplicateId);
  EXPECT_EQ(s.insert(5, {Vec3(1), Vec3(0)}, ProxyKind::Moving, {}), BroadPhaseStatus::InvalidBox);
  {
    ScopedNoFpTraps no_traps;
    const Real nan = std::numeric_limits<Real>::quiet_NaN();
    EXPECT_EQ(s.insert(6, {Vec3(0), Vec3(nan)}, ProxyKind::Moving, {}), BroadPhaseStatus::NotFinite);
    EXPECT_EQ(s.update(3, {Vec3(0), Vec3(nan)}), BroadPhaseStatus::NotFinite);
  }
  const Real inf = std::numeric_limits<Real>::infinity();
  EXPECT_EQ(s.insert(7, {Vec3(0), Vec3(inf)}, ProxyKind::Moving, {}), BroadPhaseStatus::NotFinite);
  EXPECT_EQ(s.insert(8, {Vec3(0), Vec3(kMaxCoordinate * 2)}, ProxyKind::Moving, {}), BroadPhaseStatus::InvalidBox);
  EXPECT_EQ(s.update(9, good), BroadPhaseStatus::UnknownId);
  EXPECT_EQ(s.remove(9), BroadPhaseStatus::UnknownId);
  const std::vector<ProxyUpdate> batch{{3, {Vec3(10), Vec3(11)}}, {99, good}};
  EXPECT_EQ(s.update(std::span<const ProxyUpdate>(batch)), BroadPhaseStatus::UnknownId);
  std::vector<ProxyPair> pairs;
  s.find_pairs(pairs);
  ASSERT_EQ(pairs.size(), 1u);  // the failed batch did not move proxy 3
  EXPECT_EQ(pairs[0], (ProxyPair{3, 4}));
  EXPECT_EQ(s.size(), 2u);
  EXPECT_TRUE(s.validate());
  // Huge but valid coordinates.
  ASSERT_EQ(s.insert(10, {Vec3(-kMaxCoordinate), Vec3(kMaxCoordinate)}, ProxyKind::Static, {}), BroadPhaseStatus::Ok);
  ASSERT_EQ(s.insert(11, {Vec3(kMaxCoordinate * Real(0.5)), Vec3(kMaxCoordinate)}, ProxyKind::Moving, {}),
            BroadPhaseStatus::Ok);
  s.find_pairs(pairs);
  EXPECT_EQ(pairs, (std::vector<ProxyPair>{{3, 4}, {3, 10}, {4, 10}, {10, 11}}));
  EXPECT_TRUE(s.validate());
  EXPECT_EQ(s.remove(10), BroadPhaseStatus::Ok);
  s.find_pairs(pairs);
  EXPECT_EQ(pairs, (std::vector<ProxyPair>{{3, 4}}));
}

}  // namespace proxima::test
