// CollisionWorld's objects: handles (stale and foreign ones rejected), bad input naming the
// field and leaving the state hash unchanged, filters (64-bit layers, groups, exclusions, the
// pair callback), kinds, attachment (transforms down, bounds up, no pairs inside a tree),
// removal ending pairs at the next step.
#include <gtest/gtest.h>

#include <proxima/core/tolerance.hpp>

#include "world/world_scene.hpp"

namespace proxima::test {
namespace test_world_objects {

ObjectDesc static_box(const Transform& pose, const Vec3& half) {
  ObjectDesc d;
  d.geometry = *Box::create(half);
  d.pose = pose;
  d.kind = ObjectKind::Static;
  return d;
}

TEST(WorldObjects, StaleAndForeignHandlesAreRejected) {
  CollisionWorld world = make_world();
  const ObjectHandle a = *world.add(ball(at(0)));
  EXPECT_TRUE(world.contains(a));
  ASSERT_FALSE(world.remove(a).has_value());
  EXPECT_FALSE(world.contains(a));
  const ObjectHandle b = *world.add(ball(at(0)));
  EXPECT_EQ(b.index, a.index);            // the slot is reused ...
  EXPECT_NE(b.generation, a.generation);  // ... under a new generation
  for (ObjectHandle h : {a, ObjectHandle{}, ObjectHandle{7, 0}}) {
    const std::uint64_t before = world.state_hash();
    auto e = world.move(h, at(1));
    ASSERT_TRUE(e.has_value());
    EXPECT_EQ(e->field, "object");
    EXPECT_TRUE(world.remove(h).has_value());
    EXPECT_TRUE(world.set_filter(h, {}).has_value());
    EXPECT_FALSE(world.object(h).has_value());
    EXPECT_EQ(world.state_hash(), before);
  }
  EXPECT_EQ(world.pose(b).position, Vec3(0));
}

/// The error of an add, or nothing when it succeeded.
std::optional<Error> add_error(CollisionWorld& world, const ObjectDesc& d) {
  auto r = world.add(d);
  return r.ok() ? std::nullopt : std::optional<Error>(r.error());
}

TEST(WorldObjects, BadInputNamesTheFieldAndChangesNothing) {
  CollisionWorld world = make_world();
  const ObjectHandle a = *world.add(ball(at(0)));
  const ObjectHandle s = *world.add(static_box(at(3), Vec3(1)));
  const ObjectHandle c = *world.add([&] {
    ObjectDesc d = ball(at(0));
    d.parent = a;
    d.local_pose = at(1);
    return d;
  }());
  ASSERT_FALSE(world.step(Real(0.1)).has_value());
  const std::uint64_t before = world.state_hash();
  ScopedNoFpTraps no_traps;
  const Real nan = std::numeric_limits<Real>::quiet_NaN();
  auto expect_field = [&](const std::optional<Error>& e, const std::string& field) {
    ASSERT_TRUE(e.has_value()) << field;
    EXPECT_EQ(e->field, field);
    EXPECT_FALSE(e->message.empty());
    EXPECT_EQ(world.state_hash(), before) << field;
  };
  ObjectDesc d = ball(at(nan));
  expect_field(add_error(world, d), "desc.pose.position");
  d = ball(Transform{Vec3(0), Quat(Real(2), 0, 0, 0)});
  expect_field(add_error(world, d), "desc.pose.rotation");
  d = ball(at(0));
  d.filter.layer = 0;
  expect_field(add_error(world, d), "desc.filter.layer");
  d = ball(at(0));
  d.filter.mask = 0;
  expect_field(add_error(world, d), "desc.filter.mask");
  d = ball(at(0));
  d.geometry = *HalfSpace::create(Vec3(0, 0, 1), 0);  // a moving half-space
  expect_field(add_error(world, d), "desc.geometry");
  d = ball(at(0));
  d.parent = ObjectHandle{99, 0};
  expect_field(add_error(world, d), "desc.parent");
  d = ball(at(0));
  d.parent = a;
  d.local_pose = at(nan);
  expect_field(add_error(world, d), "desc.local_pose.position");
  expect_field(world.move(a, at(Real(2) * kMaxCoordinate)), "pose.position");
  const ObjectMove moves[] = {{a, at(1)}, {s, Transform{Vec3(0), Quat(0, 0, 0, 0)}}};
  expect_field(world.move(moves), "moves[1].pose.rotation");
  const ObjectMove stale_moves[] = {{a, at(1)}, {ObjectHandle{42, 3}, at(2)}};
  expect_field(world.move(stale_moves), "moves[1].object");
  expect_field(world.set_kind(c, ObjectKind::Static), "kind");
  expect_field(world.attach(a, c, at(0)), "parent");  // its own descendant
  expect_field(world.attach(a, a, at(0)), "parent");
  expect_field(world.set_pair_excluded(a, a, true), "b");
  expect_field(world.set_filter(a, CollisionFilter{0, 1, 0}), "filter.layer");
  expect_field(world.step(Real(0)), "dt");
  expect_field(world.step(nan), "dt");
  EXPECT_EQ(world.raycast(Ray{Vec3(0), Vec3(0)}, 1).error().field, "ray.direction");
  EXPECT_EQ(world.closest_point(Vec3(0), Real(-1)).error().field, "max_distance");
  EXPECT_EQ(world
                .sweep(*TriangleMesh::create(IndexedMesh{{Vec3(0), Vec3(1, 0, 0), Vec3(0, 1, 0)}, {{0, 1, 2}}}), at(0),
                       Vec3(1, 0, 0))
                .error()
                .field,
            "geometry");
  EXPECT_EQ(world.state_hash(), before);
}

TEST(WorldObjects, SixtyFourBitLayersGroupsExclusionsAndThePairCallback) {
  CollisionWorld world = make_world();
  ObjectDesc da = ball(at(0));
  da.filter.layer = 1ull << 40;
  const ObjectHandle a = *world.add(da);
  ObjectDesc db = ball(at(Real(0.8)));
  db.filter.mask = ~(1ull << 40);
  const ObjectHandle b = *world.add(db);
  ASSERT_FALSE(world.step(Real(0.1)).has_value());
  EXPECT_TRUE(world.contacts().empty()) << "bit 40 of a's layer is outside b's mask";

  ASSERT_FALSE(world.set_filter(b, CollisionFilter{1, 1ull << 40, 0}).has_value());
  ASSERT_FALSE(world.step(Real(0.1)).has_value());
  ASSERT_EQ(world.events().begin.size(), 1u);
  EXPECT_EQ(world.events().begin[0].pair, (ObjectPair{a, b}));

  // Same non-zero group: the pair ends at the next step.
  ASSERT_FALSE(world.set_filter(a, CollisionFilter{1ull << 40, ~0ull, 7}).has_value());
  ASSERT_FALSE(world.set_filter(b, CollisionFilter{1, 1ull << 40, 7}).has_value());
  ASSERT_FALSE(world.step(Real(0.1)).has_value());
  ASSERT_EQ(world.events().end.size(), 1u);
  ASSERT_FALSE(world.set_filter(b, CollisionFilter{1, 1ull << 40, 8}).has_value());
  ASSERT_FALSE(world.step(Real(0.1)).has_value());
  EXPECT_EQ(world.events().begin.size(), 1u);

  // An exclusion ends it, and lifting it begins it again.
  ASSERT_FALSE(world.set_pair_excluded(b, a, true).has_value());
  ASSERT_FALSE(world.step(Real(0.1)).has_value());
  EXPECT_EQ(world.events().end.size(), 1u);
  ASSERT_FALSE(world.set_pair_excluded(a, b, false).has_value());
  ASSERT_FALSE(world.step(Real(0.1)).has_value());
  EXPECT_EQ(world.events().begin.size(), 1u);

  // The pair callback vetoes with context (the objects' user data).
  struct Veto final : PairFilterCallback {
    bool can_collide(const CollisionWorld& w, ObjectPair pair) override {
      return w.object(pair.a)->user_data != 13 && w.object(pair.b)->user_data != 13;
    }
  } veto;
  world.set_pair_filter(&veto);
  ASSERT_FALSE(world.set_user_data(b, 13).has_value());
  ASSERT_FALSE(world.step(Real(0.1)).has_value());
  ASSERT_EQ(world.events().end.size(), 1u);
  EXPECT_EQ(world.events().end[0].user_data_b, 13u);
  world.set_pair_filter(nullptr);
  ASSERT_FALSE(world.step(Real(0.1)).has_value());
  EXPECT_EQ(world.events().begin.size(), 1u);
}

TEST(WorldObjects, RemovingAnObjectDropsItsExclusions) {
  CollisionWorld world = make_world();
  const ObjectHandle a = *world.add(ball(at(0)));
  const ObjectHandle b = *world.add(ball(at(Real(0.9))));
  const ObjectHandle c = *world.add(ball(at(Real(-0.9))));
  ASSERT_FALSE(world.set_pair_excluded(a, b, true).has_value());
  ASSERT_FALSE(world.set_pair_excluded(a, c, true).has_value());
  ASSERT_FALSE(world.remove(b).has_value());
  const ObjectHandle reused = *world.add(ball(at(Real(0.9))));  // b's slot, no exclusion
  ASSERT_EQ(reused.index, b.index);
  ASSERT_FALSE(world.step(Real(0.1)).has_value());
  ASSERT_EQ(world.events().begin.size(), 1u);  // a-reused; a-c stays excluded
  EXPECT_EQ(world.events().begin[0].pair, (ObjectPair{a, reused}));
}

TEST(WorldObjects, StaticObjectsNeverPairWithEachOther) {
  CollisionWorld world = make_world();
  const ObjectHandle a = *world.add(static_box(at(0), Vec3(1)));
  const ObjectHandle b = *world.add(static_box(at(1), Vec3(1)));
  ASSERT_FALSE(world.step(Real(0.1)).has_value());
  EXPECT_TRUE(world.contacts().empty());
  ASSERT_FALSE(world.set_kind(b, ObjectKind::Moving).has_value());
  ASSERT_FALSE(world.step(Real(0.1)).has_value());
  ASSERT_EQ(world.events().begin.size(), 1u);
  ASSERT_FALSE(world.set_kind(b, ObjectKind::Static).has_value());
  ASSERT_FALSE(world.step(Real(0.1)).has_value());
  EXPECT_EQ(world.events().end.size(), 1u);
  EXPECT_TRUE(world.contains(a));
}

TEST(WorldObjects, AttachedObjectsFollowTheirParentAndNeverPairInsideTheTree) {
  CollisionWorld world = make_world();
  const ObjectHandle body = *world.add(ball(at(0)));
  ObjectDesc arm = ball(at(0), Real(0.3));
  arm.parent = body;
  arm.local_pose = at(Real(0.6));  // overlaps the body: never a pair
  const ObjectHandle hand = *world.add(arm);
  const ObjectHandle wall = *world.add(static_box(at(10), Vec3(Real(0.5))));
  ASSERT_FALSE(world.step(Real(0.1)).has_value());
  EXPECT_TRUE(world.contacts().empty());
  EXPECT_EQ(world.object(hand)->parent, body);

  // Transforms down: turning the body by 90 degrees about z swings the hand to +y.
  const Transform turned{Vec3(Real(9.0), 0, 0), glm::angleAxis(Real(1.5707963), Vec3(0, 0, 1))};
  ASSERT_FALSE(world.move(body, turned).has_value());
  EXPECT_NEAR(world.pose(hand).position.x, Real(9.0), Real(1e-5));
  EXPECT_NEAR(world.pose(hand).position.y, Real(0.6), Real(1e-5));
  // Bounds up: the hand's box follows.
  EXPECT_NEAR(world.bounds(hand).max.y, Real(0.9), Real(1e-5));
  ASSERT_FALSE(world.step(Real(0.1)).has_value());
  ASSERT_EQ(world.events().begin.size(), 1u);  // the body (radius 0.5 at x = 9) reaches the wall at 9.5
  EXPECT_EQ(world.events().begin[0].pair, (ObjectPair{body, wall}));

  // Detaching keeps the world pose; then the two may pair.
  ASSERT_FALSE(world.attach(hand, ObjectHandle{}, Transform{}).has_value());
  EXPECT_NEAR(world.pose(hand).position.y, Real(0.6), Real(1e-5));
  ASSERT_FALSE(world.step(Real(0.1)).has_value());
  EXPECT_EQ(world.events().begin.size(), 1u);  // body-hand now
  EXPECT_NE(world.contact(body, hand), nullptr);

  // Removing the parent removes its subtree.
  ASSERT_FALSE(world.attach(hand, body, at(Real(0.6))).has_value());
  ASSERT_FALSE(world.remove(body).has_value());
  EXPECT_FALSE(world.contains(hand));
  EXPECT_EQ(world.size(), 1u);
}

TEST(WorldObjects, RemovingAnObjectEndsItsPairsAtTheNextStep) {
  CollisionWorld world = make_world();
  ObjectDesc d = ball(at(0));
  d.user_data = 111;
  const ObjectHandle a = *world.add(d);
  d = ball(at(Real(0.9)));
  d.user_data = 222;
  const ObjectHandle b = *world.add(d);
  ASSERT_FALSE(world.step(Real(0.1)).has_value());
  ASSERT_EQ(world.events().begin.size(), 1u);
  ASSERT_FALSE(world.remove(b).has_value());
  const ObjectHandle c = *world.add(ball(at(Real(50))));  // reuses b's slot
  EXPECT_EQ(c.index, b.index);
  ASSERT_FALSE(world.step(Real(0.1)).has_value());
  ASSERT_EQ(world.events().end.size(), 1u);
  EXPECT_EQ(world.events().end[0].pair, (ObjectPair{a, b}));
  EXPECT_EQ(world.events().end[0].user_data_b, 222u);
  EXPECT_TRUE(world.events().begin.empty());
}

TEST(WorldObjects, ChangingTheGeometryRetestsItsPairs) {
  CollisionWorld world = make_world();
  const ObjectHandle a = *world.add(ball(at(0)));
  const ObjectHandle b = *world.add(ball(at(Real(0.9))));
  ASSERT_FALSE(world.step(Real(0.1)).has_value());
  ASSERT_EQ(world.contacts().size(), 1u);
  ASSERT_FALSE(world.set_geometry(b, *Sphere::create(Real(0.3))).has_value());
  ASSERT_FALSE(world.step(Real(0.1)).has_value());
  EXPECT_EQ(world.events().end.size(), 1u);
  ASSERT_FALSE(world.set_geometry(a, *Box::create(Vec3(Real(0.7)))).has_value());
  ASSERT_FALSE(world.step(Real(0.1)).has_value());
  EXPECT_EQ(world.events().begin.size(), 1u);
}

}  // namespace test_world_objects
}  // namespace proxima::test
