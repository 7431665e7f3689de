// Tests of analyse_mesh and repair_mesh. References: hand-built meshes whose defects are
// known by construction (a duplicated vertex, a flipped face, a missing face, a fin, two
// cubes, degenerate and duplicate triangles), analytic volume and area of tessellated
// boxes, volume and area bounds of an inscribed sphere tessellation, and a seeded sweep that
// scrambles closed meshes (shuffle, cyclic rotation, flips, duplicated triangles and
// vertices) and compares the repaired mesh with the original triangle by triangle.
#include <gtest/gtest.h>

#include <proxima/core/tolerance.hpp>
#include <proxima/shapes/indexed_mesh.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <random>
#include <set>
#include <vector>

#include "support/random.hpp"

namespace proxima {
namespace test_indexed_mesh {

constexpr bool kFloat = sizeof(Real) == 4;

/// Unit cube [0,1]^3, 8 vertices, 12 outward triangles.
IndexedMesh unit_cube(Vec3 offset = Vec3(0), Real size = Real(1)) {
  IndexedMesh m;
  for (int i = 0; i < 8; ++i) {
    m.vertices.push_back(offset + size * Vec3(Real(i & 1), Real((i >> 1) & 1), Real((i >> 2) & 1)));
  }
  // Quads listed counter-clockwise seen from outside.
  const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& q : quads) {
    m.triangles.push_back({std::uint32_t(q[0]), std::uint32_t(q[1]), std::uint32_t(q[2])});
    m.triangles.push_back({std::uint32_t(q[0]), std::uint32_t(q[2]), std::uint32_t(q[3])});
  }
  return m;
}

/// The test's own signed volume: sum of tetrahedra against the origin (double).
double reference_volume(const IndexedMesh& m) {
  double v = 0;
  for (const auto& t : m.triangles) {
    const Vec3& a = m.vertices[t[0]];
    const Vec3& b = m.vertices[t[1]];
    const Vec3& c = m.vertices[t[2]];
    v +=
        (double(a.x) * (double(b.y) * c.z - double(b.z) * c.y) - double(a.y) * (double(b.x) * c.z - double(b.z) * c.x) +
         double(a.z) * (double(b.x) * c.y - double(b.y) * c.x));
  }
  return v / 6;
}

RepairedMesh repaired(const IndexedMesh& m, const MeshRepairOptions& o = {}) {
  auto r = repair_mesh(m, o);
  EXPECT_TRUE(r.ok()) << (r.ok() ? "" : r.error().what());
  return r.value();
}

MeshReport analysed(const IndexedMesh& m) {
  auto r = analyse_mesh(m);
  EXPECT_TRUE(r.ok()) << (r.ok() ? "" : r.error().what());
  return r.value();
}

void expect_clean_closed(const MeshReport& r, std::size_t components = 1) {
  EXPECT_TRUE(r.closed);
  EXPECT_TRUE(r.oriented);
  EXPECT_EQ(r.boundary_edges, 0u);
  EXPECT_EQ(r.non_manifold_edges, 0u);
  EXPECT_EQ(r.inconsistent_edges, 0u);
  EXPECT_EQ(r.degenerate_triangles, 0u);
  EXPECT_EQ(r.components, components);
}

/// Box [lo, lo + size] with n x n cells per face, each face with its own vertices (the
/// seams are duplicated, as in files written face by face).
IndexedMesh tessellated_box(Vec3 lo, Vec3 size, int n) {
  IndexedMesh m;
  auto coord = [&](int axis, int i) { return lo[axis] + size[axis] * Real(i) / Real(n); };
  for (int a = 0; a < 3; ++a) {
    const int u = (a + 1) % 3;
    const int v = (a + 2) % 3;
    for (int side = 0; side < 2; ++side) {
      const auto base = static_cast<std::uint32_t>(m.vertices.size());
      for (int j = 0; j <= n; ++j) {
        for (int i = 0; i <= n; ++i) {
          Vec3 p;
          p[a] = side ? lo[a] + size[a] : lo[a];
          p[u] = coord(u, i);
          p[v] = coord(v, j);
          m.vertices.push_back(p);
        }
      }
      auto id = [&](int i, int j) { return base + static_cast<std::uint32_t>(j * (n + 1) + i); };
      for (int j = 0; j < n; ++j) {
        for (int i = 0; i < n; ++i) {
          // e_u x e_v = e_a: counter-clockwise in (u, v) faces +a.
          TriangleIndices t0{id(i, j), id(i + 1, j), id(i + 1, j + 1)};
          TriangleIndices t1{id(i, j), id(i + 1, j + 1), id(i, j + 1)};
          if (!side) {
            std::swap(t0[1], t0[2]);
            std::swap(t1[1], t1[2]);
          }
          m.triangles.push_back(t0);
          m.triangles.push_back(t1);
        }
      }
    }
  }
  return m;
}

/// Latitude-longitude sphere (poles single vertices, no seam duplicate), radius r(dir)
/// given by `radius`, outward triangles.
template <class Radius>
IndexedMesh lat_long_sphere(int stacks, int slices, Radius radius) {
  IndexedMesh m;
  const double pi = 3.14159265358979323846;
  auto dir = [&](int i, int j) {
    const double th = pi * i / stacks;
    const double ph = 2 * pi * j / slices;
    return Vec3(Real(std::sin(th) * std::cos(ph)), Real(std::sin(th) * std::sin(ph)), Real(std::cos(th)));
  };
  m.vertices.push_back(radius(Vec3(0, 0, 1)) * Vec3(0, 0, 1));
  for (int i = 1; i < stacks; ++i) {
    for (int j = 0; j < slices; ++j) {
      const Vec3 d = dir(i, j);
      m.vertices.push_back(radius(d) * d);
    }
  }
  m.vertices.push_back(radius(Vec3(0, 0, -1)) * Vec3(0, 0, -1));
  const auto south = static_cast<std::uint32_t>(m.vertices.size() - 1);
  auto id = [&](int i, int j) { return static_cast<std::uint32_t>(1 + (i - 1) * slices + (j % slices)); };
  for (int j = 0; j < slices; ++j) {
    m.triangles.push_back({0, id(1, j), id(1, j + 1)});
    m.triangles.push_back({south, id(stacks - 1, j + 1), id(stacks - 1, j)});
  }
  for (int i = 1; i < stacks - 1; ++i) {
    for (int j = 0; j < slices; ++j) {
      m.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      m.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  }
  return m;
}

// ---------------------------------------------------------------------------------------
// Hand-built cases.

TEST(IndexedMesh, CleanCube) {
  const IndexedMesh cube = unit_cube();
  const MeshReport r = analysed(cube);
  expect_clean_closed(r);
  EXPECT_EQ(r.input_vertices, 8u);
  EXPECT_EQ(r.input_triangles, 12u);
  EXPECT_NEAR(double(r.volume), 1.0, 1e-6);
  EXPECT_NEAR(double(r.surface_area), 6.0, 1e-5);
  EXPECT_NEAR(reference_volume(cube), 1.0, 1e-6);

  const RepairedMesh rep = repaired(cube);
  expect_clean_closed(rep.report);
  EXPECT_EQ(rep.report.welded_vertices + rep.report.flipped_triangles + rep.report.duplicate_triangles_removed +
                rep.report.degenerate_triangles_removed + rep.report.unused_vertices_removed,
            0u);
  EXPECT_EQ(rep.mesh.vertices, cube.vertices);
  EXPECT_EQ(rep.mesh.triangles, cube.triangles);
}

TEST(IndexedMesh, DuplicatedVertexIsWelded) {
  IndexedMesh cube = unit_cube();
  cube.vertices.push_back(cube.vertices[0]);  // vertex 8 == vertex 0
  for (std::size_t t = 0; t < cube.triangles.size(); t += 3) {
    for (auto& k : cube.triangles[t]) {
      if (k == 0) k = 8;
    }
  }
  const MeshReport before = analysed(cube);
  EXPECT_FALSE(before.closed);
  EXPECT_GT(before.boundary_edges, 0u);

  const RepairedMesh rep = repaired(cube);
  expect_clean_closed(rep.report);
  EXPECT_EQ(rep.report.welded_vertices, 1u);
  EXPECT_EQ(rep.report.unused_vertices_removed, 0u);
  EXPECT_EQ(rep.mesh.vertices.size(), 8u);
  EXPECT_EQ(rep.mesh.triangles.size(), 12u);
  EXPECT_NEAR(double(rep.report.volume), 1.0, 1e-6);

  // With a near (not exact) copy: welded by the default distance, not by distance zero.
  cube.vertices[8] = cube.vertices[0] + Vec3(Real(1e-7), 0, 0);
  MeshRepairOptions exact;
  exact.weld_distance = 0;
  EXPECT_EQ(repaired(cube, exact).report.welded_vertices, 0u);
  MeshRepairOptions wide;
  wide.weld_distance = Real(1e-3);
  EXPECT_EQ(repaired(cube, wide).report.welded_vertices, 1u);
  cube.vertices[8] = cube.vertices[0] + Vec3(Real(0.01), 0, 0);
  EXPECT_EQ(repaired(cube).report.welded_vertices, 0u);
  EXPECT_EQ(repaired(cube, wide).report.welded_vertices, 0u);
  wide.weld_distance = Real(0.02);
  EXPECT_EQ(repaired(cube, wide).report.welded_vertices, 1u);
}

TEST(IndexedMesh, FlippedFace) {
  IndexedMesh cube = unit_cube();
  std::swap(cube.triangles[5][1], cube.triangles[5][2]);
  const MeshReport r = analysed(cube);
  EXPECT_TRUE(r.closed);
  EXPECT_FALSE(r.oriented);
  EXPECT_EQ(r.inconsistent_edges, 3u);
  EXPECT_EQ(r.boundary_edges, 0u);

  const RepairedMesh rep = repaired(cube);
  expect_clean_closed(rep.report);
  EXPECT_EQ(rep.report.flipped_triangles, 1u);
  EXPECT_EQ(rep.mesh.triangles, unit_cube().triangles);  // the cycle kept, only two swapped
  EXPECT_NEAR(double(rep.report.volume), 1.0, 1e-6);

  MeshRepairOptions no_orient;
  no_orient.orient_consistently = false;
  EXPECT_EQ(repaired(cube, no_orient).report.inconsistent_edges, 3u);
}

TEST(IndexedMesh, InsideOutCubeIsTurnedOutward) {
  IndexedMesh cube = unit_cube();
  for (auto& t : cube.triangles) std::swap(t[0], t[1]);
  const MeshReport r = analysed(cube);
  EXPECT_TRUE(r.closed);
  EXPECT_TRUE(r.oriented);  // consistent, but inward
  EXPECT_NEAR(double(r.volume), -1.0, 1e-6);
  const RepairedMesh rep = repaired(cube);
  expect_clean_closed(rep.report);
  EXPECT_EQ(rep.report.flipped_triangles, 12u);
  EXPECT_NEAR(double(rep.report.volume), 1.0, 1e-6);
  EXPECT_NEAR(reference_volume(rep.mesh), 1.0, 1e-6);
}

TEST(IndexedMesh, MissingFaceIsABoundary) {
  IndexedMesh cube = unit_cube();
  cube.triangles.pop_back();
  const MeshReport r = analysed(cube);
  EXPECT_FALSE(r.closed);
  EXPECT_TRUE(r.oriented);
  EXPECT_EQ(r.boundary_edges, 3u);
  EXPECT_EQ(r.components, 1u);
  EXPECT_NEAR(double(r.surface_area), 5.5, 1e-5);

  // An open mesh with a minority of flipped triangles gets the majority winding.
  std::swap(cube.triangles[0][1], cube.triangles[0][2]);
  std::swap(cube.triangles[7][1], cube.triangles[7][2]);
  const RepairedMesh rep = repaired(cube);
  EXPECT_TRUE(rep.report.oriented);
  EXPECT_FALSE(rep.report.closed);
  EXPECT_EQ(rep.report.boundary_edges, 3u);
  EXPECT_EQ(rep.report.flipped_triangles, 2u);
  IndexedMesh expected = unit_cube();
  expected.triangles.pop_back();
  EXPECT_EQ(rep.mesh.triangles, expected.triangles);
}

TEST(IndexedMesh, FinIsNonManifold) {
  IndexedMesh cube = unit_cube();
  // A triangle standing on the cube's edge 0-1 (y = 0, z = 0), pointing away.
  cube.vertices.push_back(Vec3(Real(0.5), Real(-1), Real(-1)));
  cube.triangles.push_back({0, 1, 8});
  const MeshReport r = analysed(cube);
  EXPECT_EQ(r.non_manifold_edges, 1u);
  EXPECT_EQ(r.boundary_edges, 2u);
  EXPECT_EQ(r.components, 1u);
  EXPECT_FALSE(r.closed);

  const RepairedMesh rep = repaired(cube);
  EXPECT_EQ(rep.report.non_manifold_edges, 1u);
  EXPECT_EQ(rep.mesh.triangles.size(), 13u);
  EXPECT_TRUE(rep.report.oriented);
  // The cube's own patch is still closed through the other edges: it keeps outward winding.
  EXPECT_NEAR(reference_volume(rep.mesh), 1.0, 1e-5);  // the fin adds a flat tetrahedron
  for (std::size_t t = 0; t < 12; ++t) {
    EXPECT_EQ(rep.mesh.triangles[t], unit_cube().triangles[t]) << t;
  }
}

TEST(IndexedMesh, TwoDisjointCubes) {
  IndexedMesh m = unit_cube();
  const IndexedMesh second = unit_cube(Vec3(3, 0, 0), Real(2));
  for (const Vec3& v : second.vertices) m.vertices.push_back(v);
  for (auto t : second.triangles) {
    for (auto& k : t) k += 8;
    std::swap(t[1], t[2]);  // the second cube inside out
    m.triangles.push_back(t);
  }
  const MeshReport r = analysed(m);
  EXPECT_EQ(r.components, 2u);
  EXPECT_TRUE(r.closed);
  EXPECT_TRUE(r.oriented);
  EXPECT_NEAR(double(r.volume), 1.0 - 8.0, 1e-5);
  const RepairedMesh rep = repaired(m);
  expect_clean_closed(rep.report, 2);
  EXPECT_EQ(rep.report.flipped_triangles, 12u);
  EXPECT_NEAR(double(rep.report.volume), 9.0, 1e-5);
  EXPECT_NEAR(reference_volume(rep.mesh), 9.0, 1e-5);
  EXPECT_NEAR(double(rep.report.surface_area), 6.0 + 24.0, 1e-4);
}

TEST(IndexedMesh, DegenerateTrianglesAreRemoved) {
  IndexedMesh cube = unit_cube();
  cube.triangles.push_back({0, 0, 1});                                           // repeated index
  cube.vertices.push_back(Vec3(Real(0.5), 0, 0));                                // midpoint of edge 0-1
  cube.triangles.push_back({0, 8, 1});                                           // collinear, distinct indices
  cube.vertices.push_back(Vec3(Real(0.25), Real(0.5) * kRelativeTolerance, 0));  // sliver
  cube.triangles.push_back({0, 1, 9});
  const MeshReport r = analysed(cube);
  EXPECT_EQ(r.degenerate_triangles, 3u);

  MeshRepairOptions keep;
  keep.remove_degenerate = false;
  keep.weld_distance = 0;
  const RepairedMesh kept = repaired(cube, keep);
  EXPECT_EQ(kept.report.degenerate_triangles, 3u);
  EXPECT_EQ(kept.report.degenerate_triangles_removed, 0u);

  const RepairedMesh rep = repaired(cube);
  expect_clean_closed(rep.report);
  EXPECT_EQ(rep.report.degenerate_triangles_removed, 3u);
  EXPECT_EQ(rep.report.unused_vertices_removed, 2u);
  EXPECT_EQ(rep.mesh.vertices.size(), 8u);
  EXPECT_EQ(rep.mesh.triangles.size(), 12u);
}

TEST(IndexedMesh, DuplicateTrianglesAreRemoved) {
  IndexedMesh cube = unit_cube();
  cube.triangles.push_back(cube.triangles[3]);                                                   // same winding
  cube.triangles.push_back({cube.triangles[7][0], cube.triangles[7][2], cube.triangles[7][1]});  // reversed
  cube.triangles.push_back({cube.triangles[9][1], cube.triangles[9][2], cube.triangles[9][0]});  // rotated
  const MeshReport r = analysed(cube);
  EXPECT_EQ(r.non_manifold_edges, 9u);
  EXPECT_FALSE(r.closed);

  const RepairedMesh rep = repaired(cube);
  expect_clean_closed(rep.report);
  EXPECT_EQ(rep.report.duplicate_triangles_removed, 3u);
  EXPECT_EQ(rep.mesh.triangles, unit_cube().triangles);  // first occurrences kept

  MeshRepairOptions keep;
  keep.remove_duplicates = false;
  EXPECT_EQ(repaired(cube, keep).mesh.triangles.size(), 15u);
}

TEST(IndexedMesh, UnusedVerticesAreRemovedWithRemap) {
  IndexedMesh cube = unit_cube();
  cube.vertices.insert(cube.vertices.begin(), Vec3(9, 9, 9));  // unused, shifts every index
  for (auto& t : cube.triangles) {
    for (auto& k : t) ++k;
  }
  cube.vertices.push_back(Vec3(-9, 0, 0));
  const RepairedMesh rep = repaired(cube);
  expect_clean_closed(rep.report);
  EXPECT_EQ(rep.report.unused_vertices_removed, 2u);
  EXPECT_EQ(rep.mesh.vertices, unit_cube().vertices);
  EXPECT_EQ(rep.mesh.triangles, unit_cube().triangles);

  MeshRepairOptions keep;
  keep.remove_unused = false;
  EXPECT_EQ(repaired(cube, keep).mesh.vertices.size(), 10u);
}

TEST(IndexedMesh, MoebiusStripCannotBeOriented) {
  // A strip of n quads whose ends are glued with a half twist.
  const int n = 12;
  IndexedMesh m;
  const double pi = 3.14159265358979323846;
  for (int i = 0; i < n; ++i) {
    const double a = 2 * pi * i / n;
    for (int s = -1; s <= 1; s += 2) {
      const double w = 0.3 * s;
      const double r = 1 + w * std::cos(a / 2);
      m.vertices.push_back(Vec3(Real(r * std::cos(a)), Real(r * std::sin(a)), Real(w * std::sin(a / 2))));
    }
  }
  for (int i = 0; i < n; ++i) {
    const auto a0 = std::uint32_t(2 * i);
    const auto a1 = std::uint32_t(2 * i + 1);
    std::uint32_t b0 = std::uint32_t(2 * ((i + 1) % n));
    std::uint32_t b1 = b0 + 1;
    if (i == n - 1) std::swap(b0, b1);  // the twist
    m.triangles.push_back({a0, b0, b1});
    m.triangles.push_back({a0, b1, a1});
  }
  const RepairedMesh rep = repaired(m);
  EXPECT_FALSE(rep.report.oriented);
  EXPECT_GE(rep.report.inconsistent_edges, 1u);
  EXPECT_FALSE(rep.report.closed);
  EXPECT_EQ(rep.report.components, 1u);
  EXPECT_EQ(rep.report.boundary_edges, std::size_t(2 * n));
}

TEST(IndexedMesh, Errors) {
  IndexedMesh empty;
  empty.vertices = unit_cube().vertices;
  auto r = analyse_mesh(empty);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().code, ErrorCode::TooFew);
  EXPECT_EQ(r.error().field, "triangles");
  EXPECT_FALSE(repair_mesh(empty).ok());

  IndexedMesh bad = unit_cube();
  bad.triangles[4][2] = 8;
  r = analyse_mesh(bad);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().code, ErrorCode::OutOfRange);
  EXPECT_EQ(r.error().field, "triangles[4][2]");
  auto rr = repair_mesh(bad);
  ASSERT_FALSE(rr.ok());
  EXPECT_EQ(rr.error().field, "triangles[4][2]");

