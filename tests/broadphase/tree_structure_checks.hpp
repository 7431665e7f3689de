#pragma once
// Differential checks shared by the tree-structure tests (dynamic AABB tree, kd-tree, BSP
// tree): random scenes stepped frame after frame, every result compared with an O(n^2)
// reference written here (pairs, box, point and ray queries), validate() after every step,
// and rejected edits checked to leave the structure unchanged.
#include <gtest/gtest.h>

#include <proxima/broadphase/broadphase.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <vector>

#include "core/executor_set.hpp"
#include "support/random.hpp"

namespace proxima::test {

/// One reference proxy.
struct RefProxy {
  Aabb box;
  ProxyKind kind = ProxyKind::Moving;
  ProxyFilter filter;
};

/// The reference state: proxies by id.
using RefScene = std::map<ProxyId, RefProxy>;

/// Every pair by the O(n^2) definition of broadphase.hpp, sorted.
inline std::vector<ProxyPair> reference_pairs(const RefScene& scene) {
  std::vector<ProxyPair> out;
  for (auto i = scene.begin(); i != scene.end(); ++i) {
    for (auto j = std::next(i); j != scene.end(); ++j) {
      const RefProxy& a = i->second;
      const RefProxy& b = j->second;
      if (a.kind == ProxyKind::Static && b.kind == ProxyKind::Static) continue;
      if (!can_pair(a.filter, b.filter)) continue;
      const bool overlap = a.box.min.x <= b.box.max.x && b.box.min.x <= a.box.max.x && a.box.min.y <= b.box.max.y &&
                           b.box.min.y <= a.box.max.y && a.box.min.z <= b.box.max.z && b.box.min.z <= a.box.max.z;
      if (overlap) out.push_back({i->first, j->first});
    }
  }
  return out;
}

/// Entry fraction of a ray into a box by the slab method, written independently (no
/// division by zero: zero components are containment tests). False on a miss.
inline bool reference_ray_box(const Ray& ray, Real max_t, const Aabb& box, Real& t_out) {
  Real lo = Real(0);
  Real hi = max_t;
  for (int a = 0; a < 3; ++a) {
    const Real o = ray.origin[a];
    const Real d = ray.direction[a];
    if (d == Real(0)) {
      if (o < box.min[a] || o > box.max[a]) return false;
      continue;
    }
    const Real t1 = (box.min[a] - o) / d;
    const Real t2 = (box.max[a] - o) / d;
    lo = std::max(lo, std::min(t1, t2));
    hi = std::min(hi, std::max(t1, t2));
    if (lo > hi) return false;
  }
  t_out = lo;
  return true;
}

template <class S>
std::set<ProxyId> collect_box(const S& s, const Aabb& box) {
  std::set<ProxyId> ids;
  s.query_aabb(box, [&](ProxyId id) {
    EXPECT_TRUE(ids.insert(id).second) << "reported twice: " << id;
    return true;
  });
  return ids;
}

template <class S>
std::set<ProxyId> collect_point(const S& s, const Vec3& p) {
  std::set<ProxyId> ids;
  s.query_point(p, [&](ProxyId id) {
    EXPECT_TRUE(ids.insert(id).second) << "reported twice: " << id;
    return true;
  });
  return ids;
}

template <class S>
std::set<ProxyId> collect_ray(const S& s, const Ray& ray, Real max_t) {
  std::set<ProxyId> ids;
  s.query_ray(ray, max_t, [&](ProxyId id, Real t) {
    EXPECT_TRUE(ids.insert(id).second) << "reported twice: " << id;
    EXPECT_GE(t, Real(0));
    EXPECT_LE(t, max_t);
    return Real(-1);  // ignore: never clip
  });
  return ids;
}

/// Compares box, point and ray queries (and the clipped nearest ray hit) with the reference.
template <class S>
void check_queries(const S& s, const RefScene& scene, Random& rng, Real extent, int count) {
  for (int q = 0; q < count; ++q) {
    const Vec3 c = rng.vec3(-extent, extent);
    const Vec3 h = rng.vec3(Real(0), extent * Real(0.2));
    const Aabb box{c - h, c + h};
    std::set<ProxyId> expect_box;
    std::set<ProxyId> expect_point;
    for (const auto& [id, p] : scene) {
      if (p.box.overlaps(box)) expect_box.insert(id);
      if (p.box.contains(c)) expect_point.insert(id);
    }
    ASSERT_EQ(collect_box(s, box), expect_box);
    ASSERT_EQ(collect_point(s, c), expect_point);

    const Vec3 origin = rng.vec3(-extent, extent);
    const Real speed = rng.uniform(Real(0.5), Real(2));
    Ray ray{origin, rng.unit_vector() * speed};
    if (q % 5 == 0) ray.direction[q % 3] = Real(0);  // axis-parallel rays
    const Real max_t = q % 7 == 0 ? std::numeric_limits<Real>::infinity() : extent * Real(1.5);
    std::set<ProxyId> expect_ray;
    Real nearest = max_t;
    bool any = false;
    for (const auto& [id, p] : scene) {
      Real t;
      if (reference_ray_box(ray, max_t, p.box, t)) {
        expect_ray.insert(id);
        nearest = std::min(nearest, t);
        any = true;
      }
    }
    ASSERT_EQ(collect_ray(s, ray, max_t), expect_ray);
    // Clipping: answering t each time must end at the nearest entry fraction.
    Real got = max_t;
    bool got_any = false;
    s.query_ray(ray, max_t, [&](ProxyId, Real t) {
      EXPECT_LE(t, got);
      got = std::min(got, t);
      got_any = true;
      return t;
    });
    ASSERT_EQ(got_any, any);
    if (any) {
      ASSERT_EQ(got, nearest);
    }
  }
}

/// Options of a random scene run.
struct SceneOptions {
  int proxies = 300;
  int frames = 25;
  Real extent = Real(20);  ///< boxes in [-extent, extent]^3
  Real size = Real(1.5);   ///< largest half extent
  Real speed = Real(0.2);  ///< largest per-frame displacement
  Real static_share = Real(0.4);
  bool filters = true;
  bool integer_grid = false;  ///< integer coordinates: many touching boxes
  bool flat = false;          ///< some zero-thickness boxes
  bool teleports = true;      ///< some proxies jump across the scene
  bool edits = true;          ///< inserts and removes between frames
  bool rebuilds = true;       ///< call rebuild() now and then
};

inline Aabb random_box(Random& rng, const SceneOptions& o) {
  Vec3 c = rng.vec3(-o.extent, o.extent);
  Vec3 h = rng.vec3(o.size * Real(0.05), o.size);
  if (o.integer_grid) {
    for (int a = 0; a < 3; ++a) {
      c[a] = std::round(c[a]);
      h[a] = std::max(Real(0.5), std::round(h[a] * 2) / 2);
    }
  }
  if (o.flat && rng.integer(0, 3) == 0) h[rng.integer(0, 2)] = Real(0);
  return {c - h, c + h};
}

inline ProxyFilter random_filter(Random& rng, bool filters) {
  if (!filters) return {};
  ProxyFilter f;
  f.layer = 1u << rng.integer(0, 2);
  f.mask = rng.integer(0, 3) == 0 ? (1u | 2u) : ~0u;
  return f;
}

/// Checks that a rejected edit left the structure as it was (pairs, size, validity).
template <class S>
void expect_unchanged(S& s, const std::vector<ProxyPair>& before, std::size_t size_before) {
  std::vector<ProxyPair> after;
  s.find_pairs(after);
  EXPECT_EQ(after, before);
  EXPECT_EQ(s.size(), size_before);
  EXPECT_TRUE(s.validate());
}

/// Bad edits: each is rejected with the right status and changes nothing.
template <class S>
void check_rejections(S& s, const RefScene& scene) {
  std::vector<ProxyPair> before;
  s.find_pairs(before);
  const std::size_t n = s.size();
  const Real nan = std::numeric_limits<Real>::quiet_NaN();
  const Real inf = std::numeric_limits<Real>::infinity();
  const Aabb good{Vec3(0), Vec3(1)};
  const Aabb nan_box{Vec3(0, nan, 0), Vec3(1)};
  const Aabb inf_box{Vec3(0), Vec3(1, 1, inf)};
  const Aabb inverted{Vec3(1, 0, 0), Vec3(0, 1, 1)};
  const Aabb huge{Vec3(-kRealMax), Vec3(kRealMax)};
  ProxyId fresh = 0;
  while (scene.count(fresh)) ++fresh;
  const ProxyId existing = scene.empty() ? 0 : scene.begin()->first;

  EXPECT_EQ(s.insert(fresh, nan_box, ProxyKind::Moving, {}), BroadPhaseStatus::NotFinite);
  EXPECT_EQ(s.insert(fresh, inf_box, ProxyKind::Moving, {}), BroadPhaseStatus::NotFinite);
  EXPECT_EQ(s.insert(fresh, inverted, ProxyKind::Static, {}), BroadPhaseStatus::InvalidBox);
  EXPECT_EQ(s.insert(fresh, huge, ProxyKind::Moving, {}), BroadPhaseStatus::InvalidBox);
  EXPECT_EQ(s.remove(fresh), BroadPhaseStatus::UnknownId);
  EXPECT_EQ(s.update(fresh, good), BroadPhaseStatus::UnknownId);
  if (!scene.empty()) {
    EXPECT_EQ(s.insert(existing, good, ProxyKind::Moving, {}), BroadPhaseStatus::DuplicateId);
    EXPECT_EQ(s.update(existing, nan_box), BroadPhaseStatus::NotFinite);
    EXPECT_EQ(s.update(existing, inverted), BroadPhaseStatus::InvalidBox);
    // Batch: good entries first, then a bad one: nothing applied.
    std::vector<ProxyUpdate> batch;
    for (const auto& [id, p] : scene) batch.push_back({id, Aabb{Vec3(-1), Vec3(1)}});
    batch.push_back({existing, inf_box});
    EXPECT_EQ(s.update(batch), BroadPhaseStatus::NotFinite);
    batch.back() = {fresh, good};
    EXPECT_EQ(s.update(batch), BroadPhaseStatus::UnknownId);
  }
  expect_unchanged(s, before, n);
}

/// Runs a random scene: frames of motion, edits and rebuilds; compares every frame's pairs
/// with the reference, validates after every step and checks queries now and then.
template <class S>
void run_scene(S& s, std::uint64_t seed, const SceneOptions& o) {
  Random rng(seed);
  RefScene scene;
  std::vector<Vec3> velocity(static_cast<std::size_t>(o.proxies) * 2 + 8, Vec3(0));
  ProxyId next_id = 0;
  auto add = [&](ProxyId id) {
    RefProxy p{random_box(rng, o), rng.uniform(0, 1) < o.static_share ? ProxyKind::Static : ProxyKind::Moving,
               random_filter(rng, o.filters)};
    ASSERT_EQ(s.insert(id, p.box, p.kind, p.filter), BroadPhaseStatus::Ok);
    scene[id] = p;
    velocity[id] = rng.vec3(-o.speed, o.speed);
  };
  for (int i = 0; i < o.proxies; ++i) add(next_id++);
  ASSERT_TRUE(s.validate());
  ASSERT_EQ(s.size(), scene.size());

  std::vector<ProxyPair> got;
  for (int frame = 0; frame < o.frames; ++frame) {
    // Motion: a batch update of most moving proxies, single updates of some others.
    std::vector<ProxyUpdate> batch;
    for (auto& [id, p] : scene) {
      if (p.kind == ProxyKind::Static && rng.integer(0, 20) != 0) continue;
      Aabb b = p.box;
      if (o.teleports && rng.integer(0, 50) == 0) {
        b = random_box(rng, o);
      } else {
        Vec3 v = velocity[id];
        if (o.integer_grid) v = glm::round(v * Real(4)) / Real(4);
        b.min += v;
        b.max += v;
      }
      p.box = b;
      if (rng.integer(0, 3) == 0) {
        ASSERT_EQ(s.update(id, b), BroadPhaseStatus::Ok);
      } else {
        batch.push_back({id, b});
      }
    }
    ASSERT_EQ(s.update(batch), BroadPhaseStatus::Ok);
    ASSERT_TRUE(s.validate()) << "after updates, frame " << frame;

    if (o.edits && frame % 3 == 1) {
      for (int k = 0; k < 6 && !scene.empty(); ++k) {
        auto it = scene.begin();
        std::advance(it, rng.integer(0, static_cast<int>(scene.size()) - 1));
        ASSERT_EQ(s.remove(it->first), BroadPhaseStatus::Ok);
        scene.erase(it);
        ASSERT_TRUE(s.validate()) << "after remove, frame " << frame;
      }
      for (int k = 0; k < 6 && next_id < velocity.size(); ++k) add(next_id++);
      ASSERT_TRUE(s.validate()) << "after insert, frame " << frame;
    }
    if (o.rebuilds && frame % 7 == 3) {
      s.rebuild();
      ASSERT_TRUE(s.validate()) << "after rebuild, frame " << frame;
    }
    ASSERT_EQ(s.size(), scene.size());
    s.find_pairs(got);
    ASSERT_EQ(got, reference_pairs(scene)) << "frame " << frame << " seed " << seed;
    ASSERT_TRUE(s.validate()) << "after find_pairs, frame " << frame;
    EXPECT_EQ(s.stats().pairs_found, got.size());
    if (frame % 6 == 0) check_queries(s, scene, rng, o.extent, 20);
    if (frame % 10 == 4) check_rejections(s, scene);
  }
  // Remove everything: empty and valid.
  for (const auto& entry : scene) ASSERT_EQ(s.remove(entry.first), BroadPhaseStatus::Ok);
  EXPECT_EQ(s.size(), 0u);
  EXPECT_TRUE(s.validate());
  s.find_pairs(got);
  EXPECT_TRUE(got.empty());
}

/// The standard set of scenes every tree structure passes.
template <class Make>
void run_standard_scenes(Make make) {
  {
    SCOPED_TRACE("uniform");
    auto s = make();
    run_scene(s, 11, SceneOptions{});
  }
  {
    SCOPED_TRACE("dense, all moving");
    auto s = make();
    SceneOptions o;
    o.proxies = 400;
    o.extent = Real(8);
    o.static_share = Real(0);
    run_scene(s, 12, o);
  }
  {
    SCOPED_TRACE("touching integer boxes, flat boxes");
    auto s = make();
    SceneOptions o;
    o.integer_grid = true;
    o.flat = true;
    o.extent = Real(6);
    run_scene(s, 13, o);
  }
  {
    SCOPED_TRACE("mostly static, no filters");
    auto s = make();
    SceneOptions o;
    o.static_share = Real(0.9);
    o.filters = false;
    run_scene(s, 14, o);
  }
  {
    SCOPED_TRACE("identical boxes");
    auto s = make();
    RefScene scene;
    for (ProxyId id = 0; id < 64; ++id) {
      const RefProxy p{Aabb{Vec3(1), Vec3(2)}, id % 3 == 0 ? ProxyKind::Static : ProxyKind::Moving, {}};
      ASSERT_EQ(s.insert(id, p.box, p.kind, p.filter), BroadPhaseStatus::Ok);
      scene[id] = p;
    }
    s.rebuild();
    ASSERT_TRUE(s.validate());
    std::vector<ProxyPair> got;
    s.find_pairs(got);
    ASSERT_EQ(got, reference_pairs(scene));
    Random rng(15);
    check_queries(s, scene, rng, Real(3), 20);
  }
  {
    SCOPED_TRACE("empty and single");
    auto s = make();
    std::vector<ProxyPair> got{{1, 2}};
    s.find_pairs(got);
    EXPECT_TRUE(got.empty());
    EXPECT_TRUE(s.validate());
    s.rebuild();
    EXPECT_TRUE(collect_box(s, Aabb{Vec3(-1), Vec3(1)}).empty());
    ASSERT_EQ(s.insert(7, Aabb{Vec3(0), Vec3(1)}, ProxyKind::Moving, {}), BroadPhaseStatus::Ok);
    s.rebuild();
    EXPECT_TRUE(s.validate());
    s.find_pairs(got);
    EXPECT_TRUE(got.empty());
    EXPECT_EQ(collect_point(s, Vec3(1)), std::set<ProxyId>{7});
    EXPECT_EQ(collect_ray(s, Ray{Vec3(-1, 0.5, 0.5), Vec3(1, 0, 0)}, Real(1)), std::set<ProxyId>{7});
    EXPECT_TRUE(collect_ray(s, Ray{Vec3(-1, 0.5, 0.5), Vec3(1, 0, 0)}, Real(0.5)).empty());
  }
}

}  // namespace proxima::test

