// The W9 2D pair reader (support/polygons2d_workloads.hpp): the shared file read in full
// (its first record field by field, every pair converted to the 2D module's shapes), and
// malformed records rejected with an Error naming "<file>:<line>" and what is wrong.
#include <gtest/gtest.h>

#include "support/polygons2d_workloads.hpp"
#include "workload_test_util.hpp"

namespace proxima::bench {
namespace test_polygons2d_readers {

using test_util::temp_file;

template <class R>
void expect_error(const R& result, const std::string& where, const std::string& what) {
  ASSERT_FALSE(result.ok()) << "accepted a malformed file (" << what << ")";
  const std::string message = result.error().what();
  EXPECT_NE(message.find(where), std::string::npos) << message;
  EXPECT_NE(message.find(what), std::string::npos) << message;
}

TEST(Polygons2dReader, SharedFileReadsAndConverts) {
  const std::string dir = test_util::shared_dir();
  if (dir.empty()) GTEST_SKIP() << "shared workloads not found in " << workload_dir();
  const auto pairs = read_polygons2d_pairs(workload_path(dir, "polygons2d_pairs.txt"));
  ASSERT_TRUE(pairs.ok()) << pairs.error().what();
  ASSERT_EQ(pairs->size(), 20000u);
  // Line 2: box2d 0.908 0.851 0.079 | -1.485 -1.072 2.0136 | polygon 3 -0.267 0.717 -0.451
  // -0.496 0.446 -0.579 0 | -2.497 -1.208 -1.7655
  const Polygons2dPair& first = pairs->front();
  EXPECT_EQ(first.a.kind, Polygons2dKind::Box);
  EXPECT_EQ(first.a.half_x, 0.908);
  EXPECT_EQ(first.a.half_y, 0.851);
  EXPECT_EQ(first.a.radius, 0.079);
  EXPECT_EQ(first.pose_a.angle, 2.0136);
  EXPECT_EQ(first.b.kind, Polygons2dKind::Polygon);
  EXPECT_EQ(first.b.count, 3);
  EXPECT_EQ(first.b.vertices[2][1], -0.579);
  EXPECT_EQ(first.b.radius, 0.0);
  EXPECT_EQ(first.pose_b.x, -2.497);
  const auto shapes = to_d2_pairs(*pairs);
  ASSERT_TRUE(shapes.ok()) << shapes.error().what();
  EXPECT_EQ(shapes->front().a.type(), d2::ShapeType::Polygon);
  EXPECT_EQ(std::get<d2::Polygon>(shapes->front().a.variant()).count(), 4);
  EXPECT_EQ(shapes->front().pose_b.position.y, Real(-1.208));
}

TEST(Polygons2dReader, MalformedRecordsNameTheLine) {
  const std::string header = "polygons2d_pairs 1 count=1\n";
  const std::string pose = " | 0 0 0 | ";
  const auto file = [&](const std::string& name, const std::string& record) {
    return temp_file(name, header + record + "\n");
  };
  std::string p = file("w9_fields.txt", "circle 1 | 0 0 0 | circle 1");
  expect_error(read_polygons2d_pairs(p), p + ":2", "expected 4 fields");
  p = file("w9_unknown.txt", "ellipse 1" + pose + "circle 1 | 0 0 0");
  expect_error(read_polygons2d_pairs(p), p + ":2", "unknown shape 'ellipse'");
  p = file("w9_polygon_n.txt", "polygon 9 0 0 1 0 1 1 0 1 0 0 0 0 0 0 0 0 0 0 0" + pose + "circle 1 | 0 0 0");
  expect_error(read_polygons2d_pairs(p), p + ":2", "vertex count must be in 3..8");
  p = file("w9_polygon_tokens.txt", "polygon 3 0 0 1 0 1 1" + pose + "circle 1 | 0 0 0");
  expect_error(read_polygons2d_pairs(p), p + ":2", "expected 9 fields");
  p = file("w9_radius.txt", "box2d 1 1 -0.1" + pose + "circle 1 | 0 0 0");
  expect_error(read_polygons2d_pairs(p), p + ":2", "box radius must be >= 0");
  p = file("w9_capsule.txt", "capsule2d 0 0 1 0 0" + pose + "circle 1 | 0 0 0");
  expect_error(read_polygons2d_pairs(p), p + ":2", "capsule radius must be > 0");
  p = file("w9_pose.txt", "circle 1 | 0 0 | circle 1 | 0 0 0");
  expect_error(read_polygons2d_pairs(p), p + ":2", "x y angle");
  p = temp_file("w9_count.txt", "polygons2d_pairs 1 count=2\ncircle 1 | 0 0 0 | circle 1 | 0 0 0\n");
  expect_error(read_polygons2d_pairs(p), p, "file ends after 1 of the 2 pairs");
}

TEST(Polygons2dReader, DegenerateShapesFailToConvert) {
  const std::string p = temp_file("w9_degenerate.txt",
                                  "polygons2d_pairs 1 count=1\n"
                                  "circle 1 | 0 0 0 | segment2d 1 1 1 1 | 0 0 0\n");
  const auto pairs = read_polygons2d_pairs(p);
  ASSERT_TRUE(pairs.ok()) << pairs.error().what();
  const auto shapes = to_d2_pairs(*pairs);
  ASSERT_FALSE(shapes.ok());
  EXPECT_EQ(shapes.error().field.rfind("pairs[0].b", 0), 0u) << shapes.error().what();
}

}  // namespace test_polygons2d_readers
}  // namespace proxima::bench
