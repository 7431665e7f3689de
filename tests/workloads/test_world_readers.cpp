// The W8 readers (support/world_workloads.hpp) on the shared files: record counts against
// the header and MANIFEST.txt, the first and last records against the file text (parsed
// separately with strtod), the motion rule against FORMATS.md's worked example, the
// conversion to library shapes, the world_bullets_expected reader, and malformed input.
#include <gtest/gtest.h>

#include <proxima/shapes/shape_queries.hpp>

#include <cstdio>

#include "support/world_workloads.hpp"
#include "workload_test_util.hpp"

namespace proxima::bench {
namespace test_world_readers {

using namespace test_util;

/// The shared folder, or "" (the tests then skip).
std::string dir_or_skip() { return shared_dir(); }

/// MANIFEST.txt's notes for `file`.
std::string notes(const std::string& dir, const std::string& file) {
  const auto manifest = read_manifest(dir);
  const auto it = manifest.find(file);
  EXPECT_NE(it, manifest.end()) << file;
  return it == manifest.end() ? std::string() : it->second.notes;
}

struct Counts {
  long long moving = 0, spheres = 0, boxes = 0, capsules = 0, hulls = 0, statics = 0;
};

Counts count(const World& w) {
  Counts c;
  for (const WorldObject& o : w.objects) {
    if (o.is_static) {
      ++c.statics;
      continue;
    }
    ++c.moving;
    c.spheres += o.shape.kind == WorldShapeKind::Sphere;
    c.boxes += o.shape.kind == WorldShapeKind::Box;
    c.capsules += o.shape.kind == WorldShapeKind::Capsule;
    c.hulls += o.shape.kind == WorldShapeKind::Hull;
  }
  return c;
}

TEST(WorldReaders, EveryWorldFile) {
  const std::string dir = dir_or_skip();
  if (dir.empty()) GTEST_SKIP() << "shared workloads not found in " << workload_dir();
  struct Case {
    const char* file;
    long long statics;
  };
  for (const Case c : {Case{"world_mixed_10k.txt", 6}, Case{"world_terrain.txt", 1}, Case{"world_bullets.txt", 200},
                       Case{"world_level_40k.txt", 40001}}) {
    SCOPED_TRACE(c.file);
    const std::string note = notes(dir, c.file);
    const auto w = read_world_workload(dir, c.file);
    ASSERT_TRUE(w.ok()) << w.error().what();
    const World& world = w->world;
    EXPECT_EQ(world.name + ".txt", c.file);
    EXPECT_EQ(world.dt, 1.0 / 60);
    EXPECT_EQ(world.hulls_file, "convex_shapes_32.txt");
    EXPECT_EQ(w->hulls.shapes.size(), 200u);
    const Counts n = count(world);
    EXPECT_EQ(n.moving, capture(note, R"((\d+) moving)"));
    EXPECT_EQ(n.statics, c.statics);
    if (n.hulls > 0) {
      EXPECT_EQ(n.spheres, capture(note, R"((\d+) spheres)"));
      EXPECT_EQ(n.boxes, capture(note, R"((\d+) boxes)"));
      EXPECT_EQ(n.capsules, capture(note, R"((\d+) capsules)"));
      EXPECT_EQ(n.hulls, capture(note, R"((\d+) hulls)"));
    }
    // The first and last records against the text.
    const auto text = read_lines(workload_path(dir, c.file));
    ASSERT_EQ(text.size(), world.objects.size() + 1);
    for (const std::size_t i : {std::size_t{0}, world.objects.size() - 1}) {
      const WorldObject& o = world.objects[i];
      const auto v = numbers(text[i + 1]);
      ASSERT_GE(v.size(), 14u);
      EXPECT_EQ(o.id, static_cast<std::uint32_t>(v[0]));
      const std::size_t at = v.size() - 13;  // pose (7) and velocities (6) close the line
      if (o.shape.kind != WorldShapeKind::HalfSpace) {
        const Pose p = pose_at(v, at);
        EXPECT_EQ(o.pose.position, p.position);
        EXPECT_EQ(o.pose.rotation, p.rotation);
      }
      EXPECT_EQ(o.velocity, (Vec3d{v[at + 7], v[at + 8], v[at + 9]}));
      EXPECT_EQ(o.angular_velocity, (Vec3d{v[at + 10], v[at + 11], v[at + 12]}));
    }
    for (const WorldObject& o : world.objects) {
      ASSERT_LT(unit_error(o.pose.rotation), 1e-14) << o.id;
      // Frame 0 is fold(p0): p0 up to rounding.
      const Pose p = pose_at_frame(world, o.id, 0);
      for (int a = 0; a < 3; ++a) ASSERT_NEAR(p.position[a], o.pose.position[a], 1e-13 * (1 + std::abs(p.position[a])));
      ASSERT_NEAR(p.rotation.w, o.pose.rotation.w, 1e-15);
      if (o.is_static) {
        const Pose last = pose_at_frame(world, o.id, world.frames);
        ASSERT_EQ(last.position, o.pose.position);
        ASSERT_EQ(last.rotation, o.pose.rotation);
      }
    }
  }
}

TEST(WorldReaders, MotionRuleWorkedExample) {
  // FORMATS.md: object 3 of world_mixed_10k at frames 100 and 37, 9 decimals.
  WorldObject o;
  o.id = 3;
  o.shape.kind = WorldShapeKind::Box;
  o.pose.position = {4.384, 8.479, 0.645};
  const double q[4] = {0.26268, -0.58658, 0.6821, 0.34881};
  const double len = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
  o.pose.rotation = {q[0] / len, q[1] / len, q[2] / len, q[3] / len};
  o.velocity = {-1.214, 0.201, -1.3};
  o.angular_velocity = {0.108, -0.224, 0.025};
  const Vec3d lo{0, 0, 0}, hi{34, 34, 34};
  const double dt = 0.016666666666666666;
  const double expected[2][7] = {
      {2.360666667, 8.814000000, 1.521666667, 0.428605714, -0.629180390, 0.575378978, 0.298945161},
      {3.635366667, 8.602950000, 0.156666667, 0.325790955, -0.605418798, 0.645828389, 0.332015097}};
  const int frames[2] = {100, 37};
  for (int c = 0; c < 2; ++c) {
    SCOPED_TRACE("frame " + std::to_string(frames[c]));
    const Pose p = pose_at_time(o, frame_time(frames[c], dt), lo, hi);
    const double got[7] = {p.position.x, p.position.y, p.position.z, p.rotation.w,
                           p.rotation.x, p.rotation.y, p.rotation.z};
    for (int i = 0; i < 7; ++i) EXPECT_NEAR(got[i], expected[c][i], 5e-10) << "component " << i;
  }
  // The same object read from the file gives the same poses.
  const std::string dir = dir_or_skip();
  if (dir.empty()) return;
  const auto w = read_world(workload_path(dir, "world_mixed_10k.txt"));
  ASSERT_TRUE(w.ok()) << w.error().what();
  const WorldObject& read = w->objects[3];
  EXPECT_EQ(read.pose.position, o.pose.position);
  EXPECT_EQ(read.pose.rotation, o.pose.rotation);
  EXPECT_EQ(read.velocity, o.velocity);
  EXPECT_EQ(read.angular_velocity, o.angular_velocity);
  EXPECT_EQ(w->dt, dt);
  for (const int frame : frames) {
    const Pose a = pose_at_frame(*w, 3, frame);
    const Pose b = pose_at_time(o, frame_time(frame, dt), lo, hi);
    EXPECT_EQ(a.position, b.position);
    EXPECT_EQ(a.rotation, b.rotation);
  }
}

TEST(WorldReaders, FoldIsATriangleWave) {
  EXPECT_EQ(fold_coordinate(5, 0, 34), 5);
  EXPECT_EQ(fold_coordinate(-1.5, 0, 34), 1.5);   // reflected at lo
  EXPECT_EQ(fold_coordinate(35, 0, 34), 33);      // reflected at hi
  EXPECT_EQ(fold_coordinate(69, 0, 34), 1);       // one period on
  EXPECT_EQ(fold_coordinate(-70, 0, 34), 2);      // fmod < 0: + period
  EXPECT_EQ(fold_coordinate(34, 0, 34), 34);      // u == W stays
  EXPECT_EQ(fold_coordinate(-52, -50, 50), -48);  // lo != 0
  EXPECT_EQ(fold_coordinate(1.25, -1, 1), 0.75);  // narrow box (world_terrain's z)
}

TEST(WorldReaders, LibraryShapes) {
  const std::string dir = dir_or_skip();
  if (dir.empty()) GTEST_SKIP() << "shared workloads not found in " << workload_dir();
  for (const char* file : {"world_mixed_10k.txt", "world_terrain.txt"}) {
    SCOPED_TRACE(file);
    const auto w = read_world_workload(dir, file);
    ASSERT_TRUE(w.ok()) << w.error().what();
    const auto shapes = to_shapes(*w);
    ASSERT_TRUE(shapes.ok()) << shapes.error().what();
    ASSERT_EQ(shapes->size(), w->world.objects.size());
    for (std::size_t i = 0; i < shapes->size(); ++i) {
      const WorldShape& s = w->world.objects[i].shape;
      const Shape& lib = (*shapes)[i];
      switch (s.kind) {
        case WorldShapeKind::Sphere: ASSERT_EQ(std::get<Sphere>(lib).radius(), Real(s.radius)); break;
        case WorldShapeKind::Box: ASSERT_EQ(std::get<Box>(lib).half_extents(), to_vec3(s.half_extents)); break;
        case WorldShapeKind::Capsule: {
          // Same axis convention: the segment (0,0,-hl)-(0,0,hl) of the local z axis.
          const Capsule& c = std::get<Capsule>(lib);
          ASSERT_EQ(c.radius(), Real(s.radius));
          ASSERT_EQ(c.top(), Vec3(Real(0), Real(0), Real(s.half_length)));
          const Aabb box = world_aabb(lib, Transform::identity());
          ASSERT_NEAR(double(box.max.z), s.half_length + s.radius, 1e-6);
          ASSERT_NEAR(double(box.max.x), s.radius, 1e-6);
          break;
        }
        case WorldShapeKind::Hull: {
          const ConvexHull& h = std::get<ConvexHull>(lib);
          ASSERT_GE(h.vertices().size(), 4u);
          ASSERT_LE(h.vertices().size(), w->hulls.shapes[s.hull].points.size());
          break;
        }
        case WorldShapeKind::Mesh: {
          const TriangleMesh& m = std::get<TriangleMesh>(lib);
          EXPECT_EQ(m.triangle_count(), 80000u);
          EXPECT_EQ(m.vertices().size(), 40401u);
          break;
        }
        case WorldShapeKind::HalfSpace: {
          // {x : n.x <= d} in the world, as proxima's HalfSpace at the identity.
          const HalfSpace& h = std::get<HalfSpace>(lib);
          const WorldObject& o = w->world.objects[i];
          const Transform t = world_transform(o, pose_at_frame(w->world, i, 0));
          EXPECT_EQ(t.position, Vec3(Real(0)));
          EXPECT_EQ(h.normal(), to_vec3(s.normal));
          EXPECT_EQ(h.offset(), Real(s.offset));
          EXPECT_TRUE(h.contains(
              to_vec3(Vec3d{s.normal.x * (s.offset - 1), s.normal.y * (s.offset - 1), s.normal.z * (s.offset - 1)})));
          EXPECT_FALSE(h.contains(
              to_vec3(Vec3d{s.normal.x * (s.offset + 1), s.normal.y * (s.offset + 1), s.normal.z * (s.offset + 1)})));
          break;
        }
      }
    }
  }
}

TEST(WorldReaders, BulletsExpected) {
  const std::string dir = dir_or_skip();
  if (dir.empty()) GTEST_SKIP() << "shared workloads not found in " << workload_dir();
  const std::string file = "world_bullets_expected.txt";
  const auto e = read_bullets_expected(workload_path(dir, file));
  ASSERT_TRUE(e.ok()) << e.error().what();
  EXPECT_EQ(e->world_file, "world_bullets.txt");
  ASSERT_EQ(e->contacts.size(), 1000u);
  long long hits = 0;
  for (std::size_t i = 0; i < e->contacts.size(); ++i) {
    const BulletContact& c = e->contacts[i];
    EXPECT_EQ(c.sphere, i);
    if (!c.hit) {
      EXPECT_EQ(c.interval, -1);
      continue;
    }
    ++hits;
    EXPECT_GE(c.interval, 0);
    EXPECT_LT(c.interval, 60);
    EXPECT_GE(c.plate, 1000u);
    EXPECT_LT(c.plate, 1200u);
  }
  EXPECT_EQ(hits, capture(notes(dir, file), R"((\d+) of 1000 spheres hit)"));
  const auto text = read_lines(workload_path(dir, file));
  const auto first = numbers(text[1]);
  ASSERT_EQ(first.size(), 4u);
  EXPECT_EQ(e->contacts[0].s, first[2]);
}

TEST(WorldReaders, MalformedInput) {
  const std::string header = "world 1 name=t objects=2 frames=10 dt=0.1 lo=0,0,0 hi=10,10,10 hulls=h.txt\n";
  const std::string good0 = "0 moving sphere 0.5 | 1 2 3 1 0 0 0 | 1 0 0 0 0 1\n";
  const std::string good1 = "1 static halfspace 0 0 1 0 | 0 0 0 1 0 0 0 | 0 0 0 0 0 0\n";
  {
    const auto w = read_world(temp_file("world_good.txt", header + "# comment\n\n" + good0 + good1));
    ASSERT_TRUE(w.ok()) << w.error().what();
    EXPECT_EQ(w->objects.size(), 2u);
    EXPECT_EQ(w->hi, (Vec3d{10, 10, 10}));
    EXPECT_EQ(w->objects[1].shape.normal, (Vec3d{0, 0, 1}));
  }
  struct Case {
    const char* name;
    std::string text;
    const char* line;
    const char* message;
  };
  const Case cases[] = {
      {"world_kind.txt", "broadphase 1 n=1\n", ":1", "wrong kind"},
      {"world_lo.txt", "world 1 objects=0 frames=1 dt=1 lo=0,0 hi=1,1,1 hulls=h\n", ":1", "lo="},
      {"world_order.txt", header + good1 + good0, ":2", "out of order"},
      {"world_fields.txt", header + "0 moving sphere 0.5 | 1 2 3 1 0 0 0\n" + good1, ":2", "3 fields"},
      {"world_moving_plane.txt", header + good0 + "1 moving halfspace 0 0 1 0 | 0 0 0 1 0 0 0 | 0 0 0 0 0 0\n", ":3",
       "static"},
      {"world_static_speed.txt", header + good0 + "1 static box 1 1 1 | 0 0 0 1 0 0 0 | 1 0 0 0 0 0\n", ":3",
       "velocities"},
      {"world_shape.txt", header + "0 moving cone 1 | 1 2 3 1 0 0 0 | 1 0 0 0 0 1\n" + good1, ":2", "unknown shape"},
      {"world_short.txt", header + good0, ":2", "file ends"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    const std::string path = temp_file(c.name, c.text);
    const auto w = read_world(path);
    ASSERT_FALSE(w.ok());
    EXPECT_EQ(w.error().field, path + c.line);
    EXPECT_NE(w.error().message.find(c.message), std::string::npos) << w.error().message;
  }
  const std::string path = temp_file("bullets_bad.txt", "world_bullets_expected 1 count=1 world=w.txt\n0 3 1.5 7\n");
  const auto e = read_bullets_expected(path);
  ASSERT_FALSE(e.ok());
  EXPECT_EQ(e.error().field, path + ":2");
}

}  // namespace test_world_readers
}  // namespace proxima::bench