namespace proxima::test {

/// find_pairs(out, executor) gives the serial result on every executor of the test set, over
/// a few frames of motion (5000 proxies: above the parallel helpers' inline threshold).
template <class S>
void check_parallel_equals_serial(S& s, std::uint64_t seed) {
  Random rng(seed);
  std::vector<Aabb> boxes;
  for (ProxyId i = 0; i < 5000; ++i) {
    const Vec3 p = rng.vec3(-40, 40);
    const Vec3 h = rng.vec3(Real(0.1), Real(1.2));
    boxes.push_back({p - h, p + h});
    ASSERT_EQ(s.insert(i, boxes.back(), i % 5 == 0 ? ProxyKind::Static : ProxyKind::Moving, {}), BroadPhaseStatus::Ok);
  }
  std::vector<ProxyPair> serial;
  std::vector<ProxyPair> parallel;
  std::vector<NamedExecutor> executors = test_executors();
  for (int frame = 0; frame < 4; ++frame) {
    s.find_pairs(serial);
    ASSERT_FALSE(serial.empty());
    for (NamedExecutor& e : executors) {
      s.find_pairs(parallel, *e.executor);
      ASSERT_EQ(parallel, serial) << "executor " << e.name << " frame " << frame;
    }
    std::vector<ProxyUpdate> updates;
    for (ProxyId i = 0; i < boxes.size(); ++i) {
      if (i % 5 == 0) continue;
      const Vec3 d = rng.vec3(Real(-0.3), Real(0.3));
      boxes[i].min += d;
      boxes[i].max += d;
      updates.push_back({i, boxes[i]});
    }
    ASSERT_EQ(s.update(updates), BroadPhaseStatus::Ok);
  }
}

}  // namespace proxima::test