  {
    test::ScopedNoFpTraps no_traps;
    IndexedMesh nan = unit_cube();
    nan.vertices[7].x = std::numeric_limits<Real>::quiet_NaN();
    r = analyse_mesh(nan);
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(r.error().code, ErrorCode::NotFinite);
    EXPECT_EQ(r.error().field, "vertices[7].x");
    IndexedMesh inf = unit_cube();
    inf.vertices[2].z = -std::numeric_limits<Real>::infinity();
    rr = repair_mesh(inf);
    ASSERT_FALSE(rr.ok());
    EXPECT_EQ(rr.error().code, ErrorCode::NotFinite);
    EXPECT_EQ(rr.error().field, "vertices[2].z");
  }
  IndexedMesh huge = unit_cube();
  huge.vertices[3].y = kMaxCoordinate * Real(2);
  r = analyse_mesh(huge);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().code, ErrorCode::OutOfRange);
  EXPECT_EQ(r.error().field, "vertices[3].y");
}

TEST(IndexedMesh, RepairCanLeaveNoTriangle) {
  IndexedMesh m;
  m.vertices = {Vec3(0), Vec3(1, 0, 0), Vec3(2, 0, 0)};
  m.triangles = {{0, 1, 2}, {0, 0, 1}};
  const RepairedMesh rep = repaired(m);
  EXPECT_TRUE(rep.mesh.triangles.empty());
  EXPECT_TRUE(rep.mesh.vertices.empty());
  EXPECT_EQ(rep.report.degenerate_triangles_removed, 2u);
  EXPECT_FALSE(rep.report.closed);
  EXPECT_EQ(rep.report.volume, Real(0));
}

