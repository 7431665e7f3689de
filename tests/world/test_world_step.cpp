// The step of CollisionWorld against the brute-force narrow phase: pair sets, events derived
// from consecutive pair sets, every broad-phase structure giving the same stream, executors
// and thread counts giving the same state, persistent manifold points.
#include <gtest/gtest.h>

#include <proxima/broadphase/any_broadphase.hpp>
#include <proxima/core/executor.hpp>

#include <cmath>
#include <sweep_size.hpp>

#include "world/world_scene.hpp"

namespace proxima::test {
namespace test_world_step {

/// True when the pair's exact gap is within the narrow phase's tolerance of the contact
/// distance, where touching or not is a matter of rounding.
bool within_touching_band(const CollisionWorld& world, const ObjectPair& p, Real contact_distance) {
  const ObjectDesc a = *world.object(p.a), b = *world.object(p.b);
  const DistanceResult d = distance(a.geometry, a.pose, b.geometry, b.pose);
  const Real band = sizeof(Real) == 4 ? Real(2e-4) : Real(1e-8);
  return std::abs(d.signed_distance - contact_distance) <= band;
}

/// Runs `frames` steps of a seeded scene of `count` objects on `structure`, checking every
/// step against the brute force; returns the hashes of the event stream per step.
std::vector<std::uint64_t> run_against_brute_force(const std::string& structure, int count, int frames,
                                                   Real contact_distance, std::uint64_t seed) {
  WorldSettings settings;
  settings.broadphase = structure;
  settings.contact_distance = contact_distance;
  CollisionWorld world = make_world(settings);
  Random rng(seed);
  std::vector<Mover> movers = populate(world, rng, count, kExtent);
  std::vector<ObjectPair> previous;
  std::vector<std::uint64_t> stream;
  std::size_t band_pairs = 0, total_pairs = 0;
  for (int f = 0; f < frames; ++f) {
    if (f > 0) advance(world, movers, kExtent);
    EXPECT_FALSE(world.step(Real(1) / Real(60)).has_value());
    const std::vector<ObjectPair> now = world_pairs(world);
    const std::vector<ObjectPair> reference = brute_force_pairs(world, contact_distance);
    // The world and the brute force may disagree only on pairs within the narrow phase's
    // tolerance of touching (its intersect counts a gap within tolerance as touching, its
    // collide does not); every other pair must agree.
    std::vector<ObjectPair> clear_disagreements;
    for (const auto& diff : {minus(now, reference), minus(reference, now)})
      for (const ObjectPair& p : diff)
        if (!within_touching_band(world, p, contact_distance)) clear_disagreements.push_back(p);
    EXPECT_TRUE(clear_disagreements.empty())
        << structure << " frame " << f << " seed " << seed << ": " << pair_text(clear_disagreements);
    band_pairs += minus(now, reference).size() + minus(reference, now).size();
    total_pairs += reference.size();
    const StepEvents& ev = world.events();
    EXPECT_EQ(pairs_of(ev.begin), minus(now, previous)) << structure << " frame " << f;
    EXPECT_EQ(pairs_of(ev.end), minus(previous, now)) << structure << " frame " << f;
    EXPECT_EQ(pairs_of(ev.persist), common(now, previous)) << structure << " frame " << f;
    std::uint64_t h = 0;
    for (const ObjectPair& p : now) h = h * 1000003u + p.a.index * 7919u + p.b.index;
    stream.push_back(h);
    previous = now;
  }
  EXPECT_LE(band_pairs * 200, total_pairs + 200) << "more than 0.5 % of the pairs within tolerance of touching";
  return stream;
}

TEST(WorldStep, PairsAndEventsMatchTheBruteForceNarrowPhase) {
  run_against_brute_force("tree", sweep_size(200), 30, Real(0), 1);
}

TEST(WorldStep, SpeculativeContactDistanceMatchesTheBruteForce) {
  run_against_brute_force("tree", sweep_size(150), 20, Real(0.1), 2);
}

TEST(WorldStep, EveryBroadPhaseStructureGivesTheSameStream) {
  const std::vector<std::uint64_t> reference = run_against_brute_force("brute", sweep_size(120), 12, Real(0), 3);
  for (std::string_view name : broadphase_names()) {
    if (name == "brute") continue;
    EXPECT_EQ(run_against_brute_force(std::string(name), sweep_size(120), 12, Real(0), 3), reference) << name;
  }
}

TEST(WorldStep, ThreadCountsGiveIdenticalStates) {
  auto run = [](Executor& executor) {
    CollisionWorld world = make_world();
    Random rng(4);
    std::vector<Mover> movers = populate(world, rng, sweep_size(300), kExtent);
    std::vector<std::uint64_t> hashes;
    for (int f = 0; f < 10; ++f) {
      if (f > 0) advance(world, movers, kExtent);
      EXPECT_FALSE(world.step(Real(1) / Real(60), executor).has_value());
      hashes.push_back(world.state_hash());
    }
    return hashes;
  };
  const std::vector<std::uint64_t> serial = run(serial_executor());
  for (std::size_t threads : {2u, 3u, 8u}) {
    ThreadPool pool(threads);
    EXPECT_EQ(run(pool), serial) << threads << " threads";
  }
}

TEST(WorldStep, RestingContactPointsKeepTheirIdsAndUserSlots) {
  CollisionWorld world = make_world();
  ObjectDesc ground;
  ground.geometry = *HalfSpace::create(Vec3(0, 0, 1), Real(0));
  ground.kind = ObjectKind::Static;
  const ObjectHandle g = *world.add(ground);
  ObjectDesc box;
  box.geometry = *Box::create(Vec3(Real(0.5)));
  box.pose = Transform{Vec3(0, 0, Real(0.49)), kIdentityQuat};
  const ObjectHandle b = *world.add(box);
  ASSERT_FALSE(world.step(Real(0.01)).has_value());
  ASSERT_EQ(world.contacts().size(), 1u);
  WorldManifold* m = world.contact(g, b);
  ASSERT_NE(m, nullptr);
  ASSERT_EQ(m->count, 4);
  std::vector<std::uint32_t> ids;
  for (int k = 0; k < m->count; ++k) {
    EXPECT_FALSE(m->points[k].persisted);
    m->points[k].user[0] = Real(k + 1);
    ids.push_back(m->points[k].id);
  }
  for (int f = 1; f < 5; ++f) {  // jiggle within the same features
    ASSERT_FALSE(world.move(b, Transform{Vec3(Real(0.001) * Real(f), 0, Real(0.49)), kIdentityQuat}).has_value());
    ASSERT_FALSE(world.step(Real(0.01)).has_value());
    m = world.contact(b, g);
    ASSERT_NE(m, nullptr);
    ASSERT_EQ(m->count, 4);
    EXPECT_EQ(world.events().persist.size(), 1u);
    for (int k = 0; k < m->count; ++k) {
      EXPECT_TRUE(m->points[k].persisted);
      const auto at = std::find(ids.begin(), ids.end(), m->points[k].id);
      ASSERT_NE(at, ids.end());
      EXPECT_EQ(m->points[k].user[0], Real(at - ids.begin() + 1));
    }
  }
  // Lifted off: the pair ends, and a new touch starts fresh ids.
  ASSERT_FALSE(world.move(b, Transform{Vec3(0, 0, Real(2)), kIdentityQuat}).has_value());
  ASSERT_FALSE(world.step(Real(0.01)).has_value());
  EXPECT_EQ(world.events().end.size(), 1u);
  EXPECT_TRUE(world.contacts().empty());
}

TEST(WorldStep, NormalsAreUnitAndPointFromTheLowerHandle) {
  CollisionWorld world = make_world();
  Random rng(5);
  std::vector<Mover> movers = populate(world, rng, sweep_size(200), kExtent);
  ASSERT_FALSE(world.step(Real(1) / Real(60)).has_value());
  ASSERT_FALSE(world.contacts().empty());
  for (const WorldManifold& m : world.contacts()) {
    EXPECT_LT(m.pair.a.index, m.pair.b.index);
    EXPECT_NEAR(glm::length(m.normal), Real(1), Real(1e-4));
    const ObjectDesc a = *world.object(m.pair.a);
    const ObjectDesc b = *world.object(m.pair.b);
    const DistanceResult d = distance(a.geometry, a.pose, b.geometry, b.pose);
    EXPECT_LE(d.signed_distance, Real(1e-3));
    for (int k = 0; k < m.count; ++k) EXPECT_NEAR(glm::length(m.points[k].contact.normal), Real(1), Real(1e-4));
  }
}

}  // namespace test_world_step
}  // namespace proxima::test
