// Oriented node boxes of a mesh (src/midphase/oriented_tree.cpp): every node's box holds
// every corner of every triangle of its subtree (checked by walking the Bvh, not through
// the builder's corner ranges), the axes are orthonormal and right-handed, and a deformed
// mesh gets boxes around its new vertices; threads racing on the first use get one tree. Meshes: random triangle soups
// (seeded), a fine torus, a flat grid (a degenerate covariance) and a single triangle.
#include <gtest/gtest.h>

#include <proxima/core/tolerance.hpp>
#include <proxima/shapes/triangle_mesh.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <thread>
#include <vector>

#include "shapes/oriented_tree.hpp"
#include "support/random.hpp"
#include "support/solid_test_meshes.hpp"

namespace proxima {
namespace test_oriented_tree {

IndexedMesh soup(test::Random& rng, int count, Real spread, Real size) {
  IndexedMesh m;
  for (int i = 0; i < count; ++i) {
    const Vec3 c = rng.in_ball(spread);
    for (int k = 0; k < 3; ++k) m.vertices.push_back(c + rng.in_ball(size));
    const auto base = static_cast<std::uint32_t>(3 * i);
    m.triangles.push_back({base, base + 1, base + 2});
  }
  return m;
}

IndexedMesh torus(Real major, Real minor, int segments, int sides) {
  return test::torus_mesh(major, minor, segments, sides);
}

/// n x n grid of quads in the plane z = 1 (the covariance has a zero eigenvalue).
IndexedMesh grid(int n) {
  IndexedMesh m;
  for (int i = 0; i <= n; ++i) {
    for (int j = 0; j <= n; ++j) m.vertices.push_back({Real(i) / Real(n), Real(j) / Real(n), Real(1)});
  }
  const auto id = [&](int i, int j) { return static_cast<std::uint32_t>(i * (n + 1) + j); };
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      m.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      m.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  }
  return m;
}

TriangleMesh make(IndexedMesh m) {
  MeshCreateOptions options;
  options.repair = false;  // keep soups as they are
  Result<TriangleMesh> r = TriangleMesh::create(std::move(m), options);
  EXPECT_TRUE(r.ok());
  return std::move(r).value();
}

Real geometry_scale(const Vec3& v) { return std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)}); }

/// Walks the Bvh: every corner of every triangle below node k lies in node k's box (and in
/// every ancestor's, each checked on its own), within a rounding tolerance of the mesh size.
void expect_bounds(const TriangleMesh& mesh) {
  const detail::OrientedTree& tree = mesh.oriented_tree();
  const auto nodes = mesh.bvh().nodes();
  const auto prims = mesh.bvh().primitives();
  ASSERT_EQ(tree.nodes.size(), nodes.size());
  const Aabb box = mesh.local_aabb();
  const Real scale = std::max({Real(1), geometry_scale(box.min), geometry_scale(box.max)});
  const Real tol = Real(16) * kEpsilon * scale;
  std::uint64_t checked = 0;
  for (std::size_t k = 0; k < nodes.size(); ++k) {
    const detail::OrientedNode& o = tree.nodes[k];
    SCOPED_TRACE(k);
    // Orthonormal, right-handed axes; finite, non-negative extents.
    for (int i = 0; i < 3; ++i) {
      EXPECT_NEAR(glm::length(o.axis[i]), Real(1), Real(64) * kEpsilon);
      EXPECT_NEAR(glm::dot(o.axis[i], o.axis[(i + 1) % 3]), Real(0), Real(64) * kEpsilon);
      EXPECT_GE(o.half[i], Real(0));
    }
    EXPECT_NEAR(glm::dot(glm::cross(o.axis[0], o.axis[1]), o.axis[2]), Real(1), Real(64) * kEpsilon);
    // Subtree walk.
    std::vector<std::uint32_t> stack{static_cast<std::uint32_t>(k)};
    while (!stack.empty()) {
      const BvhNode& n = nodes[stack.back()];
      stack.pop_back();
      if (!n.is_leaf()) {
        stack.push_back(n.first);
        stack.push_back(n.first + 1);
        continue;
      }
      for (std::uint32_t s = n.first; s != n.first + n.count; ++s) {
        for (const Vec3& p : mesh.triangle(prims[s])) {
          const Vec3 d = p - o.center;
          for (int i = 0; i < 3; ++i) {
            EXPECT_LE(std::abs(glm::dot(d, o.axis[i])), o.half[i] + tol) << "triangle " << prims[s] << " axis " << i;
          }
          ++checked;
        }
      }
    }
    if (::testing::Test::HasFailure()) return;
  }
  EXPECT_GT(checked, 0u);
}

