/// @file test_d2_world_snapshot.cpp
/// The 2D world's snapshots and pair exclusions.
///
///   1. A randomised scene of every shape kind (chains from a sprite outline too), sensors,
///      statics, continuous modes, exclusions, removed and moved-but-not-stepped objects is
///      saved, loaded and stepped beside the original under the same calls: every step's
///      events, impacts and manifolds are bit-identical, the state hashes equal, and the
///      loaded world saves the same bytes (the snapshot is canonical).
///   2. Every truncation of a small world's snapshot and random byte flips are rejected with
///      an error naming the snapshot, or load a world that steps; named corruptions name
///      their field ("snapshot.objects[1].shape", "snapshot.objects[1].kind").
///   3. Polygon::restore keeps a polygon's vertex order and refuses clockwise, star-shaped,
///      collinear and non-finite vertices;
///   4. Exclusions against analytic answers: two overlapping circles begin, end when
///      excluded, begin again when allowed; bad calls name "a" / "b" and change nothing.

#include <gtest/gtest.h>

#include <proxima/d2/collision_world.hpp>
#include <proxima/d2/sprite_chains.hpp>

#include <cmath>
#include <limits>
#include <sstream>
#include <string>
#include <support/random.hpp>
#include <vector>

#include "sweep_size.hpp"

