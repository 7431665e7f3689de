// proxima_bench_world2d: the 2D collision world's step on the W9 2D world (shared/bench
// FORMATS.md, W9 `world2d_mixed_20k.txt`: 20,000 moving circles, boxes, capsules and polygons
// and 44 static walls), beside Box2D 2.4's collision part of a world step.
//
//   World2d/world2d_mixed_20k/<broadphase>/threads:<n>
//     one iteration = one frame of 1..F (cycling): every moving object moved to its frame-k
//     pose (W9 motion rule), then CollisionWorld::step (broad phase, narrow phase with
//     manifolds, events; continuous detection off: the W9 rule teleports objects through the
//     fold). The world is built at frame 0 before timing.
//     counters   pairs (touching pairs per frame, from the step's events)
//
//   World2d/world2d_mixed_20k/box2d            (only where PROXIMA_HAVE_BOX2D is set)
//     a b2World (zero gravity, sleeping off, never stepped): moving objects as dynamic
//     bodies, walls as static bodies, one fixture each (box2d_fixture_shape below).
//     One iteration = one frame of 1..F (cycling): every moving body SetTransform to its
//     frame-k pose (same W9 rule; this moves its broad-phase proxy), then the contact
//     manager's FindNewContacts (broad phase UpdatePairs, new b2Contacts) and Collide
//     (fat-AABB overlap check, b2Contact::Update: manifolds, touching flags, listener calls).
//     b2World::Step is not run: its solver is no part of the collision step.
//     counters   pairs (touching contacts per frame, b2Contact::IsTouching, counted with the
//                timer paused), contacts (b2Contacts per frame: fat AABBs overlap)

#include <proxima/d2/collision_world.hpp>

#include <memory>
#include <string>
#include <vector>

#include "bench_main.hpp"
#include "support/world2d_workloads.hpp"

#ifdef PROXIMA_HAVE_BOX2D
#include <box2d/box2d.h>
#include <cmath>
#include <numbers>

#include "support/box2d_peers.hpp"
#endif

namespace pb = proxima::bench;
namespace d2 = proxima::d2;