// ---------------------------------------------------------------------------------------
// Analytic volume and area.

TEST(IndexedMesh, TessellatedBoxVolumeAndArea) {
  for (const Real scale : {Real(1e-4), Real(1), Real(1e4)}) {
    for (const int n : {1, 3, 8}) {
      const Vec3 size = scale * Vec3(Real(1), Real(2), Real(0.5));
      const Vec3 lo = scale * Vec3(Real(-0.3), Real(0.7), Real(2));
      const IndexedMesh m = tessellated_box(lo, size, n);
      const MeshReport raw = analysed(m);
      EXPECT_EQ(raw.components, 6u);
      EXPECT_EQ(raw.boundary_edges, std::size_t(6 * 4 * n));

      const RepairedMesh rep = repaired(m);
      expect_clean_closed(rep.report);
      const std::size_t expected_vertices = std::size_t(6 * (n - 1) * (n - 1) + 12 * (n - 1) + 8);
      EXPECT_EQ(rep.mesh.vertices.size(), expected_vertices) << n;
      EXPECT_EQ(rep.report.welded_vertices, m.vertices.size() - expected_vertices);
      EXPECT_EQ(rep.report.flipped_triangles, 0u);
      const double volume = double(size.x) * size.y * size.z;
      const double area = 2.0 * (double(size.x) * size.y + double(size.y) * size.z + double(size.z) * size.x);
      const double tol = kFloat ? 2e-5 : 1e-12;
      EXPECT_NEAR(double(rep.report.volume), volume, tol * volume) << scale << " " << n;
      EXPECT_NEAR(double(rep.report.surface_area), area, tol * area);
      EXPECT_NEAR(reference_volume(rep.mesh), volume, (kFloat ? 1e-4 : 1e-10) * volume);
    }
  }
}

