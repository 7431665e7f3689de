// A game loop on the collision world: what an engine's frame does with Proxima.
//
// A ground plane, a trigger zone and a thin wall are static; three crates slide over the
// ground, a fast bullet flies through the wall between two frames. Each frame the engine
// moves its objects (here: constant velocities), calls step(), and reacts to the contact,
// sensor and impact events through a listener; at the end it asks the world a ray cast
// (picking) and a line of sight. Build and run: the output lists the events as they are
// heard (printed by the listener during step(), before the line naming the frame).
#include <proxima/world/collision_world.hpp>

#include <cstdio>
#include <vector>

using namespace proxima;

namespace {

/// The engine's reactions to the world's events.
class Listener final : public WorldListener {
 public:
  void on_contact_begin(CollisionWorld&, const ContactEvent& e) override {
    std::printf("  contact begins: %llu with %llu\n", ull(e.user_data_a), ull(e.user_data_b));
  }
  void on_contact_end(CollisionWorld&, const ContactEvent& e) override {
    std::printf("  contact ends:   %llu with %llu\n", ull(e.user_data_a), ull(e.user_data_b));
  }
  void on_sensor_enter(CollisionWorld&, const SensorEvent& e) override {
    std::printf("  %llu enters the trigger zone\n", ull(e.user_data_other));
  }
  void on_sensor_exit(CollisionWorld&, const SensorEvent& e) override {
    std::printf("  %llu leaves the trigger zone\n", ull(e.user_data_other));
  }
  void on_impact(CollisionWorld&, const ImpactEvent& e) override {
    std::printf("  impact: %llu reaches %llu at %.3f of the frame, normal (%.2f %.2f %.2f)\n", ull(e.user_data_a),
                ull(e.user_data_b), double(e.toi), double(e.normal.x), double(e.normal.y), double(e.normal.z));
  }

 private:
  static unsigned long long ull(std::uint64_t v) { return static_cast<unsigned long long>(v); }
};

/// Object names, carried as user data (an engine would store its entity id).
enum Name : std::uint64_t { Ground = 1, Zone, Wall, Crate1, Crate2, Crate3, Bullet };

}  // namespace

int main() {
  auto created = CollisionWorld::create();  // default settings: dynamic tree, contact distance 0
  if (!created) return 1;
  CollisionWorld world = std::move(created).value();
  Listener listener;
  world.set_listener(&listener);

  auto add = [&](Shape geometry, Vec3 at, ObjectKind kind, std::uint64_t name, bool sensor = false) {
    ObjectDesc d;
    d.geometry = std::move(geometry);
    d.pose = Transform{at, kIdentityQuat};
    d.kind = kind;
    d.user_data = name;
    d.sensor = sensor;
    return world.add(d).value();
  };
  add(HalfSpace::create(Vec3(0, 0, 1), Real(0)).value(), Vec3(0), ObjectKind::Static, Ground);
  add(Box::create(Vec3(1, 1, 1)).value(), Vec3(4, 0, 1), ObjectKind::Static, Zone, /*sensor=*/true);
  add(Box::create(Vec3(Real(0.02), 2, 2)).value(), Vec3(10, 0, 2), ObjectKind::Static, Wall);

  struct Body {
    ObjectHandle handle;
    Vec3 velocity;  // metres per second
  };
  std::vector<Body> bodies;
  bodies.push_back(
      {add(Box::create(Vec3(Real(0.5))).value(), Vec3(0, 0, Real(0.5)), ObjectKind::Moving, Crate1), Vec3(9, 0, 0)});
  bodies.push_back(
      {add(Box::create(Vec3(Real(0.5))).value(), Vec3(3, 3, Real(0.5)), ObjectKind::Moving, Crate2), Vec3(0, -6, 0)});
  bodies.push_back(
      {add(Sphere::create(Real(0.5)).value(), Vec3(-3, 0, Real(2)), ObjectKind::Moving, Crate3), Vec3(0, 0, -6)});
  bodies.push_back({add(Sphere::create(Real(0.05)).value(), Vec3(6, 0, 2), ObjectKind::Moving, Bullet),
                    Vec3(300, 0, 0)});  // 5 m per frame: crosses the 4 cm wall between two frames

  const Real dt = Real(1) / Real(60);
  for (int frame = 1; frame <= 40; ++frame) {
    std::vector<ObjectMove> moves;
    for (const Body& b : bodies) {
      Transform pose = world.pose(b.handle);
      pose.position += b.velocity * dt;
      if (pose.position.z < Real(0.5) && b.velocity.z < 0) pose.position.z = Real(0.5);  // rests on the ground
      moves.push_back({b.handle, pose});
    }
    if (world.move(moves)) return 1;
    if (world.step(dt)) return 1;               // events reach the listener here
    const StepEvents& events = world.events();  // the same events, as sorted arrays
    if (!events.begin.empty() || !events.end.empty() || !events.sensor_enter.empty() || !events.sensor_exit.empty() ||
        !events.impacts.empty())
      std::printf("frame %d: %zu touching pairs\n", frame, world.contacts().size());
  }

  const auto picked = world.raycast(Ray{Vec3(-10, 0, Real(0.5)), Vec3(1, 0, 0)}, Real(100));
  if (picked && !picked->empty())
    std::printf("picking ray hits %llu at t=%.2f\n", static_cast<unsigned long long>(picked->front().user_data),
                double(picked->front().t));
  const auto clear = world.line_of_sight(Vec3(8, 0, 2), Vec3(12, 0, 2));
  std::printf("line of sight through the wall: %s\n", clear && *clear ? "clear" : "blocked");
  return 0;
}
