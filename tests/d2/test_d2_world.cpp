/// @file test_d2_world.cpp
/// The 2D collision world against brute force: every step's touching pairs equal those of a
/// loop over all pairs with the narrow phase; events follow from consecutive sets; several
/// broad phases and thread counts give identical events; continuous detection stops a bullet
/// that a discrete step lets through; queries equal loops over every object; bad calls name
/// their field and change nothing.

#include <gtest/gtest.h>

#include <proxima/d2/collision_world.hpp>
#include <proxima/d2/narrowphase.hpp>

#include <algorithm>
#include <set>
#include <string>
#include <support/random.hpp>
#include <vector>

#include "sweep_size.hpp"

namespace proxima::d2 {
namespace {

/// A scene: shapes, start poses and per-step velocities (linear, angular), kinds and filters.
struct SceneObject {
  ObjectDesc desc;
  Vec2 velocity{Real(0)};
  Real spin = Real(0);
};

std::vector<SceneObject> random_scene(proxima::test::Random& rng, int count) {
  std::vector<SceneObject> scene;
  const std::vector<Vec2> floor = {{Real(20), Real(0)}, {Real(10), Real(1)}, {Real(0), Real(0)}, {Real(-20), Real(2)}};
  SceneObject ground{{Chain::create(floor, false).value(), Pose::identity(), ObjectKind::Static}};
  scene.push_back(ground);
  for (int i = 0; i < count; ++i) {
    SceneObject o;
    const int kind = rng.integer(0, 3);
    const Real size = rng.uniform(Real(0.3), Real(1));
    if (kind == 0) o.desc.shape = Circle::create(size).value();
    if (kind == 1) o.desc.shape = Polygon::box(size, Real(0.6) * size).value();
    if (kind == 2) o.desc.shape = Capsule::create({-size, 0}, {size, 0}, Real(0.3) * size).value();
    if (kind == 3) {
      const std::vector<Vec2> tri = {{0, 0}, {size, 0}, {0, size}};
      o.desc.shape = Polygon::create(tri, Real(0.05)).value();
    }
    o.desc.pose =
        Pose::from({rng.uniform(Real(-15), Real(15)), rng.uniform(Real(-1), Real(8))}, rng.uniform(Real(-3), Real(3)));
    o.desc.kind = rng.integer(0, 5) == 0 ? ObjectKind::Static : ObjectKind::Moving;
    o.desc.filter.layer = 1ull << rng.integer(0, 2);
    o.desc.filter.mask = rng.integer(0, 4) == 0 ? ~(1ull << rng.integer(0, 2)) : ~0ull;
    o.desc.sensor = rng.integer(0, 9) == 0;
    o.desc.user_data = static_cast<std::uint64_t>(i) * 7 + 1;
    if (o.desc.kind == ObjectKind::Moving) {
      o.velocity = {rng.uniform(Real(-0.2), Real(0.2)), rng.uniform(Real(-0.2), Real(0.2))};
      o.spin = rng.uniform(Real(-0.1), Real(0.1));
    }
    scene.push_back(o);
  }
  return scene;
}

Pose pose_at(const SceneObject& o, int step) {
  const Real t = static_cast<Real>(step);
  return Pose::from(o.desc.pose.position + t * o.velocity, o.desc.pose.rotation.angle() + t * o.spin);
}

/// The touching non-sensor pairs and (sensor, other) pairs by brute force.
void brute_force(const std::vector<SceneObject>& scene, const std::vector<ObjectHandle>& handles, int step,
                 const WorldSettings& settings, std::set<ObjectPair>& touching,
                 std::set<std::pair<ObjectHandle, ObjectHandle>>& sensing) {
  std::vector<Manifold> scratch;
  for (std::size_t i = 0; i < scene.size(); ++i) {
    for (std::size_t j = i + 1; j < scene.size(); ++j) {
      const ObjectDesc& a = scene[i].desc;
      const ObjectDesc& b = scene[j].desc;
      if (a.kind == ObjectKind::Static && b.kind == ObjectKind::Static) continue;
      if (!can_collide(a.filter, b.filter)) continue;
      const Pose pa = pose_at(scene[i], step), pb = pose_at(scene[j], step);
      if (a.sensor || b.sensor) {
        if (a.sensor && b.sensor && !settings.sensors_sense_sensors) continue;
        if (!intersect(a.shape, pa, b.shape, pb)) continue;
        if (a.sensor) sensing.insert({handles[i], handles[j]});
        if (b.sensor) sensing.insert({handles[j], handles[i]});
        continue;
      }
      scratch.clear();
      if (collide_all(a.shape, pa, b.shape, pb, settings.contact_distance, scratch) > 0)
        touching.insert({handles[i], handles[j]});
    }
  }
}

/// Runs the scene for `steps` steps, checking every step against brute force; returns every
/// event as text (for comparing runs).
std::string run_and_check(const std::vector<SceneObject>& scene, const WorldSettings& settings, int steps,
                          Executor& executor) {
  CollisionWorld world = CollisionWorld::create(settings).value();
  std::vector<ObjectHandle> handles;
  for (const SceneObject& o : scene) handles.push_back(world.add(o.desc).value());
  std::set<ObjectPair> before;
  std::set<std::pair<ObjectHandle, ObjectHandle>> sensed_before;
  std::string log;
  for (int k = 0; k < steps; ++k) {
    for (std::size_t i = 0; i < scene.size(); ++i) {
      if (scene[i].desc.kind == ObjectKind::Moving) {
        EXPECT_FALSE(world.move(handles[i], pose_at(scene[i], k)));
      }
    }
    EXPECT_FALSE(world.step(executor));
    std::set<ObjectPair> touching;
    std::set<std::pair<ObjectHandle, ObjectHandle>> sensing;
    brute_force(scene, handles, k, settings, touching, sensing);
    const StepEvents& ev = world.events();
    std::set<ObjectPair> now;
    for (const ContactEvent& e : ev.begin) {
      now.insert(e.pair);
      EXPECT_FALSE(before.count(e.pair)) << "step " << k;
      EXPECT_EQ(e.user_data_a, scene[e.pair.a.index].desc.user_data);
    }
    for (const ContactEvent& e : ev.persist) {
      now.insert(e.pair);
      EXPECT_TRUE(before.count(e.pair)) << "step " << k;
    }
    for (const ContactEvent& e : ev.end) EXPECT_TRUE(before.count(e.pair) && !touching.count(e.pair)) << "step " << k;
    EXPECT_EQ(now, touching) << "step " << k;

    std::set<std::pair<ObjectHandle, ObjectHandle>> sensed = sensed_before;
    for (const SensorEvent& e : ev.sensor_enter) sensed.insert({e.sensor, e.other});
    for (const SensorEvent& e : ev.sensor_exit) sensed.erase({e.sensor, e.other});
    EXPECT_EQ(sensed, sensing) << "step " << k;
    std::set<ObjectPair> manifold_pairs;
    for (const WorldManifold& m : world.manifolds()) manifold_pairs.insert(m.pair);
    EXPECT_EQ(manifold_pairs, touching) << "step " << k;
    before = std::move(touching);
    sensed_before = std::move(sensed);
    for (const ContactEvent& e : ev.begin)
      log += "b" + std::to_string(e.pair.a.index) + "," + std::to_string(e.pair.b.index) + ";";
    for (const ContactEvent& e : ev.end)
      log += "e" + std::to_string(e.pair.a.index) + "," + std::to_string(e.pair.b.index) + ";";
    for (const WorldManifold& m : world.manifolds()) {
      for (int p = 0; p < m.manifold.count; ++p) log += std::to_string(m.manifold.points[p].depth) + ";";
    }
  }
  return log;
}

TEST(D2World, EveryStepMatchesBruteForce) {
  proxima::test::Random rng(0xD2F0);
  const std::vector<SceneObject> scene = random_scene(rng, 120);
  WorldSettings settings;
  settings.contact_distance = Real(0.02);
  const std::string tree = run_and_check(scene, settings, proxima::test::sweep_size(40), serial_executor());
  EXPECT_GT(tree.size(), 100u);
  for (const char* structure : {"sap", "grid", "brute", "quadtree"}) {
    settings.broadphase = structure;
    EXPECT_EQ(run_and_check(scene, settings, proxima::test::sweep_size(40), serial_executor()), tree) << structure;
  }
  ThreadPool pool(2);
  settings.broadphase = "tree";
  EXPECT_EQ(run_and_check(scene, settings, proxima::test::sweep_size(40), pool), tree) << "two threads";
}

TEST(D2World, RemovingAnObjectEndsItsContacts) {
  CollisionWorld world = CollisionWorld::create().value();
  const ObjectHandle a = world.add({Circle::create(Real(1)).value(), Pose::identity()}).value();
  const ObjectHandle b = world
                             .add({Circle::create(Real(1)).value(),
                                   Pose::from({Real(1.5), 0}, 0),
                                   ObjectKind::Moving,
                                   {},
                                   false,
                                   CcdMode::Auto,
                                   42})
                             .value();
  world.step();
  ASSERT_EQ(world.events().begin.size(), 1u);
  EXPECT_FALSE(world.remove(b));
  EXPECT_FALSE(world.contains(b));
  EXPECT_TRUE(world.remove(b).has_value());  // stale now
  world.step();
  ASSERT_EQ(world.events().end.size(), 1u);
  EXPECT_EQ(world.events().end[0].user_data_b, 42u);
  // The slot is reused with a new generation: the old handle stays stale.
  const ObjectHandle c = world.add({Circle::create(Real(1)).value(), Pose::from({Real(1.5), 0}, 0)}).value();
  EXPECT_EQ(c.index, b.index);
  EXPECT_NE(c.generation, b.generation);
  EXPECT_FALSE(world.contains(b));
  world.step();
  ASSERT_EQ(world.events().begin.size(), 1u);
  EXPECT_EQ(world.events().begin[0].pair, (ObjectPair{a, c}));
}

TEST(D2World, ABulletIsStoppedByContinuousDetectionAndTunnelsWithout) {
  for (CcdMode mode : {CcdMode::Off, CcdMode::Auto, CcdMode::Bullet}) {
    CollisionWorld world = CollisionWorld::create().value();
    const ObjectHandle wall =
        world.add({Segment::create({0, Real(-5)}, {0, Real(5)}).value(), Pose::identity(), ObjectKind::Static}).value();
    const ObjectHandle bullet =
        world
            .add(
                {Circle::create(Real(0.05)).value(), Pose::from({Real(-3), 0}, 0), ObjectKind::Moving, {}, false, mode})
            .value();
    world.step();
    world.move(bullet, Pose::from({Real(5), 0}, 0));  // through the wall in one step
    world.step();
    EXPECT_TRUE(world.events().begin.empty());
    if (mode == CcdMode::Off) {
      EXPECT_TRUE(world.events().impacts.empty());
      continue;
    }
    ASSERT_EQ(world.events().impacts.size(), 1u) << static_cast<int>(mode);
    const ImpactEvent& hit = world.events().impacts[0];
    EXPECT_EQ(hit.a, bullet);
    EXPECT_EQ(hit.b, wall);
    EXPECT_NEAR(hit.toi, Real(2.95) / Real(8), Real(1e-4));
    EXPECT_NEAR(hit.normal.x, Real(1), Real(1e-4));
  }
}

TEST(D2World, QueriesEqualLoopsOverEveryObject) {
  proxima::test::Random rng(0xD2F1);
  const std::vector<SceneObject> scene = random_scene(rng, 80);
  CollisionWorld world = CollisionWorld::create().value();
  std::vector<ObjectHandle> handles;
  for (const SceneObject& o : scene) handles.push_back(world.add(o.desc).value());
  for (int q = 0; q < proxima::test::sweep_size(500); ++q) {
    const Ray ray{{rng.uniform(Real(-20), Real(20)), rng.uniform(Real(-3), Real(10))},
                  {rng.uniform(Real(-1), Real(1)), rng.uniform(Real(-1), Real(1))}};
    QueryFilter filter;
    filter.mask = q % 3 == 0 ? 1ull : ~0ull;
    std::optional<WorldRayHit> expected;
    for (std::size_t i = 0; i < scene.size(); ++i) {
      if (!filter.accepts(handles[i], scene[i].desc.filter)) continue;
      const auto hit = raycast(scene[i].desc.shape, scene[i].desc.pose, ray, Real(30));
      if (hit && (!expected || hit->t < expected->hit.t)) expected = WorldRayHit{handles[i], *hit};
    }
    const auto got = world.raycast(ray, Real(30), filter);
    ASSERT_EQ(got.has_value(), expected.has_value()) << "query " << q;
    if (got) {
      EXPECT_NEAR(got->hit.t, expected->hit.t, Real(1e-5)) << "query " << q;
    }
    const Shape probe = Circle::create(rng.uniform(Real(0.2), Real(2))).value();
    const Pose at = Pose::from(ray.origin, 0);
    std::vector<ObjectHandle> inside, brute;
    world.overlap(probe, at, filter, inside);
    for (std::size_t i = 0; i < scene.size(); ++i) {
      if (filter.accepts(handles[i], scene[i].desc.filter) &&
          intersect(probe, at, scene[i].desc.shape, scene[i].desc.pose)) {
        brute.push_back(handles[i]);
      }
    }
    EXPECT_EQ(inside, brute) << "query " << q;
  }
}

TEST(D2World, BadCallsNameTheirFieldAndChangeNothing) {
  WorldSettings bad;
  bad.broadphase = "no such structure";
  EXPECT_EQ(CollisionWorld::create(bad).error().field, "settings.broadphase");
  CollisionWorld world = CollisionWorld::create().value();
  const std::vector<Vec2> pts = {{0, 0}, {1, 0}};
  EXPECT_EQ(world.add({Chain::create(pts, false).value(), Pose::identity(), ObjectKind::Moving}).error().field,
            "desc.kind");
  const ObjectHandle a = world.add({Circle::create(Real(1)).value(), Pose::identity()}).value();
  proxima::test::ScopedNoFpTraps no_traps;
  const Pose nan_pose = Pose::from({std::numeric_limits<Real>::quiet_NaN(), 0}, 0);
  EXPECT_EQ(world.move(a, nan_pose)->field, "pose");
  EXPECT_EQ(world.pose(a)->position, Vec2(0, 0));
  EXPECT_EQ(world.move(ObjectHandle{7, 0}, Pose::identity())->field, "handle");
  EXPECT_EQ(world.size(), 1u);

  struct Meddler : WorldListener {
    CollisionWorld* world = nullptr;
    ObjectHandle target;
    int refused = 0;
    void on_contact_begin(const CollisionWorld&, const ContactEvent&) override {
      refused += world->remove(target).has_value();
    }
  } meddler;
  meddler.world = &world;
  meddler.target = a;
  world.add({Circle::create(Real(1)).value(), Pose::from({1, 0}, 0)}).value();
  world.set_listener(&meddler);
  world.step();
  EXPECT_EQ(meddler.refused, 1);
  EXPECT_TRUE(world.contains(a));
}

// objects() and object() against a map kept beside the world: after random adds, removals
// (slots reused), moves and filter changes, the live handles are exactly the map's keys in
// slot order and each description is the last one the caller gave.
TEST(D2World, ObjectsListTheLiveObjectsAsTheCallerLastSetThem) {
  proxima::test::Random rng(77);
  CollisionWorld world = CollisionWorld::create().value();
  std::vector<std::pair<ObjectHandle, ObjectDesc>> expected;
  const std::vector<SceneObject> scene = random_scene(rng, 60);
  for (int round = 0; round < 200; ++round) {
    const int op = rng.integer(0, 3);
    if (op == 0 || expected.empty()) {
      const ObjectDesc& d = scene[static_cast<std::size_t>(rng.integer(0, int(scene.size()) - 1))].desc;
      expected.emplace_back(world.add(d).value(), d);
      continue;
    }
    const auto k = static_cast<std::size_t>(rng.integer(0, int(expected.size()) - 1));
    auto& [handle, desc] = expected[k];
    if (op == 1) {
      ASSERT_FALSE(world.remove(handle));
      EXPECT_FALSE(world.object(handle).has_value());
      expected.erase(expected.begin() + static_cast<std::ptrdiff_t>(k));
    } else if (op == 2) {
      const Vec2 position{rng.uniform(Real(-9), Real(9)), rng.uniform(Real(-9), Real(9))};
      desc.pose = Pose::from(position, rng.uniform(Real(-1), Real(1)));
      ASSERT_FALSE(world.move(handle, desc.pose));
    } else {
      desc.filter.layer = 1ull << rng.integer(0, 5);
      ASSERT_FALSE(world.set_filter(handle, desc.filter));
    }
  }
  std::sort(expected.begin(), expected.end(),
            [](const auto& x, const auto& y) { return x.first.index < y.first.index; });
  const std::vector<ObjectHandle> live = world.objects();
  ASSERT_EQ(live.size(), expected.size());
  ASSERT_EQ(world.size(), expected.size());
  for (std::size_t i = 0; i < live.size(); ++i) {
    EXPECT_EQ(live[i], expected[i].first);
    const std::optional<ObjectDesc> got = world.object(live[i]);
    ASSERT_TRUE(got.has_value());
    const ObjectDesc& want = expected[i].second;
    EXPECT_EQ(got->shape.type(), want.shape.type());
    const Aabb gb = got->shape.world_aabb(Pose::identity()), wb = want.shape.world_aabb(Pose::identity());
    EXPECT_EQ(gb.min, wb.min);
    EXPECT_EQ(gb.max, wb.max);
    EXPECT_EQ(got->pose.position, want.pose.position);
    EXPECT_EQ(got->pose.rotation.c, want.pose.rotation.c);
    EXPECT_EQ(got->pose.rotation.s, want.pose.rotation.s);
    EXPECT_EQ(got->kind, want.kind);
    EXPECT_EQ(got->filter.layer, want.filter.layer);
    EXPECT_EQ(got->filter.mask, want.filter.mask);
    EXPECT_EQ(got->sensor, want.sensor);
    EXPECT_EQ(got->ccd, want.ccd);
    EXPECT_EQ(got->user_data, want.user_data);
  }
}

}  // namespace
}  // namespace proxima::d2
