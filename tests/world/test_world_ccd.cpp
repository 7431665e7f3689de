// Continuous detection in CollisionWorld's step: fast objects' impacts against thin static
// plates (checked against the analytic time), spinning objects, both-moving pairs in Bullet
// mode, sensors crossed within a step, filters applying to continuous detection, and the
// off switch.
#include <gtest/gtest.h>

#include "world/world_scene.hpp"

namespace proxima::test {
namespace test_world_ccd {

ObjectDesc bullet(const Transform& pose, Real r, CcdMode mode) {
  ObjectDesc d;
  d.geometry = *Sphere::create(r);
  d.pose = pose;
  d.ccd = mode;
  return d;
}

ObjectDesc plate(const Transform& pose, bool sensor = false) {
  ObjectDesc d;
  d.geometry = *Box::create(Vec3(Real(0.01), Real(2), Real(2)));
  d.pose = pose;
  d.kind = ObjectKind::Static;
  d.sensor = sensor;
  return d;
}

TEST(WorldCcd, AFastSphereThroughAThinPlateReportsItsImpact) {
  Random rng(11);
  for (int k = 0; k < 200; ++k) {
    CollisionWorld world = make_world();
    const Real x0 = rng.uniform(Real(-9), Real(-1)), x1 = rng.uniform(Real(1), Real(9));
    const Real r = rng.uniform(Real(0.02), Real(0.1));
    const Real off_z = rng.uniform(Real(-1.5), Real(1.5));  // GCC's order of the arguments this replaced
    const Real off_y = rng.uniform(Real(-1.5), Real(1.5));
    const Vec3 off(0, off_y, off_z);
    const ObjectHandle p = *world.add(plate(at(0)));
    const ObjectHandle b = *world.add(bullet(Transform{Vec3(x0, 0, 0) + off, kIdentityQuat}, r, CcdMode::Auto));
    ASSERT_FALSE(world.step(Real(1) / Real(60)).has_value());
    ASSERT_FALSE(world.move(b, Transform{Vec3(x1, 0, 0) + off, kIdentityQuat}).has_value());
    ASSERT_FALSE(world.step(Real(1) / Real(60)).has_value());
    EXPECT_TRUE(world.contacts().empty()) << "no discrete contact at either end";
    ASSERT_EQ(world.events().impacts.size(), 1u) << k;
    const ImpactEvent& e = world.events().impacts[0];
    EXPECT_EQ(e.a, b);
    EXPECT_EQ(e.b, p);
    // Analytic: the sphere's front reaches x = -0.01 when x0 + s (x1 - x0) = -0.01 - r.
    const Real s = (Real(-0.01) - r - x0) / (x1 - x0);
    EXPECT_NEAR(e.toi, s, Real(2e-4)) << k;
    EXPECT_NEAR(e.normal.x, Real(1), Real(1e-3));
    EXPECT_NEAR(e.point.x, Real(-0.01), Real(2e-3));
  }
}

TEST(WorldCcd, OffAndSlowObjectsReportNoImpact) {
  CollisionWorld world = make_world();
  world.add(plate(at(0))).value();
  const ObjectHandle off = *world.add(bullet(at(-5), Real(0.05), CcdMode::Off));
  const ObjectHandle slow = *world.add(bullet(at(-5, 3), Real(0.5), CcdMode::Auto));
  ASSERT_FALSE(world.step(Real(0.1)).has_value());
  ASSERT_FALSE(world.move(off, at(5)).has_value());
  ASSERT_FALSE(world.move(slow, at(Real(-4.95), 3)).has_value());  // 0.05 of a 1.0 extent: not fast
  ASSERT_FALSE(world.step(Real(0.1)).has_value());
  EXPECT_TRUE(world.events().impacts.empty());

  WorldSettings settings;
  settings.continuous = false;
  CollisionWorld quiet = make_world(settings);
  quiet.add(plate(at(0))).value();
  const ObjectHandle b = *quiet.add(bullet(at(-5), Real(0.05), CcdMode::Bullet));
  ASSERT_FALSE(quiet.step(Real(0.1)).has_value());
  ASSERT_FALSE(quiet.move(b, at(5)).has_value());
  ASSERT_FALSE(quiet.step(Real(0.1)).has_value());
  EXPECT_TRUE(quiet.events().impacts.empty());
}

// teleport() sets a pose with no motion: a bullet teleported across the plate is swept
// from its new pose only; a move() after the teleport is swept from the teleported pose. Its
// attached child follows with no motion either; bad calls change nothing.
TEST(WorldCcd, ATeleportIsNotSwept) {
  CollisionWorld world = make_world();
  const ObjectHandle p = *world.add(plate(at(0)));
  const ObjectHandle b = *world.add(bullet(at(-5), Real(0.05), CcdMode::Bullet));
  ObjectDesc child_desc = bullet(at(0), Real(0.05), CcdMode::Bullet);
  child_desc.parent = b;
  child_desc.local_pose = Transform{Vec3(0, Real(0.5), 0), kIdentityQuat};
  const ObjectHandle child = *world.add(child_desc);
  ASSERT_FALSE(world.step(Real(0.1)).has_value());
  ASSERT_FALSE(world.teleport(b, at(5)).has_value());
  EXPECT_EQ(world.pose(child).position, Vec3(5, Real(0.5), 0));
  ASSERT_FALSE(world.step(Real(0.1)).has_value());
  EXPECT_TRUE(world.events().impacts.empty());
  EXPECT_TRUE(world.contacts().empty());

  ASSERT_FALSE(world.teleport(b, at(-5)).has_value());
  ASSERT_FALSE(world.move(b, at(4)).has_value());  // swept from -5 (the teleport), not from 5
  ASSERT_FALSE(world.step(Real(0.1)).has_value());
  ASSERT_EQ(world.events().impacts.size(), 2u);  // the bullet and its child, each against the plate
  EXPECT_EQ(world.events().impacts[0].b, p);
  EXPECT_NEAR(world.events().impacts[0].toi, (Real(4.94) / Real(9)), Real(2e-4));

  const std::uint64_t hash = world.state_hash();
  EXPECT_EQ(world.teleport(ObjectHandle{}, at(0))->field, "object");
  EXPECT_EQ(world.teleport(b, Transform{Vec3(std::nan(""), 0, 0), kIdentityQuat})->field, "pose.position");
  EXPECT_EQ(world.state_hash(), hash);
}

TEST(WorldCcd, ASpinningPaddleHitsABallBesideIt) {
  CollisionWorld world = make_world();
  ObjectDesc ball;
  ball.geometry = *Sphere::create(Real(0.1));
  ball.pose = at(0, Real(1.5));
  ball.kind = ObjectKind::Static;
  const ObjectHandle target = *world.add(ball);
  ObjectDesc paddle;
  paddle.geometry = *Box::create(Vec3(Real(2), Real(0.02), Real(0.2)));
  paddle.pose = at(0);
  const ObjectHandle p = *world.add(paddle);
  ASSERT_FALSE(world.step(Real(0.1)).has_value());
  // A turn of 170 degrees about z in one step: the paddle's arm sweeps through the ball at
  // (0, 1.5), which it touches at neither end pose.
  ASSERT_FALSE(world.move(p, Transform{Vec3(0), glm::angleAxis(Real(2.9670597), Vec3(0, 0, 1))}).has_value());
  ASSERT_FALSE(world.step(Real(0.1)).has_value());
  EXPECT_TRUE(world.contacts().empty());
  ASSERT_EQ(world.events().impacts.size(), 1u);
  EXPECT_EQ(world.events().impacts[0].b, target);
  // The paddle's half-thickness 0.02 plus the ball's 0.1 reach the ball's centre line at
  // the angle whose sine is 0.12 / 1.5 less than 90 degrees.
  const Real angle = Real(1.5707963) - std::asin(Real(0.12) / Real(1.5));
  EXPECT_NEAR(world.events().impacts[0].toi, angle / Real(2.9670597), Real(2e-3));
}

TEST(WorldCcd, BulletModeSweepsAgainstMovingObjects) {
  for (CcdMode mode : {CcdMode::Auto, CcdMode::Bullet}) {
    CollisionWorld world = make_world();
    const ObjectHandle a = *world.add(bullet(at(-5), Real(0.05), mode));
    const ObjectHandle b = *world.add(bullet(at(5), Real(0.05), CcdMode::Off));
    ASSERT_FALSE(world.step(Real(0.1)).has_value());
    const ObjectMove moves[] = {{a, at(5, 0, Real(0.01))}, {b, at(-5)}};
    ASSERT_FALSE(world.move(moves).has_value());
    ASSERT_FALSE(world.step(Real(0.1)).has_value());
    if (mode == CcdMode::Auto) {
      EXPECT_TRUE(world.events().impacts.empty());
      continue;
    }
    ASSERT_EQ(world.events().impacts.size(), 1u);
    EXPECT_EQ(world.events().impacts[0].a, a);
    EXPECT_EQ(world.events().impacts[0].b, b);
    // They meet when the gap 10 - 20 s closes to the contact distance 0 across 0.1 of radii.
    EXPECT_NEAR(world.events().impacts[0].toi, (Real(10) - std::sqrt(Real(0.01) - Real(0.0001))) / Real(20),
                Real(1e-3));
  }
}

TEST(WorldCcd, AFastObjectCrossingASensorEntersAndExits) {
  CollisionWorld world = make_world();
  const ObjectHandle zone = *world.add(plate(at(0), true));
  const ObjectHandle b = *world.add(bullet(at(-5), Real(0.05), CcdMode::Auto));
  ASSERT_FALSE(world.step(Real(0.1)).has_value());
  ASSERT_FALSE(world.move(b, at(5)).has_value());
  ASSERT_FALSE(world.step(Real(0.1)).has_value());
  ASSERT_EQ(world.events().sensor_enter.size(), 1u);
  ASSERT_EQ(world.events().sensor_exit.size(), 1u);
  EXPECT_EQ(world.events().sensor_enter[0].sensor, zone);
  EXPECT_EQ(world.events().sensor_exit[0].other, b);
  EXPECT_TRUE(world.events().impacts.empty());
}

TEST(WorldCcd, FiltersApplyToContinuousDetection) {
  CollisionWorld world = make_world();
  ObjectDesc p = plate(at(0));
  p.filter.layer = 2;
  world.add(p).value();
  ObjectDesc d = bullet(at(-5), Real(0.05), CcdMode::Auto);
  d.filter.mask = ~2ull;
  const ObjectHandle b = *world.add(d);
  ASSERT_FALSE(world.step(Real(0.1)).has_value());
  ASSERT_FALSE(world.move(b, at(5)).has_value());
  ASSERT_FALSE(world.step(Real(0.1)).has_value());
  EXPECT_TRUE(world.events().impacts.empty());
}

}  // namespace test_world_ccd
}  // namespace proxima::test
