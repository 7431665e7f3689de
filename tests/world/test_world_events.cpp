// CollisionWorld's sensors and callbacks: sensor enter / exit (against moving and static
// objects, sensors against sensors only when asked), the world and object listeners in
// event order, on_pre_contact editing and vetoing pairs, changes from callbacks (removal
// during a callback ends the pair at the next step), and the calls a callback may not make.
#include <gtest/gtest.h>

#include <string>

#include "world/world_scene.hpp"

namespace proxima::test {
namespace test_world_events {

ObjectDesc sensor_box(const Transform& pose, ObjectKind kind) {
  ObjectDesc d;
  d.geometry = *Box::create(Vec3(1));
  d.pose = pose;
  d.kind = kind;
  d.sensor = true;
  return d;
}

TEST(WorldEvents, SensorsReportEnterAndExitNeverContacts) {
  CollisionWorld world = make_world();
  const ObjectHandle zone = *world.add(sensor_box(at(0), ObjectKind::Static));
  const ObjectHandle b = *world.add(ball(at(5)));
  ASSERT_FALSE(world.step(Real(0.1)).has_value());
  EXPECT_TRUE(world.events().sensor_enter.empty());
  ASSERT_FALSE(world.move(b, at(Real(1.2))).has_value());
  ASSERT_FALSE(world.step(Real(0.1)).has_value());
  ASSERT_EQ(world.events().sensor_enter.size(), 1u);
  EXPECT_EQ(world.events().sensor_enter[0].sensor, zone);
  EXPECT_EQ(world.events().sensor_enter[0].other, b);
  EXPECT_TRUE(world.contacts().empty());
  EXPECT_TRUE(world.events().begin.empty());
  ASSERT_FALSE(world.move(b, at(Real(0.5))).has_value());
  ASSERT_FALSE(world.step(Real(0.1)).has_value());
  EXPECT_TRUE(world.events().sensor_enter.empty());
  EXPECT_TRUE(world.events().sensor_exit.empty());
  ASSERT_FALSE(world.move(b, at(Real(3))).has_value());
  ASSERT_FALSE(world.step(Real(0.1)).has_value());
  ASSERT_EQ(world.events().sensor_exit.size(), 1u);
  EXPECT_EQ(world.events().sensor_exit[0].other, b);
}

TEST(WorldEvents, AMovingSensorSensesStaticObjects) {
  CollisionWorld world = make_world();
  ObjectDesc wall;
  wall.geometry = *Box::create(Vec3(Real(0.5)));
  wall.pose = at(0);
  wall.kind = ObjectKind::Static;
  const ObjectHandle w = *world.add(wall);
  const ObjectHandle zone = *world.add(sensor_box(at(Real(1.2)), ObjectKind::Moving));
  ASSERT_FALSE(world.step(Real(0.1)).has_value());
  ASSERT_EQ(world.events().sensor_enter.size(), 1u);
  EXPECT_EQ(world.events().sensor_enter[0].sensor, zone);
  EXPECT_EQ(world.events().sensor_enter[0].other, w);
}

TEST(WorldEvents, SensorsSenseSensorsOnlyWhenAsked) {
  for (bool sense : {false, true}) {
    WorldSettings settings;
    settings.sensors_sense_sensors = sense;
    CollisionWorld world = make_world(settings);
    const ObjectHandle a = *world.add(sensor_box(at(0), ObjectKind::Moving));
    const ObjectHandle b = *world.add(sensor_box(at(1), ObjectKind::Moving));
    ASSERT_FALSE(world.step(Real(0.1)).has_value());
    if (!sense) {
      EXPECT_TRUE(world.events().sensor_enter.empty());
      continue;
    }
    ASSERT_EQ(world.events().sensor_enter.size(), 2u);  // each senses the other
    EXPECT_EQ(world.events().sensor_enter[0].sensor, a);
    EXPECT_EQ(world.events().sensor_enter[1].sensor, b);
  }
}

/// Records every callback as a line of text.
struct Recorder : WorldListener {
  std::string name;
  std::vector<std::string>* log = nullptr;
  void on_contact_begin(CollisionWorld&, const ContactEvent& e) override { add("begin", e.pair); }
  void on_contact_persist(CollisionWorld&, const ContactEvent& e) override { add("persist", e.pair); }
  void on_contact_end(CollisionWorld&, const ContactEvent& e) override { add("end", e.pair); }
  void on_sensor_enter(CollisionWorld&, const SensorEvent& e) override { add("enter", {e.sensor, e.other}); }
  void on_sensor_exit(CollisionWorld&, const SensorEvent& e) override { add("exit", {e.sensor, e.other}); }
  void add(const char* what, ObjectPair p) {
    log->push_back(name + " " + what + " " + std::to_string(p.a.index) + "-" + std::to_string(p.b.index));
  }
};

TEST(WorldEvents, WorldAndObjectListenersHearEventsInOrder) {
  CollisionWorld world = make_world();
  std::vector<std::string> log;
  Recorder all, of_b;
  all.name = "world";
  all.log = &log;
  of_b.name = "b";
  of_b.log = &log;
  const ObjectHandle a = *world.add(ball(at(0)));
  const ObjectHandle b = *world.add(ball(at(Real(0.9))));
  const ObjectHandle c = *world.add(ball(at(Real(-0.9))));
  world.set_listener(&all);
  ASSERT_FALSE(world.set_object_listener(b, &of_b).has_value());
  ASSERT_FALSE(world.step(Real(0.1)).has_value());
  EXPECT_EQ(log, (std::vector<std::string>{"world begin 0-1", "b begin 0-1", "world begin 0-2"}));
  log.clear();
  ASSERT_FALSE(world.move(c, at(-5)).has_value());
  ASSERT_FALSE(world.step(Real(0.1)).has_value());
  EXPECT_EQ(log, (std::vector<std::string>{"world persist 0-1", "b persist 0-1", "world end 0-2"}));
  EXPECT_TRUE(world.contains(a));
}

TEST(WorldEvents, RemovalDuringACallbackEndsThePairAtTheNextStep) {
  CollisionWorld world = make_world();
  struct Remover : WorldListener {
    ObjectHandle doomed;
    int begins = 0;
    void on_contact_begin(CollisionWorld& w, const ContactEvent& e) override {
      ++begins;
      EXPECT_FALSE(w.remove(doomed).has_value());
      EXPECT_FALSE(w.contains(e.pair.b));
      EXPECT_TRUE(w.step(Real(0.1)).has_value());  // no step from a callback
    }
  } remover;
  const ObjectHandle a = *world.add(ball(at(0)));
  remover.doomed = *world.add(ball(at(Real(0.9))));
  world.set_listener(&remover);
  ASSERT_FALSE(world.step(Real(0.1)).has_value());
  EXPECT_EQ(remover.begins, 1);
  world.set_listener(nullptr);
  ASSERT_FALSE(world.step(Real(0.1)).has_value());
  ASSERT_EQ(world.events().end.size(), 1u);
  EXPECT_EQ(world.events().end[0].pair, (ObjectPair{a, remover.doomed}));
}

TEST(WorldEvents, PreContactEditsOrVetoesAPairForTheStep) {
  CollisionWorld world = make_world();
  struct Filter : WorldListener {
    bool veto = false;
    bool tried_change = false;
    ObjectHandle some;
    bool on_pre_contact(const CollisionWorld& w, WorldManifold& m) override {
      // Changes are refused here (the const world cannot be changed; a cast would be UB).
      tried_change = w.contains(some);
      m.points[0].user[1] = Real(42);
      return !veto;
    }
  } filter;
  const ObjectHandle a = *world.add(ball(at(0)));
  const ObjectHandle b = *world.add(ball(at(Real(0.9))));
  filter.some = a;
  world.set_listener(&filter);
  ASSERT_FALSE(world.step(Real(0.1)).has_value());
  ASSERT_EQ(world.events().begin.size(), 1u);
  EXPECT_EQ(world.contact(a, b)->points[0].user[1], Real(42));
  filter.veto = true;
  ASSERT_FALSE(world.step(Real(0.1)).has_value());
  EXPECT_EQ(world.events().end.size(), 1u);
  EXPECT_EQ(world.contact(a, b), nullptr);
  filter.veto = false;
  ASSERT_FALSE(world.step(Real(0.1)).has_value());
  EXPECT_EQ(world.events().begin.size(), 1u);
  EXPECT_TRUE(filter.tried_change);
}

}  // namespace test_world_events
}  // namespace proxima::test
