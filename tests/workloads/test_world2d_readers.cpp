// The W9 2D world reader (support/world2d_workloads.hpp) on the shared file: the record
// counts against MANIFEST.txt, a record against the file text, the motion rule against
// FORMATS.md's worked example, and malformed input.
#include <gtest/gtest.h>

#include "support/world2d_workloads.hpp"
#include "support/world_workloads.hpp"
#include "workload_test_util.hpp"

namespace proxima::bench {
namespace test_world2d_readers {

using namespace test_util;

TEST(World2dReaders, MixedWorldCounts) {
  const std::string dir = shared_dir();
  if (dir.empty()) GTEST_SKIP() << "shared workloads not found in " << workload_dir();
  const auto w = read_world2d(workload_path(dir, "world2d_mixed_20k.txt"));
  ASSERT_TRUE(w.ok()) << w.error().what();
  EXPECT_EQ(w->name, "world2d_mixed_20k");
  EXPECT_EQ(w->frames, 100);
  EXPECT_EQ(w->dt, 0.016666666666666666);
  EXPECT_EQ(w->lo, (Vec2d{0, 0}));
  EXPECT_EQ(w->hi, (Vec2d{298, 149}));
  // MANIFEST.txt: 8116 circle / 4929 box2d / 3958 capsule2d / 2997 polygon moving, 44 static segments.
  long long counts[5] = {0, 0, 0, 0, 0};
  long long statics = 0;
  for (const World2dObject& o : w->objects) {
    if (o.is_static) {
      ++statics;
      EXPECT_EQ(o.shape.kind, World2dShapeKind::Segment2d);
      continue;
    }
    ++counts[static_cast<int>(o.shape.kind)];
  }
  EXPECT_EQ(statics, 44);
  EXPECT_EQ(counts[int(World2dShapeKind::Circle)], 8116);
  EXPECT_EQ(counts[int(World2dShapeKind::Box2d)], 4929);
  EXPECT_EQ(counts[int(World2dShapeKind::Capsule2d)], 3958);
  EXPECT_EQ(counts[int(World2dShapeKind::Polygon)], 2997);
  // Record 9: "polygon 4 -0.004 0.631 -0.178 0.626 -0.314 0.514 0.186 -0.622 0 | 265.327 118.814 -0.5635 |
  // 2.798 -0.522 -1.261".
  const World2dObject& p = w->objects[9];
  ASSERT_EQ(p.shape.points.size(), 4u);
  EXPECT_EQ(p.shape.points[3], (Vec2d{0.186, -0.622}));
  EXPECT_EQ(p.shape.radius, 0);
  EXPECT_EQ(p.pose.angle, -0.5635);
  EXPECT_EQ(p.velocity, (Vec2d{2.798, -0.522}));
  EXPECT_EQ(p.angular_velocity, -1.261);
}

TEST(World2dReaders, MotionRuleWorkedExample) {
  // FORMATS.md: object 44, `44 moving box2d 0.631 0.543 0 | 296.992 57.868 1.3555 | 0.699 -0.272 1.87`,
  // at frame 100: x = 298.157 folds to 297.843, y = 57.414666667, angle = 4.472166667.
  World2dObject o;
  o.id = 44;
  o.shape.kind = World2dShapeKind::Box2d;
  o.pose = {{296.992, 57.868}, 1.3555};
  o.velocity = {0.699, -0.272};
  o.angular_velocity = 1.87;
  const Pose2d p = pose2d_at_time(o, frame_time(100, 0.016666666666666666), {0, 0}, {298, 149});
  EXPECT_NEAR(p.position.x, 297.843, 5e-10);
  EXPECT_NEAR(p.position.y, 57.414666667, 5e-10);
  EXPECT_NEAR(p.angle, 4.472166667, 5e-10);
  o.is_static = true;
  const Pose2d s = pose2d_at_time(o, 1.5, {0, 0}, {298, 149});
  EXPECT_EQ(s.position, o.pose.position);
  EXPECT_EQ(s.angle, o.pose.angle);
}

TEST(World2dReaders, MalformedInput) {
  const std::string header = "world2d 1 name=t objects=2 frames=10 dt=0.1 lo=0,0 hi=10,10\n";
  const std::string good0 = "0 moving polygon 3 0 0 1 0 0 1 0.1 | 1 2 0.5 | 1 0 2\n";
  const std::string good1 = "1 static segment2d 0 0 10 0 | 0 0 0 | 0 0 0\n";
  {
    const auto w = read_world2d(temp_file("world2d_good.txt", header + "# comment\n\n" + good0 + good1));
    ASSERT_TRUE(w.ok()) << w.error().what();
    EXPECT_EQ(w->objects.size(), 2u);
    EXPECT_EQ(w->objects[0].shape.radius, 0.1);
    EXPECT_EQ(w->objects[1].shape.points[1], (Vec2d{10, 0}));
  }
  struct Case {
    const char* name;
    std::string text;
    const char* line;
    const char* message;
  };
  const Case cases[] = {
      {"world2d_kind.txt", "world 1 objects=0\n", ":1", "wrong kind"},
      {"world2d_lo.txt", "world2d 1 objects=0 frames=1 dt=1 lo=0,0,0 hi=1,1\n", ":1", "lo="},
      {"world2d_order.txt", header + good1 + good0, ":2", "out of order"},
      {"world2d_polygon.txt", header + "0 moving polygon 2 0 0 1 0 0 | 1 2 0.5 | 1 0 2\n" + good1, ":2", "3..8"},
      {"world2d_radius.txt", header + "0 moving circle -1 | 1 2 0.5 | 1 0 2\n" + good1, ":2", "radius"},
      {"world2d_static_speed.txt", header + good0 + "1 static segment2d 0 0 1 0 | 0 0 0 | 0 0 1\n", ":3", "velocities"},
      {"world2d_shape.txt", header + "0 moving ellipse 1 2 | 1 2 0 | 1 0 2\n" + good1, ":2", "unknown shape"},
      {"world2d_short.txt", header + good0, ":2", "file ends"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    const std::string path = temp_file(c.name, c.text);
    const auto w = read_world2d(path);
    ASSERT_FALSE(w.ok());
    EXPECT_EQ(w.error().field, path + c.line);
    EXPECT_NE(w.error().message.find(c.message), std::string::npos) << w.error().message;
  }
}

}  // namespace test_world2d_readers
}  // namespace proxima::bench
