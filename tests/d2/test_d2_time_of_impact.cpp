/// @file test_d2_time_of_impact.cpp
/// 2D time of impact and shape casts against a long-double reference that samples the
/// motion densely and bisects the first crossing of the exact signed distance
/// (d2_reference.hpp), plus analytic cases, chains and the t = 0 contract.

#include <gtest/gtest.h>

#include <proxima/d2/time_of_impact.hpp>

#include "d2/d2_reference.hpp"
#include "sweep_size.hpp"

namespace proxima::d2 {
namespace {

using test::LD;
using test::RefPose;

/// A motion by its defining numbers.
struct RefMotion {
  RefPose start;
  LD tx = 0, ty = 0, rotation = 0;
  RefPose at(LD t) const { return {start.x + t * tx, start.y + t * ty, start.angle + t * rotation}; }
  Motion motion() const { return {start.pose(), Vec2(Real(tx), Real(ty)), Real(rotation)}; }
};

/// The first t in [0, 1] where the exact signed distance reaches `target`, found on `samples`
/// steps and refined by bisection; -1 when no sample reaches it.
LD reference_toi(const test::RefShape& a, const RefMotion& ma, const test::RefShape& b, const RefMotion& mb, LD target,
                 int samples) {
  const auto f = [&](LD t) { return test::signed_distance(a, ma.at(t), b, mb.at(t)) - target; };
  if (f(0) <= 0) return 0;
  for (int i = 1; i <= samples; ++i) {
    const LD t = static_cast<LD>(i) / samples;
    if (f(t) > 0) continue;
    LD lo = static_cast<LD>(i - 1) / samples, hi = t;
    for (int k = 0; k < 60; ++k) {
      const LD mid = (lo + hi) / 2;
      (f(mid) > 0 ? lo : hi) = mid;
    }
    return hi;
  }
  return -1;
}

RefMotion random_motion(proxima::test::Random& rng, Real spread, Real speed, Real spin) {
  RefMotion m;
  m.start = {rng.uniform(-spread, spread), rng.uniform(-spread, spread), rng.uniform(Real(-3.2), Real(3.2))};
  m.tx = rng.uniform(-speed, speed);
  m.ty = rng.uniform(-speed, speed);
  m.rotation = rng.uniform(-spin, spin);
  return m;
}

TEST(D2TimeOfImpact, EveryConvexPairMatchesTheSampledReference) {
  proxima::test::Random rng(0xD2701);
  const Real tol = sizeof(Real) == 4 ? Real(1e-4) : Real(1e-7);
  const int per_pair = proxima::test::sweep_size(50);
  int hits = 0, compared = 0;
  for (ShapeType ta : test::kConvexKinds) {
    for (ShapeType tb : test::kConvexKinds) {
      for (int i = 0; i < per_pair; ++i) {
        const test::RandomShape a = test::random_shape(rng, ta, rng.uniform(Real(0.3), Real(1.5)));
        const test::RandomShape b = test::random_shape(rng, tb, rng.uniform(Real(0.3), Real(1.5)));
        const RefMotion ma = random_motion(rng, Real(4), Real(2), i % 2 == 0 ? Real(0) : Real(6));
        RefMotion mb = random_motion(rng, Real(4), Real(2), i % 3 == 0 ? Real(0) : Real(6));
        const LD aim = rng.uniform(Real(0.3), Real(1.5));  // B heads for A's start
        mb.tx += aim * (ma.start.x - mb.start.x);
        mb.ty += aim * (ma.start.y - mb.start.y);
        const LD target = i % 4 == 0 ? LD(0.05) : LD(0);
        ToiOptions options;
        options.target_distance = static_cast<Real>(target);
        options.tolerance = tol;
        const ToiResult r = time_of_impact(a.shape, ma.motion(), b.shape, mb.motion(), options).value();
        const LD expected = reference_toi(a.ref, ma, b.ref, mb, target, 300);
        const std::string what = std::string(to_string(ta)) + "-" + to_string(tb) + " case " + std::to_string(i);
        ASSERT_NE(r.status, CcdStatus::MaxIterations) << what;
        if (r.status == CcdStatus::InitiallyOverlapping) {
          ASSERT_LT(test::signed_distance(a.ref, ma.at(0), b.ref, mb.at(0)), LD(0)) << what;
          continue;
        }
        ++compared;
        if (r.status == CcdStatus::Separated) {
          // Nothing was found: within reach at t = 0 (touching, not approaching), the shapes
          // must never come nearer; otherwise the reference finds no crossing.
          if (expected == 0) {
            const LD start = test::signed_distance(a.ref, ma.at(0), b.ref, mb.at(0));
            for (int k = 1; k <= 100; ++k) {
              const LD t = LD(k) / 100;
              ASSERT_GT(test::signed_distance(a.ref, ma.at(t), b.ref, mb.at(t)), start - 20 * tol)
                  << what << " t " << k;
            }
          } else if (expected > 0) {
            const LD deepest =
                test::signed_distance(a.ref, ma.at(expected + LD(1e-3)), b.ref, mb.at(expected + LD(1e-3)));
            ASSERT_GT(deepest, target - 20 * tol) << what << " missed a hit at " << static_cast<double>(expected);
          }
          continue;
        }
        ++hits;
        // Within reach at toi, and no earlier crossing than the certified bracket.
        const LD at_toi = test::signed_distance(a.ref, ma.at(r.toi), b.ref, mb.at(r.toi));
        ASSERT_LE(at_toi, target + 4 * tol) << what;
        // (A toi before the reference's is a graze between its samples: at_toi proves it.)
        // The certified bracket may end past the reference's crossing only by rounding.
        if (expected >= 0 && static_cast<LD>(r.t_lower) > expected) {
          ASSERT_GE(test::signed_distance(a.ref, ma.at(r.t_lower), b.ref, mb.at(r.t_lower)), target - 4 * tol) << what;
        }
        ASSERT_NEAR(glm::length(r.normal), Real(1), Real(1e-4)) << what;
      }
    }
  }
  EXPECT_GT(hits, compared / 5);
}

TEST(D2TimeOfImpact, CircleOntoABoxAtTheAnalyticTime) {
  const Shape box = Polygon::box(Real(1), Real(1)).value();
  const Shape ball = Circle::create(Real(0.5)).value();
  const ToiResult r = shape_cast(ball, Pose::from({Real(5), 0}, 0), {Real(-8), 0}, box, Pose::identity()).value();
  ASSERT_EQ(r.status, CcdStatus::Hit);
  EXPECT_NEAR(r.toi, Real(3.5) / Real(8), Real(2e-4));
  EXPECT_NEAR(r.normal.x, Real(-1), Real(1e-4));
  EXPECT_NEAR(r.point_b.x, Real(1), Real(1e-3));
}

TEST(D2TimeOfImpact, ASpinningPaddleHitsABallAtTheAnalyticAngle) {
  // A paddle (capsule of half length 2, radius 0.1) turns half a turn about its centre; a ball
  // of radius 0.2 at (-1, 1) (polar angle 3 pi / 4, distance sqrt 2) is met when the paddle's
  // line, at angle phi, is 0.3 from the ball's centre: sqrt(2) sin(3 pi / 4 - phi) = 0.3.
  // (The contact's projection on the paddle, 1.38, lies within its half length.)
  const Shape paddle = Capsule::create({Real(-2), 0}, {Real(2), 0}, Real(0.1)).value();
  const Shape ball = Circle::create(Real(0.2)).value();
  const Motion spin{Pose::identity(), Vec2(Real(0)), kPi};
  const Motion still = Motion::translating(Pose::from({Real(-1), Real(1)}, 0), Vec2(Real(0)));
  const ToiResult r = time_of_impact(paddle, spin, ball, still).value();
  ASSERT_EQ(r.status, CcdStatus::Hit);
  const Real phi = Real(3) * kPi / 4 - std::asin(Real(0.3) / std::sqrt(Real(2)));
  EXPECT_NEAR(r.toi, phi / kPi, Real(2e-4));
}

TEST(D2TimeOfImpact, TheTimeZeroContract) {
  const Shape box = Polygon::box(Real(1), Real(1)).value();
  // Overlapping at t = 0.
  ToiResult r = shape_cast(box, Pose::from({Real(1.5), 0}, 0), {Real(1), 0}, box, Pose::identity()).value();
  EXPECT_EQ(r.status, CcdStatus::InitiallyOverlapping);
  EXPECT_NEAR(r.depth, Real(0.5), Real(1e-5));
  EXPECT_NEAR(r.normal.x, Real(-1), Real(1e-5));
  // Touching and approaching: a hit at 0; touching and leaving: separated.
  r = shape_cast(box, Pose::from({Real(2), 0}, 0), {Real(-1), 0}, box, Pose::identity()).value();
  EXPECT_EQ(r.status, CcdStatus::Hit);
  EXPECT_EQ(r.toi, Real(0));
  r = shape_cast(box, Pose::from({Real(2), 0}, 0), {Real(1), 0}, box, Pose::identity()).value();
  EXPECT_EQ(r.status, CcdStatus::Separated);
}

TEST(D2TimeOfImpact, ChainsAreOneSidedAndSegmentsAreFound) {
  const std::vector<Vec2> floor_points = {{Real(10), 0}, {Real(5), 0}, {0, 0}, {Real(-5), Real(2)}};
  const Shape floor = Chain::create(floor_points, false).value();
  const Shape bullet = Circle::create(Real(0.05)).value();
  // A bullet falling fast from above hits segment 1 ([0, 5]) at the analytic time.
  ToiResult r =
      shape_cast(bullet, Pose::from({Real(2), Real(10)}, 0), {Real(0), Real(-100)}, floor, Pose::identity()).value();
  ASSERT_EQ(r.status, CcdStatus::Hit);
  EXPECT_NEAR(r.toi, Real(9.95) / Real(100), Real(1e-5));
  EXPECT_EQ(r.part_b, 1);
  // From below, it passes through.
  r = shape_cast(bullet, Pose::from({Real(2), Real(-10)}, 0), {Real(0), Real(100)}, floor, Pose::identity()).value();
  EXPECT_EQ(r.status, CcdStatus::Separated);
}

TEST(D2TimeOfImpact, BadInputNamesTheField) {
  const Shape ball = Circle::create(Real(1)).value();
  Motion bad = Motion::translating(Pose::identity(), {std::numeric_limits<Real>::infinity(), 0});
  EXPECT_EQ(time_of_impact(ball, Motion{}, ball, bad).error().field, "motion_b.translation");
  bad = Motion{Pose::identity(), Vec2(Real(0)), std::numeric_limits<Real>::quiet_NaN()};
  proxima::test::ScopedNoFpTraps no_traps;
  EXPECT_EQ(time_of_impact(ball, bad, ball, Motion{}).error().field, "motion_a.rotation");
  ToiOptions options;
  options.target_distance = Real(-1);
  EXPECT_EQ(time_of_impact(ball, Motion{}, ball, Motion{}, options).error().field, "options.target_distance");
}

}  // namespace
}  // namespace proxima::d2