namespace {

/// The W9 world and its objects' 2D shapes.
struct Scene {
  pb::World2d world;
  std::vector<d2::Shape> shapes;
};

/// One timed frame of the Proxima case: every moving object moved to its pose at `frame`,
/// then the world's step.
[[gnu::noinline]] void step_proxima_frame(d2::CollisionWorld& world, const Scene& scene,
                                          const std::vector<d2::ObjectHandle>& handles, int frame,
                                          proxima::Executor& executor) {
  for (std::size_t i = 0; i < handles.size(); ++i) {
    if (!scene.world.objects[i].is_static) {
      world.move(handles[i], pb::to_d2_pose(pb::pose2d_at_frame(scene.world, i, frame)));
    }
  }
  world.step(executor);
}

void run_world2d(benchmark::State& state, const Scene* scene, const std::string& broadphase, std::size_t threads) {
  proxima::WorldSettings settings;
  settings.broadphase = broadphase;
  settings.continuous = false;
  d2::CollisionWorld world = d2::CollisionWorld::create(settings).value();
  const std::size_t n = scene->world.objects.size();
  std::vector<d2::ObjectHandle> handles;
  for (std::size_t i = 0; i < n; ++i) {
    const pb::World2dObject& o = scene->world.objects[i];
    d2::ObjectDesc desc{scene->shapes[i], pb::to_d2_pose(pb::pose2d_at_frame(scene->world, i, 0))};
    desc.kind = o.is_static ? d2::ObjectKind::Static : d2::ObjectKind::Moving;
    handles.push_back(world.add(desc).value());
  }
  proxima::ThreadPool pool(threads);
  proxima::Executor& executor = threads == 1 ? static_cast<proxima::Executor&>(proxima::serial_executor()) : pool;
  world.step(executor);
  int frame = 0;
  double pairs = 0;
  std::int64_t frames = 0;
  for (auto _ : state) {
    frame = frame % scene->world.frames + 1;
    step_proxima_frame(world, *scene, handles, frame, executor);
    pairs += static_cast<double>(world.events().begin.size() + world.events().persist.size());
    ++frames;
  }
  state.counters["pairs"] = frames > 0 ? pairs / static_cast<double>(frames) : 0;
}

#ifdef PROXIMA_HAVE_BOX2D

/// Half width of the thin box that stands for a capsule's segment in Box2D, which has no
/// capsule (and whose two-sided b2EdgeShape never pairs with another edge in a world).
constexpr float kCapsuleHalfWidth = b2_linearSlop;

/// A W9 world shape in the form box2d_peers.hpp reads.
pb::Polygons2dShape to_polygons2d(const pb::World2dShape& s) {
  pb::Polygons2dShape out;
  using K = pb::World2dShapeKind;
  using P = pb::Polygons2dKind;
  out.kind = s.kind == K::Circle      ? P::Circle
             : s.kind == K::Capsule2d ? P::Capsule
             : s.kind == K::Segment2d ? P::Segment
             : s.kind == K::Polygon   ? P::Polygon
                                      : P::Box;
  out.radius = s.radius;
  out.half_x = s.half_extents.x;
  out.half_y = s.half_extents.y;
  out.count = static_cast<int>(s.points.size());
  for (std::size_t i = 0; i < s.points.size(); ++i) out.vertices[i] = {s.points[i].x, s.points[i].y};
  return out;
}

/// The Box2D form of a W9 shape: box2d_peers.hpp's (circle -> b2CircleShape; polygon, box ->
/// b2PolygonShape with m_radius = rounding + b2_polygonRadius; segment -> two-sided
/// b2EdgeShape, m_radius = b2_polygonRadius), except a capsule of radius r: the box of its
/// segment, kCapsuleHalfWidth (h) thick on each side, with m_radius = r + b2_polygonRadius - h,
/// so lying between the capsules of radius r + skin - h and r + skin (exact across the
/// segment, at most h short towards the ends' diagonals).
pb::Box2dShape box2d_form(const pb::World2dShape& s) {
  pb::Box2dShape b = pb::make_box2d_shape(to_polygons2d(s), pb::Polygons2dPose{});
  if (s.kind != pb::World2dShapeKind::Capsule2d) return b;
  const b2Vec2 p = b.vertices[0], q = b.vertices[1], d = q - p;
  b.polygon.SetAsBox(0.5f * d.Length(), kCapsuleHalfWidth, 0.5f * (p + q), std::atan2(d.y, d.x));
  b.polygon.m_radius = b.radius + b2_polygonRadius - kCapsuleHalfWidth;
  b.kind = pb::Box2dShape::Polygon;
  return b;
}

/// The b2Shape of `b` that a fixture copies.
const b2Shape* fixture_shape(const pb::Box2dShape& b) {
  if (b.kind == pb::Box2dShape::Circle) return &b.circle;
  if (b.kind == pb::Box2dShape::Polygon) return &b.polygon;
  return &b.edge;
}

/// A W9 angle as a body angle: wrapped to [-pi, pi] in double, then rounded to float.
float box2d_angle(double angle) { return static_cast<float>(std::remainder(angle, 2 * std::numbers::pi)); }

/// The b2World of the W9 objects at frame 0: zero gravity, sleeping off, one body and
/// fixture (density 0) per object, `bodies[i]` = object i.
std::unique_ptr<b2World> make_box2d_world(const pb::World2d& w, std::vector<b2Body*>& bodies) {
  auto world = std::make_unique<b2World>(b2Vec2(0.0f, 0.0f));
  world->SetAllowSleeping(false);
  for (std::size_t i = 0; i < w.objects.size(); ++i) {
    const pb::Pose2d pose = pb::pose2d_at_frame(w, i, 0);
    b2BodyDef def;
    def.type = w.objects[i].is_static ? b2_staticBody : b2_dynamicBody;
    def.allowSleep = false;
    def.position.Set(static_cast<float>(pose.position.x), static_cast<float>(pose.position.y));
    def.angle = box2d_angle(pose.angle);
    bodies.push_back(world->CreateBody(&def));
    const pb::Box2dShape shape = box2d_form(w.objects[i].shape);
    bodies.back()->CreateFixture(fixture_shape(shape), 0.0f);
  }
  return world;
}

/// The contact manager of `world` (b2World only gives it const; FindNewContacts and
/// Collide are public members of b2ContactManager in 2.4).
b2ContactManager& contact_manager(b2World& world) { return const_cast<b2ContactManager&>(world.GetContactManager()); }

/// One timed frame of the Box2D case: every moving body SetTransform to its pose at
/// `frame`, then the contact manager's FindNewContacts and Collide.
[[gnu::noinline]] void step_box2d_frame(b2World& world, const pb::World2d& w, const std::vector<b2Body*>& bodies,
                                        int frame) {
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    if (w.objects[i].is_static) continue;
    const pb::Pose2d pose = pb::pose2d_at_frame(w, i, frame);
    bodies[i]->SetTransform(b2Vec2(static_cast<float>(pose.position.x), static_cast<float>(pose.position.y)),
                            box2d_angle(pose.angle));
  }
  contact_manager(world).FindNewContacts();
  contact_manager(world).Collide();
}

