// Tests of the demo's billiard break on the collision world: invariants checked by brute
// force at every frame (no two balls overlap, every ball stays on the table, kinetic energy
// never grows), the world's events against its contacts and the listener's callbacks,
// every broad-phase structure against the others (identical runs), determinism, tunnelling
// of very fast balls, and the exact event-driven reference (exact_billiards.hpp).
#include <gtest/gtest.h>

#include <proxima/core/tolerance.hpp>

#include <cmath>
#include <sstream>

#include "billiard_table.hpp"
#include "demo_billiards.hpp"
#include "exact_billiards.hpp"

namespace proxima {
namespace test_billiards {

using tool::BilliardTable;

// Brute-force checks of one frame's end state. Overlaps pushed apart at a step's end leave
// at most the rounding of the time of impact (its tolerance, 1e-5 m, and the contact
// distance's margin), so balls may be closer than 2r by that much.
void expect_valid_state(const BilliardTable& table, int frame) {
  const BilliardConfig& c = table.config();
  const double r = double(c.ball_radius);
  const double slack = 2e-5 + 1e3 * double(kEpsilon) * double(c.table_length);
  const auto& p = table.positions();
  for (int i = 0; i < BilliardTable::kBallCount; ++i) {
    EXPECT_LE(std::abs(double(p[i].x)), 0.5 * double(c.table_length) - r + slack) << "ball " << i << " frame " << frame;
    EXPECT_LE(std::abs(double(p[i].y)), 0.5 * double(c.table_width) - r + slack) << "ball " << i << " frame " << frame;
    EXPECT_EQ(double(p[i].z), r);
    EXPECT_EQ(table.world().pose(table.world().objects()[4 + std::size_t(i)]).position, p[i]) << "ball " << i;
    for (int j = i + 1; j < BilliardTable::kBallCount; ++j) {
      const double dx = double(p[i].x) - double(p[j].x);
      const double dy = double(p[i].y) - double(p[j].y);
      EXPECT_GE(std::sqrt(dx * dx + dy * dy), 2 * r - slack) << "balls " << i << ", " << j << " frame " << frame;
    }
  }
}

// The listener's begin / end callbacks leave exactly the world's touching pairs.
void expect_callbacks_match_contacts(const BilliardTable& table) {
  std::vector<ObjectPair> contacts;
  for (const WorldManifold& m : table.world().contacts()) contacts.push_back(m.pair);
  const std::vector<ObjectPair> heard = table.touching_from_callbacks();
  ASSERT_EQ(heard.size(), contacts.size());
  for (std::size_t k = 0; k < heard.size(); ++k) {
    EXPECT_EQ(heard[k].a, contacts[k].a);
    EXPECT_EQ(heard[k].b, contacts[k].b);
  }
}

TEST(Billiards, BreakKeepsBallsApartOnTheTableAndLosesEnergy) {
  for (std::uint64_t seed : {0ull, 1ull, 2ull, 3ull, 42ull}) {
    BilliardConfig config;
    config.seed = seed;
    BilliardTable table(config);
    double energy = table.kinetic_energy();
    for (int f = 0; f < config.frames; ++f) {
      table.step();
      expect_valid_state(table, f);
      expect_callbacks_match_contacts(table);
      const double e = table.kinetic_energy();
      EXPECT_LE(e, energy * (1 + 1e3 * double(kEpsilon)) + 1e-12) << "seed " << seed << " frame " << f;
      energy = e;
      if (::testing::Test::HasFailure()) return;
    }
    const auto& s = table.stats();
    EXPECT_EQ(s.frames, 600u);
    EXPECT_EQ(s.steps, 2400u);
    EXPECT_GT(s.ball_collisions, 20u) << "seed " << seed;  // the rack is broken up
    EXPECT_GT(s.cushion_collisions, 10u) << "seed " << seed;
    EXPECT_GT(s.impacts, 0u);
    EXPECT_GE(s.begin_events, 20u);  // the racked balls touch (0.2 mm apart) at the first step
    EXPECT_EQ(s.begin_events, s.end_events + table.world().contacts().size());
    EXPECT_EQ(s.callbacks, s.begin_events + s.persist_events + s.end_events + s.impacts);
    EXPECT_EQ(s.capped_steps, 0u);
    EXPECT_EQ(table.contacts().size(), s.ball_collisions + s.cushion_collisions);
    std::vector<bool> hit(BilliardTable::kBallCount, false);
    for (const auto& contact : table.contacts()) {
      hit[contact.ball] = true;
      if (contact.other >= 0) hit[contact.other] = true;
    }
    for (int b = 0; b < BilliardTable::kBallCount; ++b) EXPECT_TRUE(hit[b]) << "ball " << b << " seed " << seed;
  }
}

// Every broad-phase structure may only drop pairs that cannot collide: the runs must be
// bit-identical to the brute-force one.
TEST(Billiards, EveryBroadPhaseGivesTheSameRun) {
  for (std::uint64_t seed : {0ull, 5ull}) {
    BilliardConfig brute;
    brute.seed = seed;
    brute.frames = 240;
    brute.broadphase = "brute";
    BilliardTable reference(brute);
    for (int f = 0; f < brute.frames; ++f) reference.step();
    for (const char* name : {"tree", "sap", "grid", "mbp"}) {
      BilliardConfig config = brute;
      config.broadphase = name;
      BilliardTable table(config);
      for (int f = 0; f < config.frames; ++f) table.step();
      ASSERT_EQ(table.contacts().size(), reference.contacts().size()) << name << " seed " << seed;
      for (std::size_t k = 0; k < table.contacts().size(); ++k) {
        EXPECT_EQ(table.contacts()[k].ball, reference.contacts()[k].ball) << name;
        EXPECT_EQ(table.contacts()[k].other, reference.contacts()[k].other) << name;
        EXPECT_EQ(table.contacts()[k].frame, reference.contacts()[k].frame) << name;
      }
      EXPECT_EQ(table.positions(), reference.positions()) << name;
      EXPECT_EQ(table.velocities(), reference.velocities()) << name;
      EXPECT_EQ(table.stats().begin_events, reference.stats().begin_events) << name;
    }
  }
}

TEST(Billiards, Deterministic) {
  BilliardConfig config;
  BilliardTable a(config);
  BilliardTable b(config);
  for (int f = 0; f < 200; ++f) {
    a.step();
    b.step();
  }
  EXPECT_EQ(a.positions(), b.positions());
  EXPECT_EQ(a.world().state_hash(), b.world().state_hash());
  EXPECT_EQ(tool::render_billiards_svg(a), tool::render_billiards_svg(b));
}

// Park every ball but `moving` along the top cushion, spaced, at rest.
template <class Table>
void park_balls(Table& table) {
  for (int b = 0; b < BilliardTable::kBallCount; ++b) {
    table.place_ball(b, Vec3(Real(-1.1) + Real(0.14) * Real(b), Real(0.55), 0), Vec3(0));
  }
}

// A ball 20 times faster than a break shot (3.3 m per frame, 58 diameters) still hits a
// ball in its way, which meets the cushion behind it; none passes through.
TEST(Billiards, FastBallsDoNotTunnel) {
  BilliardConfig config;
  config.rolling_deceleration = 0;
  BilliardTable table(config);
  park_balls(table);
  table.place_ball(0, Vec3(Real(-1.0), Real(-0.3), 0), Vec3(Real(200), 0, 0));
  table.place_ball(1, Vec3(Real(-0.5), Real(-0.3), 0), Vec3(0));
  table.step();
  expect_valid_state(table, 0);
  ASSERT_GE(table.contacts().size(), 2u);
  EXPECT_EQ(table.contacts()[0].ball, 0);
  EXPECT_EQ(table.contacts()[0].other, 1);
  EXPECT_TRUE(table.contacts()[0].continuous);
  // The struck ball crosses the rest of the table and meets the right cushion (cushion 1).
  EXPECT_EQ(table.contacts()[1].ball, 1);
  EXPECT_EQ(table.contacts()[1].other, -2);
  for (int f = 0; f < 120; ++f) {
    table.step();
    expect_valid_state(table, f + 1);
  }
  EXPECT_GT(table.stats().cushion_collisions, 10u);
}

// Two balls racing head-on at 300 m/s each: one impact at the meeting point (the balls stop
// at the contact distance, 0.5 mm, symmetric about it), as in the exact reference.
TEST(Billiards, HeadOnImpactAtTheMeetingPoint) {
  BilliardConfig config;
  config.rolling_deceleration = 0;
  config.ball_restitution = 1;
  BilliardTable table(config);
  park_balls(table);
  table.place_ball(2, Vec3(Real(-1), Real(-0.2), 0), Vec3(Real(300), 0, 0));
  table.place_ball(3, Vec3(Real(1), Real(-0.2), 0), Vec3(Real(-300), 0, 0));
  table.step();
  ASSERT_FALSE(table.contacts().empty());
  const auto& first = table.contacts().front();
  EXPECT_EQ(first.ball, 2);
  EXPECT_EQ(first.other, 3);
  // The balls meet at the contact distance, at the time-of-impact tolerance (1e-5 m).
  EXPECT_NEAR(double(first.point.x), 0.0, 2e-5);
  EXPECT_NEAR(double(first.point.y), -0.2, 2e-5);
  EXPECT_TRUE(first.continuous);
  expect_valid_state(table, 0);

  // The exact reference meets at the exact point.
  ExactBilliards exact(config);
  park_balls(exact);
  exact.place_ball(2, Vec3(Real(-1), Real(-0.2), 0), Vec3(Real(300), 0, 0));
  exact.place_ball(3, Vec3(Real(1), Real(-0.2), 0), Vec3(Real(-300), 0, 0));
  exact.step();
  ASSERT_FALSE(exact.contacts().empty());
  EXPECT_EQ(exact.contacts().front().ball, 2);
  EXPECT_EQ(exact.contacts().front().other, 3);
  EXPECT_NEAR(double(exact.contacts().front().point.x), 0.0, 1e3 * double(kEpsilon));
  EXPECT_NEAR(double(exact.contacts().front().point.y), -0.2, 1e3 * double(kEpsilon));
}

// Against the exact event-driven reference: one ball bouncing between two cushions for ten
// seconds (no time is lost at an impact), and the break's first impact.
TEST(Billiards, AgreesWithTheExactReference) {
  BilliardConfig config;
  config.rolling_deceleration = 0;
  config.cushion_restitution = 1;
  config.contact_distance = 0;  // impacts at touching, as in the reference
  BilliardTable table(config);
  ExactBilliards exact(config);
  park_balls(table);
  park_balls(exact);
  const Vec3 start(Real(-0.3), Real(-0.2), 0);
  const Vec3 velocity(Real(7.1), Real(0), 0);
  table.place_ball(5, start, velocity);
  exact.place_ball(5, start, velocity);
  for (int f = 0; f < 600; ++f) {
    table.step();
    exact.step();
  }
  EXPECT_GT(exact.contacts().size(), 20u);
  ASSERT_EQ(table.contacts().size(), exact.contacts().size());
  for (std::size_t k = 0; k < exact.contacts().size(); ++k) {
    EXPECT_EQ(table.contacts()[k].other, exact.contacts()[k].other) << k;
    EXPECT_EQ(table.contacts()[k].frame, exact.contacts()[k].frame) << k;
  }
  // Each bounce within the time of impact's tolerance (1e-5 m).
  EXPECT_LT(glm::length(table.positions()[5] - exact.positions()[5]), Real(1e-3));
  EXPECT_LT(glm::length(table.velocities()[5] - exact.velocities()[5]), Real(1e-3));

  BilliardConfig rack;
  BilliardTable world_break(rack);
  ExactBilliards exact_break(rack);
  while (exact_break.contacts().empty()) {
    world_break.step();
    exact_break.step();
  }
  world_break.step();
  ASSERT_FALSE(world_break.contacts().empty());
  const BilliardContact& w = world_break.contacts().front();
  const BilliardContact& e = exact_break.contacts().front();
  EXPECT_EQ(w.ball, e.ball);
  EXPECT_EQ(w.other, e.other);
  EXPECT_EQ(w.frame, e.frame);
  EXPECT_LT(glm::length(w.point - e.point), Real(1e-3));
}

TEST(Billiards, DemoPrintsStatistics) {
  tool::DemoOptions options;
  options.svg_path.clear();
  options.config.frames = 60;
  std::ostringstream out, err;
  EXPECT_EQ(tool::run_billiards_demo(options, out, err), 0);
  EXPECT_EQ(err.str(), "");
  EXPECT_NE(out.str().find("collision world: 20 objects"), std::string::npos) << out.str();
  EXPECT_NE(out.str().find("240 steps (4 per frame)"), std::string::npos) << out.str();
  options.quiet = true;
  std::ostringstream quiet;
  EXPECT_EQ(tool::run_billiards_demo(options, quiet, err), 0);
  EXPECT_EQ(quiet.str(), "");
  options.config.broadphase = "no-such-structure";
  std::ostringstream bad_out, bad_err;
  EXPECT_EQ(tool::run_billiards_demo(options, bad_out, bad_err), 2);
  EXPECT_NE(bad_err.str().find("unknown broad-phase structure 'no-such-structure'"), std::string::npos)
      << bad_err.str();
}

}  // namespace test_billiards
}  // namespace proxima