TEST(IndexedMesh, SphereVolumeAndAreaWithinInscribedBounds) {
  // A convex polyhedron inscribed in the sphere of radius r contains the ball of radius h
  // (its smallest face distance from the centre), so 4/3 pi h^3 <= V <= 4/3 pi r^3 and
  // 4 pi h^2 <= A <= 4 pi r^2 (area is monotone for nested convex bodies).
  const double pi = 3.14159265358979323846;
  for (const int k : {8, 32, 96}) {
    const double r = 2.5;
    IndexedMesh m = lat_long_sphere(k, 2 * k, [&](const Vec3&) { return Real(r); });
    const RepairedMesh rep = repaired(m);
    expect_clean_closed(rep.report);
    double h = r;
    for (const auto& t : rep.mesh.triangles) {
      const Vec3 a = rep.mesh.vertices[t[0]];
      const Vec3 n = glm::normalize(glm::cross(rep.mesh.vertices[t[1]] - a, rep.mesh.vertices[t[2]] - a));
      EXPECT_GT(double(glm::dot(n, a)), 0.0);  // outward
      h = std::min(h, double(glm::dot(n, a)));
    }
    const double slack = kFloat ? 1e-5 : 1e-12;
    const double v = double(rep.report.volume);
    const double ar = double(rep.report.surface_area);
    EXPECT_LE(v, 4.0 / 3.0 * pi * r * r * r * (1 + slack));
    EXPECT_GE(v, 4.0 / 3.0 * pi * h * h * h * (1 - slack));
    EXPECT_LE(ar, 4.0 * pi * r * r * (1 + slack));
    EXPECT_GE(ar, 4.0 * pi * h * h * (1 - slack));
    if (k == 96) {
      EXPECT_NEAR(v, 4.0 / 3.0 * pi * r * r * r, 5e-3 * v);
    }
  }
}