/// Number of the world's contacts that are touching (b2Contact::IsTouching).
std::size_t touching_contacts(b2World& world) {
  std::size_t n = 0;
  for (const b2Contact* c = world.GetContactList(); c != nullptr; c = c->GetNext()) n += c->IsTouching() ? 1 : 0;
  return n;
}

void run_box2d(benchmark::State& state, const Scene* scene) {
  std::vector<b2Body*> bodies;
  const std::unique_ptr<b2World> world = make_box2d_world(scene->world, bodies);
  contact_manager(*world).FindNewContacts();
  contact_manager(*world).Collide();
  int frame = 0;
  double pairs = 0, contacts = 0;
  std::int64_t frames = 0;
  for (auto _ : state) {
    frame = frame % scene->world.frames + 1;
    step_box2d_frame(*world, scene->world, bodies, frame);
    state.PauseTiming();
    pairs += static_cast<double>(touching_contacts(*world));
    contacts += static_cast<double>(world->GetContactCount());
    ++frames;
    state.ResumeTiming();
  }
  const double f = frames > 0 ? static_cast<double>(frames) : 1;
  state.counters["pairs"] = pairs / f;
  state.counters["contacts"] = contacts / f;
}

#endif  // PROXIMA_HAVE_BOX2D

bool register_world2d(const std::string& dir) {
  static Scene scene;
  auto read = pb::read_world2d(pb::workload_path(dir, "world2d_mixed_20k.txt"));
  if (!read) return pb::report_load_error(read.error());
  scene.world = std::move(read).value();
  for (const pb::World2dObject& o : scene.world.objects) {
    auto shape = pb::to_d2_shape(o.shape);
    if (!shape) return pb::report_load_error(shape.error());
    scene.shapes.push_back(std::move(shape).value());
  }
  for (const char* broadphase : {"tree", "sap", "grid", "mbp"}) {
    for (const std::size_t threads : {std::size_t(1), std::size_t(2)}) {
      const std::string name = "World2d/" + scene.world.name + "/" + broadphase + "/threads:" + std::to_string(threads);
      benchmark::RegisterBenchmark(name.c_str(), run_world2d, &scene, std::string(broadphase), threads)
          ->Unit(benchmark::kMillisecond)
          ->UseRealTime();
    }
  }
#ifdef PROXIMA_HAVE_BOX2D
  const std::string name = "World2d/" + scene.world.name + "/box2d";
  benchmark::RegisterBenchmark(name.c_str(), run_box2d, &scene)->Unit(benchmark::kMillisecond)->UseRealTime();
#endif
  return true;
}

}  // namespace

int main(int argc, char** argv) { return pb::run_benchmarks(argc, argv, register_world2d); }