TEST(OrientedTree, SoupsAreBounded) {
  test::Random rng(31);
  for (int round = 0; round < 6; ++round) {
    SCOPED_TRACE(round);
    const Real spread = round < 3 ? Real(1) : Real(40);
    expect_bounds(make(soup(rng, 50 + 150 * round, spread, spread * Real(0.05))));
  }
}

TEST(OrientedTree, TorusIsBoundedAndTighterThanItsBoxes) {
  const TriangleMesh mesh = make(torus(Real(2), Real(0.3), 96, 24));
  expect_bounds(mesh);
  // The oriented boxes are tighter than the axis-aligned ones on the whole (volume sum).
  const auto& tree = mesh.oriented_tree();
  double obb = 0.0;
  double aabb = 0.0;
  for (std::size_t k = 0; k < tree.nodes.size(); ++k) {
    const Vec3 h = tree.nodes[k].half;
    const Vec3 e = mesh.bvh().nodes()[k].max - mesh.bvh().nodes()[k].min;
    obb += 8.0 * double(h.x) * double(h.y) * double(h.z);
    aabb += double(e.x) * double(e.y) * double(e.z);
  }
  EXPECT_LT(obb, aabb);
}

TEST(OrientedTree, FlatGridAndSingleTriangle) {
  expect_bounds(make(grid(16)));
  IndexedMesh one;
  one.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  one.triangles = {{0, 1, 2}};
  const TriangleMesh mesh = make(one);
  expect_bounds(mesh);
  EXPECT_EQ(mesh.oriented_tree().nodes.size(), 1u);
}

TEST(OrientedTree, DeformedMeshGetsItsOwnBoxes) {
  const TriangleMesh mesh = make(torus(Real(1), Real(0.25), 32, 12));
  const detail::OrientedTree& before = mesh.oriented_tree();
  std::vector<Vec3> moved(mesh.vertices().begin(), mesh.vertices().end());
  for (Vec3& v : moved) v = Vec3(v.x * Real(2), v.y, v.z * Real(3) + v.x);
  Result<TriangleMesh> deformed = mesh.deformed(moved);
  ASSERT_TRUE(deformed.ok());
  expect_bounds(*deformed);
  EXPECT_NE(&before, &deformed->oriented_tree());
  // The copy shares the original's boxes.
  const TriangleMesh copy = mesh;
  EXPECT_EQ(&before, &copy.oriented_tree());
}

TEST(OrientedTree, FirstUseFromManyThreadsBuildsOnce) {
  const TriangleMesh mesh = make(torus(Real(1), Real(0.25), 64, 16));
  constexpr int kThreads = 8;
  std::vector<const detail::OrientedTree*> seen(kThreads, nullptr);
  std::vector<std::thread> threads;
  for (int i = 0; i < kThreads; ++i) {
    threads.emplace_back([&mesh, &seen, i] {
      const TriangleMesh copy = mesh;  // copies share the data, as objects sharing a mesh do
      seen[static_cast<std::size_t>(i)] = &copy.oriented_tree();
    });
  }
  for (std::thread& t : threads) t.join();
  for (const detail::OrientedTree* p : seen) EXPECT_EQ(p, seen[0]);
  expect_bounds(mesh);
}

}  // namespace test_oriented_tree
}  // namespace proxima
