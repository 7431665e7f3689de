// proxima_make_workload: its files read back by the readers with the requested counts and
// the statistics FORMATS.md describes (W1 about 1.5 / 3.4 overlaps per box, W2 about half
// separated, W3 about 61 % overlapping, W7 about 50 % / 54 %), computed here with
// independent references (brute-force pairs, 15-axis SAT, segment distance, a dense search
// for separating axes); output deterministic in the seed; with the default seeds and the
// shared sizes, byte-identical to the shared files (their SHA-256 from SHA256SUMS).
#include <gtest/gtest.h>

#include <cstdlib>
#include <sys/wait.h>

#include "workload_test_util.hpp"

namespace proxima::bench {
namespace test_make_workload {

namespace fs = std::filesystem;
using namespace test_util;

fs::path out_dir() {
  const fs::path dir = fs::temp_directory_path() / "proxima_make_workload_tests";
  fs::create_directories(dir);
  return dir;
}

/// Runs the generator with `args`; returns its exit status.
int make(const std::string& args) {
  const std::string command = std::string("\"") + PROXIMA_MAKE_WORKLOAD_EXE + "\" " + args + " 2>/dev/null";
  const int status = std::system(command.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

double overlaps_per_box(const std::vector<BroadphaseBox>& boxes) {
  return 2.0 * static_cast<double>(overlapping_pairs(boxes).size()) / static_cast<double>(boxes.size());
}

TEST(MakeWorkload, BroadphaseUniform) {
  const std::string file = (out_dir() / "bp_uniform.txt").string();
  ASSERT_EQ(make("broadphase --n 30000 --frames 3 --layout uniform --seed 11 --out " + file), 0);
  const auto w = read_broadphase(file);
  ASSERT_TRUE(w.ok()) << w.error().what();
  EXPECT_EQ(w->boxes.size(), 30000u);
  EXPECT_EQ(w->frames, 3);
  EXPECT_EQ(w->name, "broadphase_uniform_30k");
  EXPECT_NEAR(w->hi, std::cbrt(64.0 * 30000 / 1.5), 1e-3);
  for (const BroadphaseBox& b : w->boxes) {
    const double speed =
        std::sqrt(b.velocity.x * b.velocity.x + b.velocity.y * b.velocity.y + b.velocity.z * b.velocity.z);
    EXPECT_NEAR(speed, 0.1, 0.05 + 2e-3);  // in [0.05, 0.15] up to the 3-decimal rounding
    for (int a = 0; a < 3; ++a) {
      EXPECT_GE(b.half_extents[a], 0.5);
      EXPECT_LE(b.half_extents[a], 1.5);
      EXPECT_GE(b.center[a], 0.0);
      EXPECT_LE(b.center[a], w->hi);
    }
  }
  EXPECT_NEAR(overlaps_per_box(w->boxes), 1.5, 0.15);
  // Still about 1.5 after moving.
  std::vector<BroadphaseBox> boxes = w->boxes;
  for (int f = 0; f < w->frames; ++f) advance_frame(boxes, w->dt, w->lo, w->hi);
  EXPECT_NEAR(overlaps_per_box(boxes), 1.5, 0.15);
}

TEST(MakeWorkload, BroadphaseClustered) {
  const std::string file = (out_dir() / "bp_clustered.txt").string();
  ASSERT_EQ(make("broadphase --n 50000 --frames 5 --layout clustered --seed 12 --name my_scene --out " + file), 0);
  const auto w = read_broadphase(file);
  ASSERT_TRUE(w.ok()) << w.error().what();
  EXPECT_EQ(w->boxes.size(), 50000u);
  EXPECT_EQ(w->name, "my_scene");
  EXPECT_NEAR(w->hi, 240.0 * std::cbrt(0.5), 1e-3);
  std::size_t still = 0;
  for (const BroadphaseBox& b : w->boxes) still += b.velocity == Vec3d{0, 0, 0} ? 1 : 0;
  EXPECT_EQ(still, 5000u);  // the 10 % static boxes
  EXPECT_NEAR(overlaps_per_box(w->boxes), 3.4, 0.4);
}

TEST(MakeWorkload, SpheresAndCapsules) {
  const std::string spheres_file = (out_dir() / "spheres.txt").string();
  ASSERT_EQ(make("spheres --count 4000 --repeat 5 --seed 13 --out " + spheres_file), 0);
  const auto spheres = read_sphere_pairs(spheres_file);
  ASSERT_TRUE(spheres.ok()) << spheres.error().what();
  EXPECT_EQ(spheres->distinct.size(), 4000u);
  EXPECT_EQ(spheres->queries.size(), 20000u);
  std::size_t hits = 0;
  for (const SpherePair& p : spheres->distinct) {
    const double dx = p.center1.x - p.center2.x, dy = p.center1.y - p.center2.y, dz = p.center1.z - p.center2.z;
    const double r = p.radius1 + p.radius2;
    hits += dx * dx + dy * dy + dz * dz <= r * r ? 1 : 0;
    EXPECT_GE(p.radius1, 0.1);
    EXPECT_LE(p.radius2, 1.0);
  }
  EXPECT_NEAR(static_cast<double>(hits) / 4000.0, 0.50, 0.04);

  const std::string capsules_file = (out_dir() / "capsules.txt").string();
  ASSERT_EQ(make("capsules --count 4000 --repeat 3 --seed 14 --out " + capsules_file), 0);
  const auto capsules = read_capsule_pairs(capsules_file);
  ASSERT_TRUE(capsules.ok()) << capsules.error().what();
  EXPECT_EQ(capsules->distinct.size(), 4000u);
  EXPECT_EQ(capsules->queries.size(), 12000u);
  hits = 0;
  for (const CapsulePair& p : capsules->distinct) {
    hits += segment_distance(p.a0, p.a1, p.b0, p.b1) <= p.radius_a + p.radius_b ? 1 : 0;
  }
  EXPECT_NEAR(static_cast<double>(hits) / 4000.0, 0.54, 0.04);
}

TEST(MakeWorkload, Boxes) {
  const std::string file = (out_dir() / "boxes.txt").string();
  ASSERT_EQ(make("boxes --count 5000 --seed 15 --out " + file), 0);
  const auto pairs = read_box_pairs(file);
  ASSERT_TRUE(pairs.ok()) << pairs.error().what();
  ASSERT_EQ(pairs->size(), 5000u);
  std::size_t overlapping = 0;
  for (const BoxPair& p : *pairs) overlapping += boxes_overlap(p) ? 1 : 0;
  EXPECT_NEAR(static_cast<double>(overlapping) / 5000.0, 0.61, 0.03);
}

TEST(MakeWorkload, Convex) {
  const fs::path dir = out_dir() / "convex";
  fs::create_directories(dir);
  ASSERT_EQ(make("convex --points 16 --shapes 50 --count 2000 --seed 16 --out " + dir.string()), 0);
  const auto w = read_convex_workload(dir.string(), 16);
  ASSERT_TRUE(w.ok()) << w.error().what();
  EXPECT_EQ(w->shapes.shapes.size(), 50u);
  EXPECT_EQ(w->shapes.points_per_shape, 16);
  EXPECT_EQ(w->pairs.pairs.size(), 2000u);
  EXPECT_EQ(w->pairs.shapes_file, "convex_shapes_16.txt");
  for (const ConvexShape& s : w->shapes.shapes) {
    for (int a = 0; a < 3; ++a) {
      EXPECT_GE(s.semi_axes[a], 0.3);
      EXPECT_LE(s.semi_axes[a], 1.0);
    }
  }
  // Separated pairs: a separating axis among a dense set of directions (a lower bound on
  // the true count, close to it with 2000 directions).
  std::vector<Vec3d> directions;
  const int kDirections = 2000;
  for (int k = 0; k < kDirections; ++k) {  // Fibonacci sphere
    const double z = 1 - (2 * k + 1.0) / kDirections;
    const double r = std::sqrt(1 - z * z);
    const double phi = k * 2.399963229728653;
    directions.push_back({r * std::cos(phi), r * std::sin(phi), z});
  }
  std::size_t separated = 0;
  for (const ConvexPair& p : w->pairs.pairs) {
    std::vector<Vec3d> a, b;
    for (const Vec3d& l : w->shapes.shapes[p.a].points) a.push_back(apply(p.pose_a, l));
    for (const Vec3d& l : w->shapes.shapes[p.b].points) b.push_back(apply(p.pose_b, l));
    for (const Vec3d& d : directions) {
      double max_a = -1e300, min_b = 1e300;
      for (const Vec3d& q : a) max_a = std::max(max_a, q.x * d.x + q.y * d.y + q.z * d.z);
      for (const Vec3d& q : b) min_b = std::min(min_b, q.x * d.x + q.y * d.y + q.z * d.z);
      if (max_a < min_b) {
        ++separated;
        break;
      }
    }
  }
  // Half the pairs are separated by construction (factor > 1 on the construction axis);
  // the search misses a few with a tiny gap. Of the others, most intersect.
  const double fraction = static_cast<double>(separated) / 2000.0;
  EXPECT_GT(fraction, 0.45);
  EXPECT_LT(fraction, 0.75);
}

TEST(MakeWorkload, DeterministicInTheSeed) {
  const std::string a = (out_dir() / "det_a.txt").string();
  const std::string b = (out_dir() / "det_b.txt").string();
  const std::string c = (out_dir() / "det_c.txt").string();
  ASSERT_EQ(make("capsules --count 500 --seed 99 --out " + a), 0);
  ASSERT_EQ(make("capsules --count 500 --seed 99 --out " + b), 0);
  ASSERT_EQ(make("capsules --count 500 --seed 98 --out " + c), 0);
  EXPECT_EQ(*sha256_file(a), *sha256_file(b));
  EXPECT_NE(*sha256_file(a), *sha256_file(c));
}

TEST(MakeWorkload, RejectsBadUsage) {
  const std::string out = (out_dir() / "bad.txt").string();
  EXPECT_EQ(make(""), 2);
  EXPECT_EQ(make("teapots --out " + out), 2);
  EXPECT_EQ(make("broadphase --layout diagonal --out " + out), 2);
  EXPECT_EQ(make("broadphase --n 10"), 2);  // no --out
  EXPECT_EQ(make("broadphase --n -5 --out " + out), 2);
  EXPECT_EQ(make("broadphase --n ten --out " + out), 2);
  EXPECT_EQ(make("spheres --frames 3 --out " + out), 2);  // not an option of spheres
  EXPECT_EQ(make("spheres --count 0 --out " + out), 2);
  EXPECT_EQ(make("boxes --count 10 --out /nonexistent/dir/x.txt"), 1);
  EXPECT_EQ(make("--help"), 0);
}

TEST(MakeWorkload, DefaultSeedsReproduceTheSharedFiles) {
  const std::string dir = shared_dir();
  if (dir.empty()) GTEST_SKIP() << "shared workloads not found";
  std::map<std::string, std::string> expected;
  for (const std::string& line : read_lines(workload_path(dir, "SHA256SUMS"))) {
    std::istringstream in(line);
    std::string digest, name;
    in >> digest >> name;
    expected[name] = digest;
  }
  const fs::path out = out_dir() / "shared";
  fs::create_directories(out);
  auto o = [&](const char* name) { return (out / name).string(); };
  ASSERT_EQ(make("broadphase --n 10000 --out " + o("broadphase_uniform_10k.txt")), 0);
  ASSERT_EQ(make("broadphase --n 100000 --seed 102 --out " + o("broadphase_uniform_100k.txt")), 0);
  ASSERT_EQ(make("broadphase --n 100000 --layout clustered --out " + o("broadphase_clustered_100k.txt")), 0);
  ASSERT_EQ(make("spheres --out " + o("sphere_pairs.txt")), 0);
  ASSERT_EQ(make("capsules --out " + o("capsule_pairs.txt")), 0);
  ASSERT_EQ(make("boxes --out " + o("box_pairs.txt")), 0);
  for (const int points : {8, 32, 128}) {
    ASSERT_EQ(make("convex --points " + std::to_string(points) + " --out " + out.string()), 0);
  }
  int compared = 0;
  for (const auto& entry : fs::directory_iterator(out)) {
    const std::string name = entry.path().filename().string();
    ASSERT_EQ(expected.count(name), 1u) << name;
    EXPECT_EQ(*sha256_file(entry.path().string()), expected[name]) << name;
    ++compared;
  }
  EXPECT_EQ(compared, 12);
}

}  // namespace test_make_workload
}  // namespace proxima::bench
