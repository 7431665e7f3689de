// Every reader on every shared workload file: record counts against the header and
// MANIFEST.txt, the first and last records against the file text (parsed separately
// with strtod), unit quaternions after normalisation, and the statistics MANIFEST.txt
// states (overlap counts recomputed from the records).
#include <gtest/gtest.h>

#include <proxima/core/tolerance.hpp>

#include <algorithm>
#include <set>
#include <utility>

#include "workload_test_util.hpp"

namespace proxima::bench {
namespace test_readers {

using namespace test_util;

class SharedWorkloads : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = shared_dir();
    if (dir_.empty()) GTEST_SKIP() << "shared workloads not found in " << workload_dir();
    manifest_ = read_manifest(dir_);
  }
  std::string path(const std::string& name) const { return workload_path(dir_, name); }
  /// The manifest's notes for `name`, after checking its byte count.
  std::string notes(const std::string& name) const {
    const auto it = manifest_.find(name);
    EXPECT_NE(it, manifest_.end()) << name;
    if (it == manifest_.end()) return {};
    EXPECT_EQ(std::filesystem::file_size(path(name)), it->second.bytes) << name;
    return it->second.notes;
  }

  std::string dir_;
  std::map<std::string, ManifestEntry> manifest_;
};

void expect_pose_eq(const Pose& actual, const Pose& expected) {
  EXPECT_EQ(actual.position, expected.position);
  EXPECT_EQ(actual.rotation, expected.rotation);
  EXPECT_LT(unit_error(actual.rotation), 1e-14);
}

void expect_vec_eq(const Vec3d& actual, const std::vector<double>& v, std::size_t at) {
  EXPECT_EQ(actual, (Vec3d{v[at], v[at + 1], v[at + 2]}));
}

// ---- W1 -----------------------------------------------------------------------------

TEST_F(SharedWorkloads, Broadphase) {
  struct Case {
    const char* file;
    bool uniform;
  };
  for (const Case c : {Case{"broadphase_uniform_10k.txt", true}, Case{"broadphase_uniform_100k.txt", true},
                       Case{"broadphase_clustered_100k.txt", false}}) {
    SCOPED_TRACE(c.file);
    const std::string note = notes(c.file);
    const auto w = read_broadphase(path(c.file));
    ASSERT_TRUE(w.ok()) << w.error().what();
    EXPECT_EQ(static_cast<long long>(w->boxes.size()), capture(note, R"(n=(\d+))"));
    EXPECT_EQ(w->frames, 100);
    EXPECT_EQ(w->dt, 1.0);
    EXPECT_EQ(w->lo, 0.0);
    EXPECT_EQ(w->name + ".txt", c.file);
    const auto text = read_lines(path(c.file));
    ASSERT_EQ(text.size(), w->boxes.size() + 1);
    std::smatch hi;
    ASSERT_TRUE(std::regex_search(text[0], hi, std::regex(R"( hi=([0-9.]+))")));
    EXPECT_EQ(std::strtod(hi[1].str().c_str(), nullptr), w->hi);
    for (const std::size_t i : {std::size_t{0}, w->boxes.size() - 1}) {
      const auto v = numbers(text[i + 1]);
      ASSERT_EQ(v.size(), 9u);
      expect_vec_eq(w->boxes[i].center, v, 0);
      expect_vec_eq(w->boxes[i].half_extents, v, 3);
      expect_vec_eq(w->boxes[i].velocity, v, 6);
    }
    for (const BroadphaseBox& b : w->boxes) {
      for (int a = 0; a < 3; ++a) {
        EXPECT_GE(b.center[a], w->lo);
        EXPECT_LE(b.center[a], w->hi);
        EXPECT_LE(std::abs(b.velocity[a]), 0.15);
        if (c.uniform) {
          EXPECT_GE(b.half_extents[a], 0.5);
          EXPECT_LE(b.half_extents[a], 1.5);
        }
      }
    }
    // MANIFEST's frame-0 pair count came from the generator's own grid.
    EXPECT_EQ(static_cast<long long>(overlapping_pairs(w->boxes).size()), capture(note, R"(frame0_pairs=(\d+))"));
  }
}

// ---- W2 -----------------------------------------------------------------------------