namespace proxima::d2 {
namespace test_d2_world_snapshot {

using proxima::test::Random;
using proxima::test::sweep_size;

/// A world and the moving objects the scene drives.
struct Scene {
  CollisionWorld world;
  std::vector<ObjectHandle> movers;
};

Shape random_convex(Random& rng) {
  const Real size = rng.uniform(Real(0.3), Real(1));
  const Vec2 offset{rng.uniform(Real(-0.2), Real(0.2)), rng.uniform(Real(-0.2), Real(0.2))};
  switch (rng.integer(0, 5)) {
    case 0: return Point::create(offset).value();
    case 1: return Circle::create(size, offset).value();
    case 2: return Segment::create(-offset - Vec2(size, 0), offset + Vec2(size, 0)).value();
    case 3: return Capsule::create({-size, 0}, {size, Real(0.1)}, Real(0.3) * size).value();
    case 4: return Polygon::box(size, Real(0.6) * size, offset, rng.uniform(Real(-3), Real(3))).value();
    default: {
      std::vector<Vec2> points;
      for (int k = 0; k < 7; ++k) points.push_back({rng.uniform(-size, size), rng.uniform(-size, size)});
      auto p = Polygon::create(points, rng.integer(0, 1) == 0 ? Real(0) : Real(0.05));
      return p.ok() ? Shape(p.value()) : Shape(Circle::create(size).value());
    }
  }
}

/// Static level geometry: an open floor, a closed loop, and a sprite's outline chains.
void add_level(Scene& s) {
  const std::vector<Vec2> floor = {{Real(20), Real(0)}, {Real(10), Real(1)}, {Real(0), Real(0)}, {Real(-20), Real(2)}};
  const std::vector<Vec2> loop = {{Real(0), Real(0)}, {Real(2), Real(0)}, {Real(2), Real(2)}, {Real(0), Real(2)}};
  ObjectDesc d;
  d.kind = ObjectKind::Static;
  d.shape = Chain::create(floor, false).value();
  s.world.add(d).value();
  d.shape = Chain::create(loop, true).value();
  d.pose = Pose::from({Real(6), Real(5)}, Real(0.3));
  s.world.add(d).value();
  const std::vector<std::string> rows = {"0110", "1111", "1001", "1111"};
  const std::vector<Chain> outline = sprite_chains(SpriteMask::from_rows(rows).value(), 0.0, Real(0.5)).value();
  ASSERT_FALSE(outline.empty());
  for (const Chain& c : outline) {
    d.shape = c;
    d.pose = Pose::from({Real(-8), Real(4)}, Real(0));
    s.world.add(d).value();
  }
}

Scene random_scene(std::uint64_t seed, int count, const WorldSettings& settings = {}) {
  Random rng(seed);
  Scene s{CollisionWorld::create(settings).value(), {}};
  add_level(s);
  for (int i = 0; i < count; ++i) {
    ObjectDesc d;
    d.shape = random_convex(rng);
    d.pose =
        Pose::from({rng.uniform(Real(-12), Real(12)), rng.uniform(Real(-1), Real(8))}, rng.uniform(Real(-3), Real(3)));
    d.kind = rng.integer(0, 5) == 0 ? ObjectKind::Static : ObjectKind::Moving;
    d.filter.layer = 1ull << rng.integer(0, 2);
    d.filter.mask = rng.integer(0, 4) == 0 ? ~(1ull << rng.integer(0, 2)) : ~0ull;
    d.sensor = rng.integer(0, 9) == 0;
    d.ccd = static_cast<CcdMode>(rng.integer(0, 2));
    d.user_data = static_cast<std::uint64_t>(i) * 7 + 1;
    const ObjectHandle h = s.world.add(d).value();
    if (d.kind == ObjectKind::Moving) s.movers.push_back(h);
  }
  return s;
}

/// The calls of frame `frame`, the same for every world given the same seed: each mover
/// drifts (now and then a fast jump that continuous detection sweeps, or a teleport).
void drive(CollisionWorld& world, const std::vector<ObjectHandle>& movers, std::uint64_t seed, int frame) {
  Random rng(seed * 1000003u + static_cast<std::uint64_t>(frame));
  for (ObjectHandle h : movers) {
    if (!world.contains(h)) continue;
    const Pose p = world.pose(h).value();
    Vec2 step{rng.uniform(Real(-0.3), Real(0.3)), rng.uniform(Real(-0.3), Real(0.3))};
    const int what = rng.integer(0, 19);
    if (what == 0) step *= Real(20);
    Vec2 to = p.position + step;
    if (std::abs(to.x) > Real(14) || to.y < Real(-2) || to.y > Real(10)) to = {Real(0), Real(4)};
    const Pose next = Pose::from(to, p.rotation.angle() + rng.uniform(Real(-0.2), Real(0.2)));
    const auto e = what == 1 ? world.teleport(h, next) : world.move(h, next);
    ASSERT_FALSE(e.has_value());
  }
}

std::string bytes_of(const CollisionWorld& world) {
  std::ostringstream out(std::ios::binary);
  EXPECT_FALSE(world.save(out).has_value());
  return out.str();
}

CollisionWorld loaded(const std::string& bytes) {
  std::istringstream in(bytes, std::ios::binary);
  auto r = CollisionWorld::load(in);
  EXPECT_TRUE(r.ok()) << r.error().what();
  return std::move(r).value();
}

bool same_point(const ContactPoint& x, const ContactPoint& y) {
  return x.point_a == y.point_a && x.point_b == y.point_b && x.depth == y.depth && x.feature_id == y.feature_id;
}

/// Bit-identical manifolds (== on reals: equal values; NaN never occurs).
void expect_same_manifolds(std::span<const WorldManifold> a, std::span<const WorldManifold> b, int frame) {
  ASSERT_EQ(a.size(), b.size()) << "frame " << frame;
  for (std::size_t k = 0; k < a.size(); ++k) {
    const Manifold& x = a[k].manifold;
    const Manifold& y = b[k].manifold;
    EXPECT_EQ(a[k].pair, b[k].pair);
    EXPECT_TRUE(x.count == y.count && x.normal == y.normal && x.method == y.method && x.part_a == y.part_a &&
                x.part_b == y.part_b)
        << "frame " << frame << " manifold " << k;
    for (int i = 0; i < std::min(x.count, y.count); ++i) {
      EXPECT_TRUE(same_point(x.points[std::size_t(i)], y.points[std::size_t(i)])) << "frame " << frame;
    }
  }
}

void expect_same_events(const StepEvents& a, const StepEvents& b, int frame) {
  EXPECT_EQ(a.begin, b.begin) << "frame " << frame;
  EXPECT_EQ(a.persist, b.persist) << "frame " << frame;
  EXPECT_EQ(a.end, b.end) << "frame " << frame;
  EXPECT_EQ(a.sensor_enter, b.sensor_enter) << "frame " << frame;
  EXPECT_EQ(a.sensor_exit, b.sensor_exit) << "frame " << frame;
  ASSERT_EQ(a.impacts.size(), b.impacts.size()) << "frame " << frame;
  for (std::size_t k = 0; k < a.impacts.size(); ++k) {
    const ImpactEvent& x = a.impacts[k];
    const ImpactEvent& y = b.impacts[k];
    EXPECT_TRUE(x.a == y.a && x.b == y.b && x.toi == y.toi && x.point == y.point && x.normal == y.normal &&
                x.part_b == y.part_b && x.user_data_a == y.user_data_a && x.user_data_b == y.user_data_b)
        << "frame " << frame << " impact " << k;
  }
}

/// Runs a scene, saving and reloading it every `period` frames into a copy stepped beside it.
void check_round_trips(std::uint64_t seed, const std::string& broadphase) {
  WorldSettings settings;
  settings.broadphase = broadphase;
  settings.contact_distance = Real(0.02);
  Scene s = random_scene(seed, 60, settings);
  ASSERT_FALSE(s.world.set_pair_excluded(s.movers[0], s.movers[1], true).has_value());
  ASSERT_FALSE(s.world.set_pair_excluded(s.movers[2], s.movers[5], true).has_value());
  for (int frame = 0; frame < 5; ++frame) {
    drive(s.world, s.movers, seed, frame);
    ASSERT_FALSE(s.world.step().has_value());
  }
  ASSERT_FALSE(s.world.remove(s.movers[3]).has_value());  // a touching pair that ends at the next step
  drive(s.world, s.movers, seed, 5);                      // moved, not stepped: the next motion is saved
  CollisionWorld copy = loaded(bytes_of(s.world));
  EXPECT_EQ(copy.state_hash(), s.world.state_hash());
  EXPECT_EQ(bytes_of(copy), bytes_of(s.world));
  std::size_t impacts = 0, begins = 0;
  for (int frame = 6; frame < 6 + sweep_size(60); ++frame) {
    ASSERT_FALSE(s.world.step().has_value());
    ASSERT_FALSE(copy.step().has_value());
    expect_same_events(s.world.events(), copy.events(), frame);
    expect_same_manifolds(s.world.manifolds(), copy.manifolds(), frame);
    ASSERT_EQ(s.world.state_hash(), copy.state_hash()) << "frame " << frame;
    impacts += s.world.events().impacts.size();
    begins += s.world.events().begin.size();
    if (frame % 7 == 0) copy = loaded(bytes_of(copy));
    drive(s.world, s.movers, seed, frame);
    drive(copy, s.movers, seed, frame);
  }
  EXPECT_GT(begins, 0u);
  EXPECT_GT(impacts, 0u) << "the scene should exercise continuous detection";
}

TEST(D2WorldSnapshot, LoadedWorldsStepLikeTheOriginal) {
  for (std::uint64_t seed : {1u, 2u, 3u}) check_round_trips(seed, "tree");
}

TEST(D2WorldSnapshot, LoadedWorldsStepLikeTheOriginalOnOtherBroadPhases) {
  check_round_trips(4, "sap");
  check_round_trips(5, "grid");
}

TEST(D2WorldSnapshot, StateHashesSeeEveryChange) {
  Scene s = random_scene(7, 10);
  const std::uint64_t h0 = s.world.state_hash();
  EXPECT_EQ(loaded(bytes_of(s.world)).state_hash(), h0);
  ASSERT_FALSE(s.world.move(s.movers[0], Pose::from({Real(1), Real(1)}, Real(0))).has_value());
  const std::uint64_t h1 = s.world.state_hash();
  EXPECT_NE(h1, h0);
  ASSERT_FALSE(s.world.set_filter(s.movers[1], CollisionFilter{2, 3, 0}).has_value());
  EXPECT_NE(s.world.state_hash(), h1);
}

/// A small world: a circle resting on a box (so there is a touching pair and its manifold).
CollisionWorld small_world() {
  CollisionWorld w = CollisionWorld::create().value();
  ObjectDesc ground;
  ground.shape = Polygon::box(Real(2), Real(0.5)).value();
  ground.kind = ObjectKind::Static;
  w.add(ground).value();
  ObjectDesc ball;
  ball.shape = Circle::create(Real(0.5)).value();
  ball.pose = Pose::from({Real(0), Real(0.9)}, Real(0));
  ball.user_data = 9;
  w.add(ball).value();
  EXPECT_FALSE(w.step().has_value());
  EXPECT_EQ(w.events().begin.size(), 1u);
  return w;
}

TEST(D2WorldSnapshot, EveryTruncationIsRejected) {
  const std::string bytes = bytes_of(small_world());
  for (std::size_t n = 0; n < bytes.size(); ++n) {
    std::istringstream in(bytes.substr(0, n), std::ios::binary);
    auto r = CollisionWorld::load(in);
    ASSERT_FALSE(r.ok()) << "truncated to " << n << " bytes";
    EXPECT_EQ(r.error().field.rfind("snapshot", 0), 0u) << r.error().field;
  }
  std::istringstream whole(bytes, std::ios::binary);
  EXPECT_TRUE(CollisionWorld::load(whole).ok());
}

TEST(D2WorldSnapshot, FlippedBytesAreRejectedOrLoadWorldsThatStep) {
  Scene s = random_scene(11, 12);
  ASSERT_FALSE(s.world.step().has_value());
  const std::string bytes = bytes_of(s.world);
  Random rng(12);
  proxima::test::ScopedNoFpTraps no_traps;  // flipped bits may make NaN: rejected, not trapped
  int rejected = 0;
  for (int k = 0; k < sweep_size(2000); ++k) {
    std::string flipped = bytes;
    for (int j = rng.integer(1, 3); j > 0; --j) {
      const std::size_t at = std::size_t(rng.integer(0, int(flipped.size()) - 1));
      flipped[at] = static_cast<char>(flipped[at] ^ (1 << rng.integer(0, 7)));
    }
    std::istringstream in(flipped, std::ios::binary);
    auto r = CollisionWorld::load(in);
    if (!r.ok()) {
      EXPECT_EQ(r.error().field.rfind("snapshot", 0), 0u) << r.error().field;
      ++rejected;
      continue;
    }
    CollisionWorld w = std::move(r).value();
    EXPECT_FALSE(w.step().has_value());  // a loaded world runs
    EXPECT_EQ(loaded(bytes_of(w)).state_hash(), w.state_hash());
  }
  EXPECT_GT(rejected, 0);
}

/// The index of the last byte where two snapshots differ.
std::size_t last_difference(const std::string& a, const std::string& b) {
  std::size_t at = 0;
  for (std::size_t k = 0; k < std::min(a.size(), b.size()); ++k)
    if (a[k] != b[k]) at = k;
  return at;
}

std::string snapshot_with_ball(Real radius, ObjectKind kind) {
  CollisionWorld w = CollisionWorld::create().value();
  w.add(ObjectDesc{}).value();
  ObjectDesc d;
  d.shape = Circle::create(radius).value();
  d.kind = kind;
  w.add(d).value();
  return bytes_of(w);
}

Error load_error(const std::string& bytes) {
  std::istringstream in(bytes, std::ios::binary);
  auto r = CollisionWorld::load(in);
  EXPECT_FALSE(r.ok());
  return r.ok() ? Error{} : r.error();
}

TEST(D2WorldSnapshot, CorruptedFieldsAreNamed) {
  const std::string one = snapshot_with_ball(Real(1), ObjectKind::Moving);
  // The radius's sign byte (1 and 3 differ in their last two bytes): -3 does not validate.
  std::string bad = snapshot_with_ball(Real(3), ObjectKind::Moving);
  bad[last_difference(one, bad)] = static_cast<char>(bad[last_difference(one, bad)] | 0x80);
  EXPECT_EQ(load_error(bad).field, "snapshot.objects[1].shape");
  // The kind byte (Static and Moving differ there only): 7 is no kind.
  bad = snapshot_with_ball(Real(1), ObjectKind::Static);
  ASSERT_EQ(bad.size(), one.size());
  bad[last_difference(one, bad)] = 7;
  EXPECT_EQ(load_error(bad).field, "snapshot.objects[1].kind");
  bad = one;
  bad[0] = 'X';
  EXPECT_EQ(load_error(bad).field, "snapshot");
  bad = one;
  bad[8] = 2;
  EXPECT_NE(load_error(bad).message.find("version"), std::string::npos);
  std::ostringstream three_d;  // another kind of snapshot (the 3D world's magic)
  three_d << "PROXWRLD" << std::string(40, '\0');
  EXPECT_EQ(load_error(three_d.str()).field, "snapshot");
}

TEST(D2WorldExclusions, ExcludedPairsEndAndBeginAgainWhenAllowed) {
  CollisionWorld w = CollisionWorld::create().value();
  ObjectDesc d;
  d.shape = Circle::create(Real(1)).value();
  const ObjectHandle a = w.add(d).value();
  d.pose = Pose::from({Real(1.5), Real(0)}, Real(0));  // 0.5 overlap
  const ObjectHandle b = w.add(d).value();
  ASSERT_FALSE(w.step().has_value());
  ASSERT_EQ(w.events().begin.size(), 1u);
  ASSERT_FALSE(w.set_pair_excluded(b, a, true).has_value());
  ASSERT_FALSE(w.set_pair_excluded(a, b, true).has_value());  // idempotent
  ASSERT_FALSE(w.step().has_value());
  ASSERT_EQ(w.events().end.size(), 1u);
  EXPECT_EQ(w.events().end[0].pair, (ObjectPair{a, b}));
  EXPECT_TRUE(w.manifolds().empty());
  CollisionWorld copy = loaded(bytes_of(w));  // the exclusion is in the snapshot
  ASSERT_FALSE(copy.step().has_value());
  EXPECT_TRUE(copy.events().begin.empty());
  ASSERT_FALSE(w.set_pair_excluded(a, b, false).has_value());
  ASSERT_FALSE(w.step().has_value());
  EXPECT_EQ(w.events().begin.size(), 1u);
}

TEST(D2WorldExclusions, RemovingAnObjectForgetsItsExclusions) {
  CollisionWorld w = CollisionWorld::create().value();
  ObjectDesc d;
  const ObjectHandle a = w.add(d).value();
  const ObjectHandle b = w.add(d).value();
  ASSERT_FALSE(w.set_pair_excluded(a, b, true).has_value());
  ASSERT_FALSE(w.remove(b).has_value());
  const ObjectHandle c = w.add(d).value();  // reuses b's slot
  ASSERT_EQ(c.index, b.index);
  ASSERT_FALSE(w.step().has_value());
  EXPECT_EQ(w.events().begin.size(), 1u);
}

TEST(D2WorldExclusions, BadCallsNameTheirFieldAndChangeNothing) {
  CollisionWorld w = CollisionWorld::create().value();
  const ObjectHandle a = w.add(ObjectDesc{}).value();
  const ObjectHandle b = w.add(ObjectDesc{}).value();
  ASSERT_FALSE(w.remove(b).has_value());
  const std::uint64_t before = w.state_hash();
  EXPECT_EQ(w.set_pair_excluded(b, a, true)->field, "a");
  EXPECT_EQ(w.set_pair_excluded(a, b, true)->field, "b");
  EXPECT_EQ(w.set_pair_excluded(a, a, true)->field, "b");
  EXPECT_EQ(w.state_hash(), before);
}

TEST(D2PolygonRestore, KeepsTheVertexOrderAndRefusesWhatIsNotStrictlyConvex) {
  const Polygon box = Polygon::box(Real(1), Real(0.5), {Real(0.3), Real(0.1)}, Real(0.7), Real(0.05)).value();
  std::vector<Vec2> v;
  for (int i = 0; i < box.count(); ++i) v.push_back(box.vertex(i));
  const Polygon again = Polygon::restore(v, box.radius()).value();
  ASSERT_EQ(again.count(), box.count());
  for (int i = 0; i < box.count(); ++i) {
    EXPECT_EQ(again.vertex(i), box.vertex(i));
    EXPECT_EQ(again.normal(i), box.normal(i));
  }
  EXPECT_EQ(again.radius(), box.radius());
  const std::vector<Vec2> clockwise(v.rbegin(), v.rend());
  EXPECT_EQ(Polygon::restore(clockwise).error().field, "points");
  std::vector<Vec2> star;  // a pentagram: every turn is left, but it winds twice
  for (int k = 0; k < 5; ++k)
    star.push_back({std::cos(Real(k) * Real(4 * 3.14159265) / 5), std::sin(Real(k) * Real(4 * 3.14159265) / 5)});
  EXPECT_EQ(Polygon::restore(star).error().field, "points");
  const std::vector<Vec2> collinear = {{0, 0}, {1, 0}, {2, 0}, {1, 1}};
  EXPECT_EQ(Polygon::restore(collinear).error().field, "points");
  std::vector<Vec2> bad = v;
  bad[1].x = std::numeric_limits<Real>::quiet_NaN();
  EXPECT_EQ(Polygon::restore(bad).error().field, "points[1]");
  EXPECT_EQ(Polygon::restore(v, Real(-1)).error().field, "radius");
  EXPECT_EQ(Polygon::restore(std::vector<Vec2>(17, Vec2(0))).error().code, ErrorCode::OutOfRange);
}

}  // namespace test_d2_world_snapshot
}  // namespace proxima::d2