// ---------------------------------------------------------------------------------------
// Seeded sweep: scramble a closed mesh and check that repair restores it.

/// Scrambles `m`: vertex copies (exact) used by some triangles, shuffled vertex and triangle
/// arrays, cyclic rotation of each triangle, flipped triangles, duplicated triangles.
IndexedMesh scramble(const IndexedMesh& m, test::Random& rng, std::size_t& flips, std::size_t& duplicates) {
  IndexedMesh s = m;
  const std::size_t nv = s.vertices.size();
  for (auto& t : s.triangles) {
    for (auto& k : t) {
      if (rng.integer(0, 9) == 0) {
        s.vertices.push_back(s.vertices[k]);
        k = static_cast<std::uint32_t>(s.vertices.size() - 1);
      }
    }
  }
  (void)nv;
  std::vector<std::uint32_t> perm(s.vertices.size());
  std::iota(perm.begin(), perm.end(), 0u);
  std::shuffle(perm.begin(), perm.end(), rng.engine());
  std::vector<Vec3> moved(s.vertices.size());
  for (std::size_t i = 0; i < perm.size(); ++i) moved[perm[i]] = s.vertices[i];
  s.vertices = moved;
  flips = 0;
  for (auto& t : s.triangles) {
    for (auto& k : t) k = perm[k];
    std::rotate(t.begin(), t.begin() + rng.integer(0, 2), t.end());
    if (rng.integer(0, 3) == 0) {
      std::swap(t[1], t[2]);
      ++flips;
    }
  }
  duplicates = 0;
  const std::size_t nt = s.triangles.size();
  for (std::size_t i = 0; i < nt / 10; ++i) {
    TriangleIndices t = s.triangles[static_cast<std::size_t>(rng.integer(0, int(nt) - 1))];
    if (rng.integer(0, 1)) std::swap(t[0], t[1]);
    s.triangles.push_back(t);
    ++duplicates;
  }
  std::shuffle(s.triangles.begin(), s.triangles.end(), rng.engine());
  return s;
}