TEST_F(SharedWorkloads, ConvexShapesAndPairs) {
  for (const int points : {8, 32, 128}) {
    SCOPED_TRACE(points);
    const std::string shapes_file = "convex_shapes_" + std::to_string(points) + ".txt";
    const std::string pairs_file = "convex_pairs_" + std::to_string(points) + ".txt";
    const std::string shape_note = notes(shapes_file);
    const std::string pair_note = notes(pairs_file);
    const auto w = read_convex_workload(dir_, points);
    ASSERT_TRUE(w.ok()) << w.error().what();
    const ConvexShapes& shapes = w->shapes;
    EXPECT_EQ(static_cast<long long>(shapes.shapes.size()), capture(shape_note, R"((\d+) shapes)"));
    EXPECT_EQ(shapes.points_per_shape, points);
    EXPECT_EQ(capture(shape_note, R"(x (\d+) points)"), points);

    const auto text = read_lines(path(shapes_file));
    ASSERT_EQ(text.size(), 1 + shapes.shapes.size() * (1 + static_cast<std::size_t>(points)));
    const auto head = numbers(text[1]);  // "shape 0 P ax ay az"
    ASSERT_EQ(head.size(), 5u);
    expect_vec_eq(shapes.shapes.front().semi_axes, head, 2);
    expect_vec_eq(shapes.shapes.front().points.front(), numbers(text[2]), 0);
    expect_vec_eq(shapes.shapes.back().points.back(), numbers(text.back()), 0);
    for (const ConvexShape& s : shapes.shapes) {
      ASSERT_EQ(s.points.size(), static_cast<std::size_t>(points));
      for (const Vec3d& p : s.points) {
        // On the ellipsoid, up to the 5- and 4-decimal rounding of the file.
        const double e = p.x * p.x / (s.semi_axes.x * s.semi_axes.x) + p.y * p.y / (s.semi_axes.y * s.semi_axes.y) +
                         p.z * p.z / (s.semi_axes.z * s.semi_axes.z);
        EXPECT_NEAR(e, 1.0, 2e-3);
      }
    }

    const ConvexPairs& pairs = w->pairs;
    EXPECT_EQ(pairs.shapes_file, shapes_file);
    EXPECT_EQ(static_cast<long long>(pairs.pairs.size()), capture(pair_note, R"((\d+) pairs)"));
    const auto ptext = read_lines(path(pairs_file));
    ASSERT_EQ(ptext.size(), pairs.pairs.size() + 1);
    for (const std::size_t i : {std::size_t{0}, pairs.pairs.size() - 1}) {
      const auto v = numbers(ptext[i + 1]);
      ASSERT_EQ(v.size(), 16u);
      EXPECT_EQ(pairs.pairs[i].a, static_cast<std::uint32_t>(v[0]));
      EXPECT_EQ(pairs.pairs[i].b, static_cast<std::uint32_t>(v[1]));
      expect_pose_eq(pairs.pairs[i].pose_a, pose_at(v, 2));
      expect_pose_eq(pairs.pairs[i].pose_b, pose_at(v, 9));
    }
    for (const ConvexPair& p : pairs.pairs) {
      EXPECT_LT(unit_error(p.pose_a.rotation), 1e-14);
      EXPECT_LT(unit_error(p.pose_b.rotation), 1e-14);
    }
  }
}

// ---- W3 -----------------------------------------------------------------------------

TEST_F(SharedWorkloads, BoxPairs) {
  const std::string note = notes("box_pairs.txt");
  const auto pairs = read_box_pairs(path("box_pairs.txt"));
  ASSERT_TRUE(pairs.ok()) << pairs.error().what();
  EXPECT_EQ(static_cast<long long>(pairs->size()), capture(note, R"((\d+) pairs)"));
  const auto text = read_lines(path("box_pairs.txt"));
  ASSERT_EQ(text.size(), pairs->size() + 1);
  for (const std::size_t i : {std::size_t{0}, pairs->size() - 1}) {
    const auto v = numbers(text[i + 1]);
    ASSERT_EQ(v.size(), 20u);
    expect_vec_eq((*pairs)[i].half_extents_a, v, 0);
    expect_pose_eq((*pairs)[i].pose_a, pose_at(v, 3));
    expect_vec_eq((*pairs)[i].half_extents_b, v, 10);
    expect_pose_eq((*pairs)[i].pose_b, pose_at(v, 13));
  }
  long long overlapping = 0;
  for (const BoxPair& p : *pairs) {
    EXPECT_LT(unit_error(p.pose_a.rotation), 1e-14);
    EXPECT_LT(unit_error(p.pose_b.rotation), 1e-14);
    overlapping += boxes_overlap(p) ? 1 : 0;
  }
  // The generator's count used its own SAT on the same numbers; allow for boundary cases.
  EXPECT_NEAR(static_cast<double>(overlapping), static_cast<double>(capture(note, R"(pairs, (\d+) \()")), 2.0);
}

// ---- W4 -----------------------------------------------------------------------------

