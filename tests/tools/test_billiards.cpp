// Tests of the demo's simulation: invariants checked by brute force at every frame (no two
// balls overlap, every ball stays on the table, kinetic energy never grows), the broad phase
// against passing every pair on (bit-identical runs), determinism, and tunnelling of very
// fast balls.
#include <gtest/gtest.h>

#include <proxima/core/tolerance.hpp>

#include <cmath>
#include <sstream>

#include "billiard_table.hpp"
#include "demo_billiards.hpp"

namespace proxima {
namespace test_billiards {

using tool::BilliardConfig;
using tool::BilliardTable;

// Brute-force checks of one frame's end state.
void expect_valid_state(const BilliardTable& table, int frame) {
  const BilliardConfig& c = table.config();
  const double r = double(c.ball_radius);
  // Rounding of the event times lets touching balls overlap by a few ulps of the table size.
  const double slack = 1e3 * double(kEpsilon) * double(c.table_length);
  const auto& p = table.positions();
  for (int i = 0; i < BilliardTable::kBallCount; ++i) {
    EXPECT_LE(std::abs(double(p[i].x)), 0.5 * double(c.table_length) - r + slack) << "ball " << i << " frame " << frame;
    EXPECT_LE(std::abs(double(p[i].y)), 0.5 * double(c.table_width) - r + slack) << "ball " << i << " frame " << frame;
    EXPECT_EQ(double(p[i].z), r);
    for (int j = i + 1; j < BilliardTable::kBallCount; ++j) {
      const double dx = double(p[i].x) - double(p[j].x);
      const double dy = double(p[i].y) - double(p[j].y);
      EXPECT_GE(std::sqrt(dx * dx + dy * dy), 2 * r - slack) << "balls " << i << ", " << j << " frame " << frame;
    }
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
      const double e = table.kinetic_energy();
      EXPECT_LE(e, energy * (1 + 1e3 * double(kEpsilon)) + 1e-12) << "seed " << seed << " frame " << f;
      energy = e;
      if (::testing::Test::HasFailure()) return;
    }
    const auto& s = table.stats();
    EXPECT_EQ(s.frames, 600u);
    EXPECT_EQ(s.brute_ball_pairs, 600u * 120u);
    EXPECT_EQ(s.brute_cushion_pairs, 600u * 64u);
    EXPECT_GT(s.ball_collisions, 20u) << "seed " << seed;  // the rack is broken up
    EXPECT_GT(s.cushion_collisions, 10u) << "seed " << seed;
    EXPECT_LT(s.candidate_ball_pairs, s.brute_ball_pairs / 4);  // the sweep prunes most pairs
    EXPECT_EQ(s.capped_frames, 0u);
    EXPECT_EQ(table.contacts().size(), s.ball_collisions + s.cushion_collisions);
    // Every ball of the rack has been hit.
    std::vector<bool> hit(BilliardTable::kBallCount, false);
    for (const auto& contact : table.contacts()) {
      hit[contact.ball] = true;
      if (contact.other >= 0) hit[contact.other] = true;
    }
    for (int b = 0; b < BilliardTable::kBallCount; ++b) EXPECT_TRUE(hit[b]) << "ball " << b << " seed " << seed;
  }
}

// The sort-and-sweep may only drop pairs that cannot collide: the run with every pair passed
// on must be bit-identical.
TEST(Billiards, BroadPhaseGivesTheSameRunAsEveryPair) {
  for (std::uint64_t seed : {0ull, 1ull, 5ull}) {
    BilliardConfig swept;
    swept.seed = seed;
    BilliardConfig brute = swept;
    brute.brute_force_pairs = true;
    BilliardTable a(swept);
    BilliardTable b(brute);
    for (int f = 0; f < swept.frames; ++f) {
      a.step();
      b.step();
    }
    ASSERT_EQ(a.contacts().size(), b.contacts().size()) << "seed " << seed;
    for (std::size_t k = 0; k < a.contacts().size(); ++k) {
      EXPECT_EQ(a.contacts()[k].ball, b.contacts()[k].ball);
      EXPECT_EQ(a.contacts()[k].other, b.contacts()[k].other);
      EXPECT_EQ(a.contacts()[k].frame, b.contacts()[k].frame);
    }
    for (int i = 0; i < BilliardTable::kBallCount; ++i) {
      EXPECT_EQ(a.positions()[i], b.positions()[i]) << "ball " << i;
      EXPECT_EQ(a.velocities()[i], b.velocities()[i]) << "ball " << i;
    }
    EXPECT_EQ(b.stats().candidate_ball_pairs, b.stats().brute_ball_pairs);
    EXPECT_LT(a.stats().candidate_ball_pairs, b.stats().candidate_ball_pairs);
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
  EXPECT_EQ(tool::render_billiards_svg(a), tool::render_billiards_svg(b));
}

// A ball 20 times faster than a break shot (3.3 m per frame, 58 diameters) still hits a
// ball in its way, which meets the cushion behind it in the same frame; none passes through.
TEST(Billiards, FastBallsDoNotTunnel) {
  BilliardConfig config;
  config.rolling_deceleration = 0;
  BilliardTable table(config);
  // Park every ball along the top cushion, spaced, at rest.
  for (int b = 0; b < BilliardTable::kBallCount; ++b) {
    table.place_ball(b, Vec3(Real(-1.1) + Real(0.14) * Real(b), Real(0.55), 0), Vec3(0));
  }
  table.place_ball(0, Vec3(Real(-1.0), Real(-0.3), 0), Vec3(Real(200), 0, 0));
  table.place_ball(1, Vec3(Real(-0.5), Real(-0.3), 0), Vec3(0));
  table.step();
  expect_valid_state(table, 0);
  ASSERT_GE(table.contacts().size(), 1u);
  EXPECT_EQ(table.contacts()[0].ball, 0);
  EXPECT_EQ(table.contacts()[0].other, 1);
  // The struck ball crosses the rest of the table within the same frame and meets the
  // right cushion (cushion 1) next.
  ASSERT_GE(table.contacts().size(), 2u);
  EXPECT_EQ(table.contacts()[1].ball, 1);
  EXPECT_EQ(table.contacts()[1].other, -2);
  for (int f = 0; f < 120; ++f) {
    table.step();
    expect_valid_state(table, f + 1);
  }
  EXPECT_GT(table.stats().cushion_collisions, 10u);
}

// Two balls racing head-on at 300 m/s each: one impact at the exact meeting point.
TEST(Billiards, HeadOnImpactAtTheMeetingPoint) {
  BilliardConfig config;
  config.rolling_deceleration = 0;
  config.ball_restitution = 1;
  BilliardTable table(config);
  for (int b = 0; b < BilliardTable::kBallCount; ++b) {
    table.place_ball(b, Vec3(Real(-1.1) + Real(0.14) * Real(b), Real(0.55), 0), Vec3(0));
  }
  table.place_ball(2, Vec3(Real(-1), Real(-0.2), 0), Vec3(Real(300), 0, 0));
  table.place_ball(3, Vec3(Real(1), Real(-0.2), 0), Vec3(Real(-300), 0, 0));
  table.step();
  ASSERT_FALSE(table.contacts().empty());
  const auto& first = table.contacts().front();
  EXPECT_EQ(first.ball, 2);
  EXPECT_EQ(first.other, 3);
  EXPECT_NEAR(double(first.point.x), 0.0, 1e3 * double(kEpsilon));
  EXPECT_NEAR(double(first.point.y), -0.2, 1e3 * double(kEpsilon));
  expect_valid_state(table, 0);
}

TEST(Billiards, DemoPrintsStatistics) {
  tool::DemoOptions options;
  options.svg_path.clear();
  options.config.frames = 60;
  std::ostringstream out, err;
  EXPECT_EQ(tool::run_billiards_demo(options, out, err), 0);
  EXPECT_EQ(err.str(), "");
  EXPECT_NE(out.str().find("brute-force pair tests: 11040 (7200 ball-ball"), std::string::npos) << out.str();
  options.quiet = true;
  std::ostringstream quiet;
  EXPECT_EQ(tool::run_billiards_demo(options, quiet, err), 0);
  EXPECT_EQ(quiet.str(), "");
}

}  // namespace test_billiards
}  // namespace proxima
