// Malformed workload files are rejected with an Error naming "<file>:<line>" and what is
// wrong; blank and comment lines are skipped without losing the line count; unknown
// header keys are ignored; the workload folder is taken from --workloads= / the
// environment.
#include <gtest/gtest.h>

#include <cstdlib>
#include <support/polygons2d_workloads.hpp>
#include <support/world_workloads.hpp>

#include "workload_test_util.hpp"

namespace proxima::bench {
namespace test_malformed {

using test_util::temp_file;

/// Expects `result` to fail with an error mentioning `where` ("file:line") and `what`.
template <class R>
void expect_error(const R& result, const std::string& where, const std::string& what) {
  ASSERT_FALSE(result.ok()) << "accepted a malformed file (" << what << ")";
  const std::string message = result.error().what();
  EXPECT_NE(message.find(where), std::string::npos) << message;
  EXPECT_NE(message.find(what), std::string::npos) << message;
}

const char* kBoxLine = "0.5 0.5 0.5 0 0 0 1 0 0 0  0.5 0.5 0.5 1 0 0 0.7071 0 0.7071 0\n";

TEST(MalformedWorkloads, HeaderKindAndVersion) {
  std::string p = temp_file("unknown_kind.txt", std::string("foo 1 count=1\n") + kBoxLine);
  expect_error(read_box_pairs(p), p + ":1", "unknown kind 'foo'");
  p = temp_file("wrong_kind.txt", std::string("sphere_pairs 1 count=1 repeat=1\n") + kBoxLine);
  expect_error(read_box_pairs(p), p + ":1", "wrong kind 'sphere_pairs', expected 'box_pairs'");
  p = temp_file("version2.txt", std::string("box_pairs 2 count=1\n") + kBoxLine);
  expect_error(read_box_pairs(p), p + ":1", "unsupported version 2");
  expect_error(read_header(p), p + ":1", "unsupported version 2");
  p = temp_file("version_text.txt", std::string("box_pairs one count=1\n") + kBoxLine);
  expect_error(read_box_pairs(p), p + ":1", "version 'one'");
  p = temp_file("no_version.txt", "box_pairs\n");
  expect_error(read_box_pairs(p), p + ":1", "malformed header");
  p = temp_file("bad_key.txt", std::string("box_pairs 1 count\n") + kBoxLine);
  expect_error(read_box_pairs(p), p + ":1", "'count' is not key=value");
  p = temp_file("missing_key.txt", std::string("box_pairs 1 n=1\n") + kBoxLine);
  expect_error(read_box_pairs(p), p + ":1", "lacks the key count=");
  p = temp_file("bad_count.txt", std::string("box_pairs 1 count=-1\n") + kBoxLine);
  expect_error(read_box_pairs(p), p + ":1", "count=-1");
  p = temp_file("empty.txt", "");
  expect_error(read_box_pairs(p), p + ":1", "empty file");
  p = temp_file("leading_blank.txt", std::string("\nbox_pairs 1 count=1\n") + kBoxLine);
  expect_error(read_box_pairs(p), p + ":1", "malformed header");
  expect_error(read_box_pairs("/nonexistent/dir/box_pairs.txt"), "/nonexistent/dir/box_pairs.txt", "cannot open");
}

TEST(MalformedWorkloads, UnknownKeysAreIgnoredAndCommentsSkipped) {
  const std::string p =
      temp_file("comments.txt", std::string("box_pairs 1 count=2 generator=other seed=5\n") + "# a comment\n\n   \n" +
                                    kBoxLine + "  # indented comment\n" + kBoxLine + "\n");
  const auto pairs = read_box_pairs(p);
  ASSERT_TRUE(pairs.ok()) << pairs.error().what();
  ASSERT_EQ(pairs->size(), 2u);
  EXPECT_NEAR(pairs->back().pose_b.rotation.w, std::sqrt(0.5), 1e-12);  // 0.7071 normalised
  EXPECT_NEAR(test_util::unit_error(pairs->back().pose_b.rotation), 0, 1e-15);
  const auto header = read_header(p);
  ASSERT_TRUE(header.ok());
  EXPECT_EQ(header->kind, "box_pairs");
  EXPECT_EQ(header->keys.at("generator"), "other");
}

TEST(MalformedWorkloads, RecordErrorsNameTheLine) {
  std::string p = temp_file("short_line.txt", std::string("box_pairs 1 count=2\n# note\n") + kBoxLine + "1 2 3\n");
  expect_error(read_box_pairs(p), p + ":4", "expected 20 fields");
  p = temp_file("not_number.txt", "sphere_pairs 1 count=1 repeat=1\n1 2 abc 0.5 1 2 3 0.5\n");
  expect_error(read_sphere_pairs(p), p + ":2", "'abc' is not a number");
  p = temp_file("nan.txt", "sphere_pairs 1 count=1 repeat=1\n1 2 nan 0.5 1 2 3 0.5\n");
  expect_error(read_sphere_pairs(p), p + ":2", "'nan' is not a finite number");
  p = temp_file("inf.txt", "sphere_pairs 1 count=1 repeat=1\n1 2 3 inf 1 2 3 0.5\n");
  expect_error(read_sphere_pairs(p), p + ":2", "'inf' is not a finite number");
  p = temp_file("neg_radius.txt", "sphere_pairs 1 count=1 repeat=1\n1 2 3 -0.5 1 2 3 0.5\n");
  expect_error(read_sphere_pairs(p), p + ":2", "r1 must be > 0");
  p = temp_file("repeat0.txt", "sphere_pairs 1 count=1 repeat=0\n1 2 3 0.5 1 2 3 0.5\n");
  expect_error(read_sphere_pairs(p), p + ":1", "repeat= must be >= 1");
  p = temp_file("too_few.txt", "capsule_pairs 1 count=3 repeat=1\n0 0 0 1 0 0 0.1  0 1 0 1 1 0 0.1\n\n");
  expect_error(read_capsule_pairs(p), p + ":3", "file ends after 1 of the 3 records");
  p = temp_file("too_many.txt", "mesh_poses 1 count=1 a=x.obj b=y.obj\n0 0 0 1 0 0 0\n# c\n1 1 1 1 0 0 0\n");
  expect_error(read_mesh_poses(p), p + ":4", "more records than the header's count=1");
  p = temp_file("zero_quat.txt", "mesh_poses 1 count=1 a=x.obj b=y.obj\n0 0 0 0 0 0 0\n");
  expect_error(read_mesh_poses(p), p + ":2", "quaternion of zero length");
  p = temp_file("rays_zero_dir.txt", "rays 1 count=1 mesh=m.obj\n0 0 0 0 0 0 100\n");
  expect_error(read_rays(p), p + ":2", "zero ray direction");
  p = temp_file("rays_no_mesh.txt", "rays 1 count=1\n0 0 0 1 0 0 100\n");
  expect_error(read_rays(p), p + ":1", "lacks the key mesh=");
  p = temp_file("bp_half.txt", "broadphase 1 n=1 frames=1 dt=1 lo=0 hi=10\n1 1 1 -1 1 1 0 0 0\n");
  expect_error(read_broadphase(p), p + ":2", "half extents must be >= 0");
  p = temp_file("bp_lohi.txt", "broadphase 1 n=1 frames=1 dt=1 lo=10 hi=10\n1 1 1 1 1 1 0 0 0\n");
  expect_error(read_broadphase(p), p + ":1", "lo= must be smaller than hi=");
  p = temp_file("bp_ok.txt", "broadphase 1 n=1 frames=2 dt=1 lo=0 hi=10\n1 1 1 1 1 1 0 0 0\n");
  const auto ok = read_broadphase(p);
  ASSERT_TRUE(ok.ok()) << ok.error().what();
  EXPECT_EQ(ok->name, "bp_ok");  // no name= key: the file stem
}

// Fuzz finding (fuzz/corpus/workload_readers/regression_bullets_huge_count): a header count
// of 77777777777777773 was reserved before any record was read (std::length_error in the
// release build, an allocation-size abort under ASan). Counts now reserve no more than the
// bytes left to read, and reading stops at the file's end; count * repeat is capped.
TEST(MalformedWorkloads, HugeCountsReserveOnlyWhatTheFileHolds) {
  const std::string huge = "77777777777777773";
  std::string p = temp_file("bullets_huge.txt", "world_bullets_expected 1 count=" + huge +
                                                    " world=w.txt\n0 59 0.044720903 1024\n1 29 0.272580950 1151\n");
  expect_error(read_bullets_expected(p), p + ":3", "file ends after 2 of the " + huge + " records");
  p = temp_file("box_pairs_huge.txt", "box_pairs 1 count=" + huge + "\n" + kBoxLine);
  expect_error(read_box_pairs(p), p + ":2", "file ends after 1 of the " + huge + " records");
  p = temp_file("polygons_huge.txt", "polygons2d_pairs 1 count=" + huge + "\n");
  expect_error(read_polygons2d_pairs(p), p + ":1", "");
  p = temp_file("repeat_huge.txt", "sphere_pairs 1 count=2 repeat=8388609\n1 2 3 0.5 1 2 3 0.5\n1 2 3 0.5 1 2 3 0.5\n");
  expect_error(read_sphere_pairs(p), p + ":1", "count= * repeat= is more than kMaxWorkloadQueries (2^24)");
}

TEST(MalformedWorkloads, ConvexShapes) {
  std::string p = temp_file("shapes_order.txt",
                            "convex_shapes 1 count=2 points=1\nshape 0 1 1 1 1\n0 0 1\n"
                            "shape 2 1 1 1 1\n0 0 1\n");
  expect_error(read_convex_shapes(p), p + ":4", "shape id 2 out of order, expected 1");
  p = temp_file("shapes_points.txt", "convex_shapes 1 count=1 points=2\nshape 0 3 1 1 1\n0 0 1\n");
  expect_error(read_convex_shapes(p), p + ":2", "the header says points=2");
  p = temp_file("shapes_short.txt", "convex_shapes 1 count=1 points=2\nshape 0 2 1 1 1\n0 0 1\n");
  expect_error(read_convex_shapes(p), p + ":3", "after 1 of its 2 points");
  p = temp_file("shapes_word.txt", "convex_shapes 1 count=1 points=1\nhull 0 1 1 1 1\n0 0 1\n");
  expect_error(read_convex_shapes(p), p + ":2", "expected 'shape");

  const auto dir = std::filesystem::temp_directory_path() / "proxima_workload_tests" / "convex_dir";
  std::filesystem::create_directories(dir);
  std::ofstream((dir / "convex_shapes_1.txt").string()) << "convex_shapes 1 count=1 points=1\nshape 0 1 1 1 1\n0 0 1\n";
  std::ofstream((dir / "convex_pairs_1.txt").string())
      << "convex_pairs 1 count=1 shapes=convex_shapes_1.txt\n0 1 0 0 0 1 0 0 0 1 1 1 1 0 0 0\n";
  const auto w = read_convex_workload(dir.string(), 1);
  ASSERT_FALSE(w.ok());
  EXPECT_NE(w.error().what().find("convex_pairs_1.txt:2"), std::string::npos) << w.error().what();
  EXPECT_NE(w.error().what().find("shape id 1 beyond the 1 shapes of convex_shapes_1.txt"), std::string::npos)
      << w.error().what();

  std::ofstream((dir / "ccd_pairs.txt").string())
      << "ccd_pairs 1 count=2 hulls=convex_shapes_1.txt\n"
      << "hull 0 | sphere 1 | 0 0 0 1 0 0 0 1 0 0 1 0 0 0 | 0 0 0 1 0 0 0 1 0 0 1 0 0 0\n"
      << "# comment\n"
      << "sphere 1 | hull 3 | 0 0 0 1 0 0 0 1 0 0 1 0 0 0 | 0 0 0 1 0 0 0 1 0 0 1 0 0 0\n";
  const auto ccd = read_ccd_workload(dir.string());
  ASSERT_FALSE(ccd.ok());
  EXPECT_NE(ccd.error().what().find("ccd_pairs.txt:4"), std::string::npos) << ccd.error().what();
  EXPECT_NE(ccd.error().what().find("hull id 3 beyond the 1 shapes"), std::string::npos) << ccd.error().what();
  std::ofstream((dir / "ccd_pairs.txt").string()) << "ccd_pairs 1 count=0\n";
  const auto no_hulls = read_ccd_workload(dir.string());
  ASSERT_FALSE(no_hulls.ok());
  EXPECT_NE(no_hulls.error().what().find("lacks the key hulls="), std::string::npos) << no_hulls.error().what();
}

TEST(MalformedWorkloads, CcdLines) {
  const std::string poses = "0 0 0 1 0 0 0 1 0 0 1 0 0 0";
  std::string p = temp_file("ccd_shape.txt",
                            "ccd_pairs 1 count=1 hulls=h.txt\ncone 1 | sphere 1 | " + poses + " | " + poses + "\n");
  expect_error(read_ccd_pairs(p), p + ":2", "unknown shape 'cone'");
  p = temp_file("ccd_bars.txt", "ccd_pairs 1 count=1 hulls=h.txt\nsphere 1 | sphere 1 " + poses + " | " + poses + "\n");
  expect_error(read_ccd_pairs(p), p + ":2", "expected 4 fields separated by '|'");
  p = temp_file("ccd_box.txt", "ccd_pairs 1 count=1 hulls=h.txt\nbox 1 1 | sphere 1 | " + poses + " | " + poses + "\n");
  expect_error(read_ccd_pairs(p), p + ":2", "expected 4 fields (box hx hy hz)");
  p = temp_file("ccd_ok.txt", "ccd_pairs 1 count=1 hulls=h.txt\nhull 7 | box 1 2 3 | " + poses + " | " + poses + "\n");
  const auto ok = read_ccd_pairs(p);
  ASSERT_TRUE(ok.ok()) << ok.error().what();
  EXPECT_EQ(ok->cases[0].a.kind, CcdShapeKind::Hull);
  EXPECT_EQ(ok->cases[0].a.hull, 7u);
  EXPECT_EQ(ok->cases[0].b.half_extents, (Vec3d{1, 2, 3}));
  EXPECT_EQ(ok->cases[0].a1.position, (Vec3d{1, 0, 0}));
}

TEST(MalformedWorkloads, ObjSubset) {
  std::string p = temp_file("obj_range.obj", "# c\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n");
  expect_error(read_obj(p), p + ":5", "vertex index 4 out of range (3 vertices so far)");
  p = temp_file("obj_zero.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n");
  expect_error(read_obj(p), p + ":4", "indices are 1-based");
  p = temp_file("obj_statement.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nl 1 2\nf 1 2 3\n");
  expect_error(read_obj(p), p + ":4", "unsupported OBJ statement 'l'");
  p = temp_file("obj_short_face.obj", "v 0 0 0\nv 1 0 0\nf 1 2\n");
  expect_error(read_obj(p), p + ":3", "at least 3 vertices");
  p = temp_file("obj_vertex.obj", "v 0 0\n");
  expect_error(read_obj(p), p + ":1", "expected 'v x y z'");
  p = temp_file("obj_empty.obj", "# nothing\n");
  expect_error(read_obj(p), p, "no vertices or no faces");
  // Quads are fanned, i/t/n forms and negative (relative) indices accepted, extras ignored.
  p = temp_file("obj_ok.obj",
                "o thing\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvn 0 0 1\ns off\n"
                "f 1/1/1 2/2/1 3/3/1 4/4/1\nf -4//1 -2//1 -1//1\n");
  const auto mesh = read_obj(p);
  ASSERT_TRUE(mesh.ok()) << mesh.error().what();
  ASSERT_EQ(mesh->triangles.size(), 3u);
  EXPECT_EQ(mesh->triangles[0], (std::array<std::uint32_t, 3>{0, 1, 2}));
  EXPECT_EQ(mesh->triangles[1], (std::array<std::uint32_t, 3>{0, 2, 3}));
  EXPECT_EQ(mesh->triangles[2], (std::array<std::uint32_t, 3>{0, 2, 3}));
}

TEST(WorkloadDir, CommandLineThenEnvironmentThenDefault) {
  std::string a0 = "prog", a1 = "--workloads=/data/x", a2 = "--benchmark_filter=Floor", a3 = "--workloads",
              a4 = "/data/y";
  {
    char* argv[] = {a0.data(), a1.data(), a2.data(), nullptr};
    int argc = 3;
    EXPECT_EQ(workload_dir(argc, argv), "/data/x");
    ASSERT_EQ(argc, 2);
    EXPECT_STREQ(argv[1], "--benchmark_filter=Floor");
    EXPECT_EQ(argv[2], nullptr);
  }
  {
    char* argv[] = {a0.data(), a3.data(), a4.data(), a2.data(), nullptr};
    int argc = 4;
    EXPECT_EQ(workload_dir(argc, argv), "/data/y");
    ASSERT_EQ(argc, 2);
    EXPECT_STREQ(argv[1], "--benchmark_filter=Floor");
  }
  const char* saved = std::getenv("PROXIMA_WORKLOADS");
  const std::string saved_value = saved != nullptr ? saved : "";
  ::setenv("PROXIMA_WORKLOADS", "/data/env", 1);
  {
    char* argv[] = {a0.data(), a2.data(), nullptr};
    int argc = 2;
    EXPECT_EQ(workload_dir(argc, argv), "/data/env");
    EXPECT_EQ(argc, 2);
  }
  ::unsetenv("PROXIMA_WORKLOADS");
  EXPECT_EQ(workload_dir(), PROXIMA_DEFAULT_WORKLOAD_DIR);
  if (saved != nullptr) ::setenv("PROXIMA_WORKLOADS", saved_value.c_str(), 1);
  EXPECT_EQ(workload_path("/a/b", "c.txt"), "/a/b/c.txt");
  EXPECT_EQ(workload_path("/a/b/", "c.txt"), "/a/b/c.txt");
}

}  // namespace test_malformed
}  // namespace proxima::bench