/// True when every directed edge appears once and its reverse too (closed, consistently
/// oriented 2-manifold).
bool closed_and_oriented(const ObjMesh& mesh) {
  std::set<std::pair<std::uint32_t, std::uint32_t>> edges;
  for (const auto& t : mesh.triangles) {
    for (int k = 0; k < 3; ++k) {
      if (!edges.insert({t[k], t[(k + 1) % 3]}).second) return false;
    }
  }
  return std::all_of(edges.begin(), edges.end(), [&](const auto& e) { return edges.count({e.second, e.first}) == 1; });
}

TEST_F(SharedWorkloads, MeshesAndPoses) {
  for (const char* file : {"mesh_icosphere.obj", "mesh_torusknot.obj"}) {
    SCOPED_TRACE(file);
    const std::string note = notes(file);
    const auto mesh = read_obj(path(file));
    ASSERT_TRUE(mesh.ok()) << mesh.error().what();
    EXPECT_EQ(static_cast<long long>(mesh->vertices.size()), capture(note, R"((\d+) vertices)"));
    EXPECT_EQ(static_cast<long long>(mesh->triangles.size()), capture(note, R"((\d+) triangles)"));
    const auto text = read_lines(path(file));
    ASSERT_EQ(text.size(), 1 + mesh->vertices.size() + mesh->triangles.size());
    expect_vec_eq(mesh->vertices.front(), numbers(text[1]), 0);
    expect_vec_eq(mesh->vertices.back(), numbers(text[mesh->vertices.size()]), 0);
    const auto first_face = numbers(text[1 + mesh->vertices.size()]);
    const auto last_face = numbers(text.back());
    for (int k = 0; k < 3; ++k) {
      EXPECT_EQ(mesh->triangles.front()[k] + 1, static_cast<std::uint32_t>(first_face[k]));
      EXPECT_EQ(mesh->triangles.back()[k] + 1, static_cast<std::uint32_t>(last_face[k]));
    }
    EXPECT_TRUE(closed_and_oriented(*mesh));
  }

  const std::string note = notes("mesh_poses.txt");
  const auto poses = read_mesh_poses(path("mesh_poses.txt"));
  ASSERT_TRUE(poses.ok()) << poses.error().what();
  EXPECT_EQ(poses->mesh_a, "mesh_icosphere.obj");
  EXPECT_EQ(poses->mesh_b, "mesh_torusknot.obj");
  EXPECT_EQ(static_cast<long long>(poses->poses.size()), capture(note, R"((\d+) poses)"));
  const auto text = read_lines(path("mesh_poses.txt"));
  ASSERT_EQ(text.size(), poses->poses.size() + 1);
  expect_pose_eq(poses->poses.front(), pose_at(numbers(text[1]), 0));
  expect_pose_eq(poses->poses.back(), pose_at(numbers(text.back()), 0));
  for (const Pose& p : poses->poses) EXPECT_LT(unit_error(p.rotation), 1e-14);
}

// ---- W5 -----------------------------------------------------------------------------

TEST_F(SharedWorkloads, Rays) {
  const std::string note = notes("rays.txt");
  const auto rays = read_rays(path("rays.txt"));
  ASSERT_TRUE(rays.ok()) << rays.error().what();
  EXPECT_EQ(rays->mesh, "mesh_torusknot.obj");
  EXPECT_EQ(static_cast<long long>(rays->rays.size()), capture(note, R"((\d+) rays)"));
  const auto text = read_lines(path("rays.txt"));
  ASSERT_EQ(text.size(), rays->rays.size() + 1);
  for (const std::size_t i : {std::size_t{0}, rays->rays.size() - 1}) {
    const auto v = numbers(text[i + 1]);
    ASSERT_EQ(v.size(), 7u);
    expect_vec_eq(rays->rays[i].origin, v, 0);
    expect_vec_eq(rays->rays[i].direction, v, 3);  // as written, not renormalised
    EXPECT_EQ(rays->rays[i].max_t, v[6]);
  }
  std::size_t clipped = 0;
  for (const RayQuery& r : rays->rays) {
    const Vec3d& d = r.direction;
    EXPECT_NEAR(std::sqrt(d.x * d.x + d.y * d.y + d.z * d.z), 1.0, 1e-4);
    const Vec3d& o = r.origin;
    EXPECT_NEAR(std::sqrt(o.x * o.x + o.y * o.y + o.z * o.z), 4.0, 1e-3);
    if (r.max_t != 100) {
      ++clipped;
      EXPECT_GE(r.max_t, 2.5);
      EXPECT_LE(r.max_t, 5.0);
    }
  }
  EXPECT_NEAR(static_cast<double>(clipped) / static_cast<double>(rays->rays.size()), 0.2, 0.01);
}