/// Directed triangles as position triples, rotated so the smallest position comes first.
std::multiset<std::array<std::array<Real, 3>, 3>> directed_triangles(const IndexedMesh& m) {
  std::multiset<std::array<std::array<Real, 3>, 3>> out;
  for (const auto& t : m.triangles) {
    std::array<std::array<Real, 3>, 3> p;
    for (int i = 0; i < 3; ++i) {
      const Vec3& v = m.vertices[t[static_cast<std::size_t>(i)]];
      p[static_cast<std::size_t>(i)] = {v.x, v.y, v.z};
    }
    std::rotate(p.begin(), std::min_element(p.begin(), p.end()), p.end());
    out.insert(p);
  }
  return out;
}

TEST(IndexedMesh, ScrambledClosedMeshesAreRestored) {
  test::Random rng(0x5eed1234);
  int cases = 0;
  for (int iter = 0; iter < 60; ++iter) {
    // A star-shaped blob (random radial bumps on a lat-long sphere), sometimes two blobs.
    const int k = rng.integer(3, 12);
    const Vec3 c1 = rng.vec3(-1, 1);
    const Vec3 c2 = rng.vec3(-1, 1);
    const Real a1 = rng.uniform(Real(0), Real(0.3));
    const Real a2 = rng.uniform(Real(0), Real(0.3));
    const Real scale = rng.uniform(Real(0.5), Real(3));
    IndexedMesh original = lat_long_sphere(k, rng.integer(3, 16), [&](const Vec3& d) {
      return scale * (Real(1) + a1 * std::sin(Real(3) * d.x + c1.y) * std::cos(Real(2) * d.y + c1.z) + a2 * d.z * d.z);
    });
    const bool two = iter % 3 == 0;
    if (two) {
      const IndexedMesh second = lat_long_sphere(4, 5, [&](const Vec3&) { return Real(0.7); });
      const auto base = static_cast<std::uint32_t>(original.vertices.size());
      for (const Vec3& v : second.vertices) original.vertices.push_back(v + Vec3(10, 0, 0) + c2);
      for (auto t : second.triangles) {
        for (auto& i : t) i += base;
        original.triangles.push_back(t);
      }
    }
    const double volume = reference_volume(original);
    ASSERT_GT(volume, 0.0);

    std::size_t flips = 0;
    std::size_t duplicates = 0;
    const IndexedMesh scrambled = scramble(original, rng, flips, duplicates);
    const RepairedMesh rep = repaired(scrambled);
    expect_clean_closed(rep.report, two ? 2u : 1u);
    EXPECT_EQ(rep.mesh.vertices.size(), original.vertices.size()) << iter;
    EXPECT_EQ(rep.mesh.triangles.size(), original.triangles.size()) << iter;
    EXPECT_EQ(rep.report.duplicate_triangles_removed, duplicates);
    EXPECT_EQ(rep.report.welded_vertices, scrambled.vertices.size() - original.vertices.size());
    EXPECT_NEAR(double(rep.report.volume), volume, (kFloat ? 1e-5 : 1e-12) * volume) << iter;
    EXPECT_NEAR(reference_volume(rep.mesh), volume, (kFloat ? 1e-4 : 1e-10) * volume) << iter;
    // Every triangle is back with its original (outward) winding.
    EXPECT_EQ(directed_triangles(rep.mesh), directed_triangles(original)) << iter;
    ++cases;
  }
  EXPECT_EQ(cases, 60);
}

}  // namespace test_indexed_mesh
}  // namespace proxima
