// CollisionWorld snapshots: a saved and loaded world has the same state hash and gives the
// same events and hashes as the original over the following steps (hulls, meshes,
// compounds, half-spaces, sensors, attachments, exclusions, user slots included); damaged
// snapshots (truncated at every length, wrong magic or version, random byte flips) are
// rejected with an error naming the snapshot, or load into a valid world, never a crash.
#include <gtest/gtest.h>

#include <sstream>
#include <sweep_size.hpp>

#include "world/world_scene.hpp"

namespace proxima::test {
namespace test_world_snapshot {

/// A scene with every kind of object and a few steps behind it.
struct Saved {
  CollisionWorld world = make_world();
  std::vector<Mover> movers;
  Random rng{31};
  bool has_hulls = false;
};

/// Builds the scene; without hulls when `hulls` is false (random hulls become spheres).
void build(Saved& s, bool hulls = true) {
  s.movers = populate(s.world, s.rng, 80, kExtent);
  s.has_hulls = hulls;
  if (!hulls) {
    for (const Mover& m : s.movers)
      if (std::holds_alternative<ConvexHull>(s.world.object(m.handle)->geometry)) {
        ASSERT_FALSE(s.world.set_geometry(m.handle, *Sphere::create(Real(0.5))).has_value());
      }
  }
  ObjectDesc zone;
  zone.geometry = *Box::create(Vec3(2));
  zone.sensor = true;
  zone.kind = ObjectKind::Static;
  s.world.add(zone).value();
  ObjectDesc arm;
  arm.geometry = *Capsule::create(Real(0.2), Real(0.5));
  arm.parent = s.movers[0].handle;
  arm.local_pose = Transform{Vec3(1, 0, 0), kIdentityQuat};
  s.world.add(arm).value();
  ASSERT_FALSE(s.world.set_pair_excluded(s.movers[1].handle, s.movers[2].handle, true).has_value());
  ASSERT_FALSE(s.world.remove(s.movers[3].handle).has_value());
  s.movers.erase(s.movers.begin() + 3);
  for (int f = 0; f < 8; ++f) {
    advance(s.world, s.movers, kExtent);
    ASSERT_FALSE(s.world.step(Real(1) / Real(60)).has_value());
    for (const WorldManifold& m : s.world.contacts()) s.world.contact(m.pair.a, m.pair.b)->points[0].user[0] = Real(f);
  }
  advance(s.world, s.movers, kExtent);  // moved but not stepped: the next motion is saved too
}

std::string save(const CollisionWorld& world) {
  std::ostringstream out;
  EXPECT_FALSE(world.save(out).has_value());
  return out.str();
}

void check_round_trip(bool hulls) {
  Saved s;
  build(s, hulls);
  const std::string bytes = save(s.world);
  std::istringstream in(bytes);
  auto loaded = CollisionWorld::load(in);
  ASSERT_TRUE(loaded.ok()) << loaded.error().what();
  CollisionWorld copy = std::move(loaded).value();
  EXPECT_EQ(copy.state_hash(), s.world.state_hash());
  EXPECT_EQ(copy.size(), s.world.size());
  std::vector<Mover> copy_movers = s.movers;
  for (int f = 0; f < 12; ++f) {
    ASSERT_FALSE(s.world.step(Real(1) / Real(60)).has_value());
    ASSERT_FALSE(copy.step(Real(1) / Real(60)).has_value());
    // Hulls are rebuilt by qhull, which may number their vertices and faces differently:
    // contact points on hulls may then differ in feature ids and rounding, not in events.
    if (!s.has_hulls) {
      EXPECT_EQ(copy.state_hash(), s.world.state_hash()) << "step " << f;
    }
    EXPECT_EQ(copy.events().begin, s.world.events().begin);
    EXPECT_EQ(copy.events().persist, s.world.events().persist);
    EXPECT_EQ(copy.events().end, s.world.events().end);
    EXPECT_EQ(copy.events().sensor_enter, s.world.events().sensor_enter);
    advance(s.world, s.movers, kExtent);
    advance(copy, copy_movers, kExtent);
  }
}

TEST(WorldSnapshot, ALoadedWorldContinuesWithTheSameEvents) { check_round_trip(true); }

TEST(WorldSnapshot, ALoadedWorldWithoutHullsContinuesWithTheSameStateHashes) { check_round_trip(false); }

TEST(WorldSnapshot, DamagedSnapshotsAreRejectedOrLoadValidWorlds) {
  Saved s;
  build(s);
  const std::string bytes = save(s.world);
  for (std::size_t n = 0; n < bytes.size(); n += 1 + n / 16) {
    std::istringstream in(bytes.substr(0, n));
    auto r = CollisionWorld::load(in);
    ASSERT_FALSE(r.ok()) << "truncated to " << n << " bytes";
    EXPECT_EQ(r.error().field.rfind("snapshot", 0), 0u) << r.error().field;
  }
  std::string wrong = bytes;
  wrong[0] = 'X';
  std::istringstream bad_magic(wrong);
  EXPECT_EQ(CollisionWorld::load(bad_magic).error().field, "snapshot");
  wrong = bytes;
  wrong[8] = 7;
  std::istringstream bad_version(wrong);
  EXPECT_NE(CollisionWorld::load(bad_version).error().message.find("version"), std::string::npos);
  Random rng(32);
  ScopedNoFpTraps no_traps;  // flipped bits may make NaN: they must be rejected, not trapped
  for (int k = 0; k < sweep_size(300); ++k) {
    std::string flipped = bytes;
    for (int j = 0; j < 3; ++j) {
      const std::size_t at = std::size_t(rng.integer(9, int(flipped.size()) - 1));
      flipped[at] = static_cast<char>(flipped[at] ^ (1 << rng.integer(0, 7)));
    }
    std::istringstream in(flipped);
    auto r = CollisionWorld::load(in);
    if (!r.ok()) continue;
    CollisionWorld w = std::move(r).value();
    EXPECT_FALSE(w.step(Real(1) / Real(60)).has_value());  // a loaded world runs
  }
}

}  // namespace test_world_snapshot
}  // namespace proxima::test