// ---- W6 -----------------------------------------------------------------------------

TEST_F(SharedWorkloads, CcdPairs) {
  const std::string note = notes("ccd_pairs.txt");
  const auto w = read_ccd_workload(dir_);
  ASSERT_TRUE(w.ok()) << w.error().what();
  const CcdPairs& pairs = w->pairs;
  EXPECT_EQ(pairs.hulls_file, "convex_shapes_32.txt");
  EXPECT_EQ(w->hulls.points_per_shape, 32);
  EXPECT_EQ(static_cast<long long>(pairs.cases.size()), capture(note, R"((\d+) cases)"));
  const auto text = read_lines(path("ccd_pairs.txt"));
  ASSERT_EQ(text.size(), pairs.cases.size() + 1);
  // First line: "sphere r | box hx hy hz | pA0 pA1 | pB0 pB1".
  {
    const CcdCase& c = pairs.cases.front();
    ASSERT_EQ(text[1].rfind("sphere", 0), 0u);
    const auto v = numbers(text[1]);
    ASSERT_EQ(v.size(), 1u + 3u + 28u);
    EXPECT_EQ(c.a.kind, CcdShapeKind::Sphere);
    EXPECT_EQ(c.a.radius, v[0]);
    EXPECT_EQ(c.b.kind, CcdShapeKind::Box);
    expect_vec_eq(c.b.half_extents, v, 1);
    expect_pose_eq(c.a0, pose_at(v, 4));
    expect_pose_eq(c.a1, pose_at(v, 11));
    expect_pose_eq(c.b0, pose_at(v, 18));
    expect_pose_eq(c.b1, pose_at(v, 25));
  }
  {
    const CcdCase& c = pairs.cases.back();
    const auto v = numbers(text.back());
    ASSERT_GE(v.size(), 28u);
    const std::size_t at = v.size() - 28;  // the poses are the last 28 numbers
    expect_pose_eq(c.a0, pose_at(v, at));
    expect_pose_eq(c.a1, pose_at(v, at + 7));
    expect_pose_eq(c.b0, pose_at(v, at + 14));
    expect_pose_eq(c.b1, pose_at(v, at + 21));
  }
  long long tunnelling = 0;
  for (const CcdCase& c : pairs.cases) {
    for (const Pose* p : {&c.a0, &c.a1, &c.b0, &c.b1}) EXPECT_LT(unit_error(p->rotation), 1e-14);
    // Shortest arc: q0 . q1 >= 0 survives normalisation.
    auto qdot = [](const Quatd& a, const Quatd& b) { return a.w * b.w + a.x * b.x + a.y * b.y + a.z * b.z; };
    EXPECT_GE(qdot(c.a0.rotation, c.a1.rotation), 0.0);
    EXPECT_GE(qdot(c.b0.rotation, c.b1.rotation), 0.0);
    // Tunnelling cases are the only ones with a plate thinner than 0.1.
    if (c.a.kind == CcdShapeKind::Sphere && c.b.kind == CcdShapeKind::Box && c.b.half_extents.z < 0.05) ++tunnelling;
  }
  EXPECT_EQ(tunnelling, capture(note, R"((\d+) tunnelling)"));
}

// ---- W7 -----------------------------------------------------------------------------

TEST_F(SharedWorkloads, SpherePairs) {
  const std::string note = notes("sphere_pairs.txt");
  const auto pairs = read_sphere_pairs(path("sphere_pairs.txt"));
  ASSERT_TRUE(pairs.ok()) << pairs.error().what();
  const long long count = capture(note, R"((\d+) pairs x)");
  EXPECT_EQ(static_cast<long long>(pairs->distinct.size()), count);
  EXPECT_EQ(static_cast<long long>(pairs->repeat), capture(note, R"(repeat (\d+))"));
  EXPECT_EQ(static_cast<long long>(pairs->queries.size()), capture(note, R"(= (\d+) queries)"));
  EXPECT_EQ(pairs->queries.size(), pairs->query_count());
  for (std::size_t k = 0; k < pairs->queries.size(); k += 997) {
    EXPECT_EQ(pairs->queries[k].center1, pairs->distinct[k % pairs->distinct.size()].center1);
    EXPECT_EQ(pairs->queries[k].radius2, pairs->query(k).radius2);
  }
  const auto text = read_lines(path("sphere_pairs.txt"));
  ASSERT_EQ(text.size(), pairs->distinct.size() + 1);
  for (const std::size_t i : {std::size_t{0}, pairs->distinct.size() - 1}) {
    const auto v = numbers(text[i + 1]);
    ASSERT_EQ(v.size(), 8u);
    expect_vec_eq(pairs->distinct[i].center1, v, 0);
    EXPECT_EQ(pairs->distinct[i].radius1, v[3]);
    expect_vec_eq(pairs->distinct[i].center2, v, 4);
    EXPECT_EQ(pairs->distinct[i].radius2, v[7]);
  }
  long long overlapping = 0;
  for (const SpherePair& p : pairs->distinct) {
    const double dx = p.center1.x - p.center2.x, dy = p.center1.y - p.center2.y, dz = p.center1.z - p.center2.z;
    const double r = p.radius1 + p.radius2;
    overlapping += dx * dx + dy * dy + dz * dz <= r * r ? 1 : 0;
  }
  EXPECT_EQ(overlapping, capture(note, R"(queries; (\d+) \()"));

  // Not materialised on request.
  const auto lazy = read_sphere_pairs(path("sphere_pairs.txt"), Materialize::No);
  ASSERT_TRUE(lazy.ok());
  EXPECT_TRUE(lazy->queries.empty());
  EXPECT_EQ(lazy->query_count(), pairs->queries.size());
  const auto radii = materialize<float>(*lazy, [](const SpherePair& p) { return static_cast<float>(p.radius1); });
  ASSERT_EQ(radii.size(), pairs->queries.size());
  EXPECT_EQ(radii.back(), static_cast<float>(pairs->queries.back().radius1));
}

TEST_F(SharedWorkloads, CapsulePairs) {
  const std::string note = notes("capsule_pairs.txt");
  const auto pairs = read_capsule_pairs(path("capsule_pairs.txt"));
  ASSERT_TRUE(pairs.ok()) << pairs.error().what();
  EXPECT_EQ(static_cast<long long>(pairs->distinct.size()), capture(note, R"((\d+) pairs x)"));
  EXPECT_EQ(static_cast<long long>(pairs->repeat), capture(note, R"(repeat (\d+))"));
  EXPECT_EQ(static_cast<long long>(pairs->queries.size()), capture(note, R"(= (\d+) queries)"));
  for (std::size_t k = 0; k < pairs->queries.size(); k += 1009) {
    EXPECT_EQ(pairs->queries[k].b1, pairs->distinct[k % pairs->distinct.size()].b1);
  }
  const auto text = read_lines(path("capsule_pairs.txt"));
  ASSERT_EQ(text.size(), pairs->distinct.size() + 1);
  for (const std::size_t i : {std::size_t{0}, pairs->distinct.size() - 1}) {
    const auto v = numbers(text[i + 1]);
    ASSERT_EQ(v.size(), 14u);
    const CapsulePair& p = pairs->distinct[i];
    expect_vec_eq(p.a0, v, 0);
    expect_vec_eq(p.a1, v, 3);
    EXPECT_EQ(p.radius_a, v[6]);
    expect_vec_eq(p.b0, v, 7);
    expect_vec_eq(p.b1, v, 10);
    EXPECT_EQ(p.radius_b, v[13]);
  }
  long long overlapping = 0;
  for (const CapsulePair& p : pairs->distinct) {
    overlapping += segment_distance(p.a0, p.a1, p.b0, p.b1) <= p.radius_a + p.radius_b ? 1 : 0;
  }
  EXPECT_EQ(overlapping, capture(note, R"(queries; (\d+) \()"));
}

// ---- Poses -----------------------------------------------------------------------------

TEST(Poses, ConversionToTransformAgreesWithFormula) {
  // A quaternion written with 5 decimals, normalised by the reader's rule.
  const double w = 0.43973, x = 0.00291, y = -0.83030, z = -0.34241;
  const double n = std::sqrt(w * w + x * x + y * y + z * z);
  const Pose pose{{0.5535, -1.9720, -1.4238}, {w / n, x / n, y / n, z / n}};
  const Transform t = to_transform(pose);
  EXPECT_NEAR(static_cast<double>(glm::length(t.rotation)), 1.0, 4 * static_cast<double>(kEpsilon));
  for (const Vec3d l : {Vec3d{1, 0, 0}, Vec3d{0, 1, 0}, Vec3d{0, 0, 1}, Vec3d{0.3, -2, 5}}) {
    const Vec3d expected = apply(pose, l);  // FORMATS.md's matrix, in double
    const Vec3 got = t.apply(to_vec3(l));
    for (int a = 0; a < 3; ++a) {
      EXPECT_NEAR(static_cast<double>(got[a]), expected[a],
                  50 * static_cast<double>(kEpsilon) * (1 + std::abs(expected[a])));
    }
  }
}

}  // namespace test_readers
}  // namespace proxima::bench
