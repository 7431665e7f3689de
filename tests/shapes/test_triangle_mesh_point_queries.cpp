// TriangleMesh point queries (src/midphase/triangle_mesh_point_queries.cpp): closest point
// (signed for closed meshes), containment and mass properties.
//
// References: brute force over every triangle (closest point on each triangle in double, in
// solid_test_meshes.hpp), the generalised winding number in double for the inside/outside
// sign, analytic volume, centroid and inertia of tessellated boxes and of an L-shaped union of
// cubes (parallel-axis theorem), and the primitive Sphere::closest_point for a tessellated
// sphere (within the tessellation's own error). The same checks run on the internal routines
// with a linear scan (no BVH) and on TriangleMesh (with its BVH), seeded sweeps of thousands
// of points.
//
// Containment through the BSP (closed meshes): TriangleMesh::contains equals the reference
// detail::mesh_contains (pseudo-normal at the nearest point) on every point, random ones and
// ones placed at multiples of the tolerance off faces, edges and vertices, and equals the
// winding number wherever the point is farther than the tolerance from the surface; the lazy
// build is raced from several threads. Open meshes: the fast winding number stays within its
// own error bound of the exact sum, and contains equals (exact winding number >= 1/2) on every
// point.
#include <gtest/gtest.h>

#include <proxima/core/tolerance.hpp>
#include <proxima/shapes/sphere.hpp>
#include <proxima/shapes/triangle_mesh.hpp>

#include <atomic>
#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "shapes/mesh_point_queries.hpp"
#include "support/random.hpp"
#include "support/solid_test_meshes.hpp"
#include "sweep_size.hpp"

namespace proxima {
namespace test_triangle_mesh_point_queries {

struct Prepared {
  std::string name;
  IndexedMesh mesh;
  std::vector<std::array<std::uint32_t, 3>> neighbors;
  Aabb box;
  detail::MeshView view(bool closed) const {
    detail::MeshView v;
    v.vertices = mesh.vertices;
    v.triangles = mesh.triangles;
    v.neighbors = neighbors;
    v.closed = closed;
    v.scale = max_abs_component(box.extents());
    return v;
  }
};

Prepared prepare(std::string name, IndexedMesh mesh) {
  Prepared p;
  p.name = std::move(name);
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> edge_owner;
  for (std::uint32_t t = 0; t < mesh.triangles.size(); ++t) {
    for (int e = 0; e < 3; ++e) {
      edge_owner[{mesh.triangles[t][std::size_t(e)], mesh.triangles[t][std::size_t((e + 1) % 3)]}] = t;
    }
  }
  p.neighbors.resize(mesh.triangles.size());
  for (std::uint32_t t = 0; t < mesh.triangles.size(); ++t) {
    for (int e = 0; e < 3; ++e) {
      const auto it = edge_owner.find({mesh.triangles[t][std::size_t((e + 1) % 3)], mesh.triangles[t][std::size_t(e)]});
      p.neighbors[t][std::size_t(e)] = it == edge_owner.end() ? kNoIndex : it->second;
    }
  }
  for (const Vec3& v : mesh.vertices) p.box.grow(v);
  p.mesh = std::move(mesh);
  return p;
}

std::vector<Prepared> closed_meshes() {
  std::vector<Prepared> v;
  v.push_back(prepare("box", test::box_mesh(Vec3(-1, -0.5, -0.25), Vec3(1, 0.5, 0.25))));
  v.push_back(prepare("tetra", test::tetra_mesh(Vec3(0), Vec3(1, 0, 0), Vec3(0.2f, 1, 0), Vec3(0.3f, 0.3f, 1))));
  v.push_back(prepare("sphere", test::icosphere_mesh(3, Real(1))));
  v.push_back(prepare("l_shape", test::l_shape_mesh()));
  v.push_back(prepare("ring", test::ring_mesh()));
  v.push_back(prepare("torus", test::torus_mesh(Real(1), Real(0.35), 24, 12)));
  return v;
}

Vec3 random_point_near(test::Random& rng, const Aabb& box) {
  const Vec3 pad = box.extents() * Real(0.3);
  return rng.in_box(box.min - pad, box.max + pad);
}

// Checks one closest-point answer against brute force and the winding number.
void check_closest(const Prepared& m, const Vec3& p, const SurfacePoint& sp, bool closed) {
  const double brute = test::surface_distance(m.mesh, p).first;
  const double tol = 1e-5 * (1 + double(max_abs_component(m.box.extents())));
  EXPECT_NEAR(std::abs(double(sp.signed_distance)), brute, tol);
  // The point lies on the surface and at the reported distance.
  EXPECT_NEAR(test::surface_distance(m.mesh, sp.point).first, 0, tol);
  EXPECT_NEAR(double(glm::length(p - sp.point)), std::abs(double(sp.signed_distance)), tol);
  EXPECT_NEAR(double(glm::length(sp.normal)), 1, 1e-4);
  if (closed && brute > tol) {
    const bool inside = test::winding_number(m.mesh, p) > 0.5;
    EXPECT_EQ(sp.signed_distance < 0, inside) << "point " << p.x << " " << p.y << " " << p.z;
    // Outward normal: along (p - point) outside, against it inside.
    const Vec3 dir = (p - sp.point) / std::abs(sp.signed_distance);
    EXPECT_NEAR(double(glm::dot(dir, sp.normal)), inside ? -1 : 1, 1e-3);
  }
  if (!closed) {
    EXPECT_GE(sp.signed_distance, 0);
  }
}

TEST(MeshPointQueries, ClosestPointAgreesWithBruteForceScan) {
  test::Random rng(20261121);
  for (const Prepared& m : closed_meshes()) {
    SCOPED_TRACE(m.name);
    const detail::MeshView view = m.view(true);
    for (int i = 0; i < 400; ++i) {
      const Vec3 p = random_point_near(rng, m.box);
      check_closest(m, p, detail::mesh_closest_point(view, Bvh{}, p), true);
      const bool inside = test::winding_number(m.mesh, p) > 0.5;
      const double d = test::surface_distance(m.mesh, p).first;
      if (d > 1e-4) {
        EXPECT_EQ(detail::mesh_contains(view, Bvh{}, p), inside);
      }
    }
  }
}

TEST(MeshPointQueries, PointsNearEdgesAndVerticesGetTheRightSign) {
  // Points pushed off vertices and edge midpoints in random directions: the nearest feature is
  // then often a vertex or an edge, where only the pseudo-normal decides the sign correctly.
  test::Random rng(31);
  for (const Prepared& m : closed_meshes()) {
    SCOPED_TRACE(m.name);
    const detail::MeshView view = m.view(true);
    for (int i = 0; i < 300; ++i) {
      const auto& t = m.mesh.triangles[std::size_t(rng.integer(0, int(m.mesh.triangles.size()) - 1))];
      const Vec3 a = m.mesh.vertices[t[0]];
      const Vec3 b = m.mesh.vertices[t[1]];
      const Vec3 base = i % 2 == 0 ? a : (a + b) * Real(0.5);
      const Vec3 p = base + rng.vector_of_length(Real(1e-3), Real(0.05));
      const SurfacePoint sp = detail::mesh_closest_point(view, Bvh{}, p);
      check_closest(m, p, sp, true);
    }
    // On the surface: distance zero, contained.
    for (const Vec3& v : m.mesh.vertices) {
      EXPECT_TRUE(detail::mesh_contains(view, Bvh{}, v));
      EXPECT_NEAR(detail::mesh_closest_point(view, Bvh{}, v).signed_distance, 0, 1e-6);
    }
  }
}

TEST(MeshPointQueries, OpenMeshUsesWindingNumber) {
  // A box without its top: the winding number inside is about 1 - (solid angle of the hole).
  IndexedMesh box = test::box_mesh(Vec3(-1), Vec3(1));
  IndexedMesh open = box;
  std::vector<TriangleIndices> kept;
  for (const TriangleIndices& t : open.triangles) {
    bool top = true;
    for (const std::uint32_t i : t) top = top && open.vertices[i].z > 0;
    if (!top) kept.push_back(t);
  }
  ASSERT_EQ(kept.size(), 10u);
  open.triangles = kept;
  const Prepared m = prepare("open_box", open);
  const detail::MeshView view = m.view(false);
  EXPECT_TRUE(detail::mesh_contains(view, Bvh{}, Vec3(0, 0, -0.5f)));  // w ~ 0.9
  EXPECT_FALSE(detail::mesh_contains(view, Bvh{}, Vec3(0, 0, 3)));     // far above the hole
  EXPECT_FALSE(detail::mesh_contains(view, Bvh{}, Vec3(0, 0, -3)));
  EXPECT_NEAR(detail::mesh_winding_number(view, Vec3(0)), 5.0 / 6.0, 1e-5);  // 5 of 6 faces
  test::Random rng(8);
  for (int i = 0; i < 300; ++i) {
    const Vec3 p = random_point_near(rng, m.box);
    check_closest(m, p, detail::mesh_closest_point(view, Bvh{}, p), false);
  }
  // Not closed: no mass.
  EXPECT_EQ(detail::mesh_mass_properties(view, Real(1)).volume, 0);
}

// Analytic mass properties of a union of cubes of side `cell` at density 1.
MassProperties union_of_cubes(const std::vector<std::array<int, 3>>& cells, double cell) {
  double mass = 0;
  double c[3] = {0, 0, 0};
  for (const auto& k : cells) {
    mass += cell * cell * cell;
    for (int i = 0; i < 3; ++i) c[i] += cell * cell * cell * (k[std::size_t(i)] + 0.5) * cell;
  }
  for (double& x : c) x /= mass;
  double inertia[3][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
  const double m1 = cell * cell * cell;
  for (const auto& k : cells) {
    double d[3];
    for (int i = 0; i < 3; ++i) d[i] = (k[std::size_t(i)] + 0.5) * cell - c[i];
    const double d2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) {
        inertia[i][j] += (i == j ? m1 * cell * cell / 6.0 : 0.0) + m1 * ((i == j ? d2 : 0.0) - d[i] * d[j]);
      }
    }
  }
  MassProperties r;
  r.volume = Real(mass);
  r.mass = Real(mass);
  r.centroid = Vec3(Real(c[0]), Real(c[1]), Real(c[2]));
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) r.inertia[i][j] = Real(inertia[i][j]);
  }
  return r;
}

void expect_mass_near(const MassProperties& got, const MassProperties& want, Real density) {
  const Real rel = Real(1e-4);
  EXPECT_NEAR(got.volume, want.volume, rel * want.volume);
  EXPECT_NEAR(got.mass, want.mass * density, rel * want.mass * density);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(got.centroid[i], want.centroid[i], rel * (1 + std::abs(want.centroid[i])));
  const Real scale = want.inertia[0][0] * density;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) EXPECT_NEAR(got.inertia[i][j], want.inertia[i][j] * density, rel * scale);
  }
}

TEST(MeshPointQueries, MassPropertiesOfTessellatedSolids) {
  // A 4 x 2 x 3 block of cells (a box tessellated into 2 x 2 squares), the L-shape and the ring.
  std::vector<std::array<int, 3>> block;
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 2; ++j) {
      for (int k = 0; k < 3; ++k) block.push_back({i, j, k});
    }
  }
  const std::vector<std::array<int, 3>> ell = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {0, 1, 1}};
  for (const auto& cells : {block, ell}) {
    const Prepared m = prepare("cells", test::voxel_mesh(cells, Real(0.5)));
    const MassProperties want = union_of_cubes(cells, 0.5);
    expect_mass_near(detail::mesh_mass_properties(m.view(true), Real(2.5)), want, Real(2.5));
  }
  // A box far from the origin: the reference point keeps it accurate.
  const Prepared far = prepare("far_box", test::box_mesh(Vec3(1000, 1000, 1000), Vec3(1002, 1001, 1003)));
  const MassProperties mp = detail::mesh_mass_properties(far.view(true), Real(1));
  EXPECT_NEAR(mp.volume, 6, 1e-2);
  EXPECT_NEAR(mp.inertia[0][0], 6 * (1 + 9) / 12.0, 2e-2);
}

TEST(MeshPointQueries, TessellatedSphereMatchesThePrimitive) {
  const Real radius = Real(1.5);
  const Prepared m = prepare("sphere", test::icosphere_mesh(3, radius));
  // Tessellation error: the surface lies between the nearest face plane and the sphere.
  double min_plane = 1e30;
  for (const TriangleIndices& t : m.mesh.triangles) {
    const test::D3 a = test::to_d3(m.mesh.vertices[t[0]]);
    const test::D3 n =
        test::cross(test::sub(test::to_d3(m.mesh.vertices[t[1]]), a), test::sub(test::to_d3(m.mesh.vertices[t[2]]), a));
    min_plane = std::min(min_plane, std::abs(test::dot(n, a)) / test::norm(n));
  }
  const double error = double(radius) - min_plane;
  ASSERT_LT(error, 0.02);
  const Sphere sphere = Sphere::create(radius).value();
  test::Random rng(99);
  for (int i = 0; i < 1000; ++i) {
    const Vec3 p = rng.in_ball(Real(3));
    const SurfacePoint a = detail::mesh_closest_point(m.view(true), Bvh{}, p);
    const SurfacePoint b = sphere.closest_point(p);
    EXPECT_NEAR(a.signed_distance, b.signed_distance, error + 1e-5);
    EXPECT_LE(glm::length(a.point - b.point), 0.2);  // within a facet's size
    if (std::abs(b.signed_distance) > 0.1) {
      EXPECT_GT(glm::dot(a.normal, b.normal), 0.9);
    }
  }
}

// ---- the same through TriangleMesh (with its BVH) -------------------------------------------

TEST(TriangleMeshPointQueries, AgreesWithBruteForce) {
  test::Random rng(123);
  for (const Prepared& m : closed_meshes()) {
    SCOPED_TRACE(m.name);
    const Result<TriangleMesh> created = TriangleMesh::create(m.mesh);
    ASSERT_TRUE(created.ok()) << created.error().what();
    const TriangleMesh& mesh = *created;
    ASSERT_TRUE(mesh.is_closed());
    for (int i = 0; i < 300; ++i) {
      const Vec3 p = random_point_near(rng, m.box);
      const Prepared& ref = m;
      check_closest(ref, p, mesh.closest_point(p), true);
      const double d = test::surface_distance(m.mesh, p).first;
      if (d > 1e-4) {
        EXPECT_EQ(mesh.contains(p), test::winding_number(m.mesh, p) > 0.5);
      }
    }
    {
      test::ScopedNoFpTraps no_traps;
      const Vec3 nan(std::numeric_limits<Real>::quiet_NaN());
      EXPECT_FALSE(mesh.contains(nan));
      EXPECT_EQ(mesh.closest_point(nan).signed_distance, std::numeric_limits<Real>::infinity());
    }
  }
  const std::vector<std::array<int, 3>> ell = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {0, 1, 1}};
  const TriangleMesh l_mesh = TriangleMesh::create(test::voxel_mesh(ell, Real(0.5))).value();
  expect_mass_near(l_mesh.mass_properties(Real(3)), union_of_cubes(ell, 0.5), Real(3));
}

TEST(TriangleMeshPointQueries, PrunedDescentEqualsLinearScan) {
  // A 9216-triangle torus: the BVH descent must find exactly the linear scan's answer (same
  // per-triangle routine, ties to the lower index), also for points far away and inside.
  const Prepared m = prepare("torus", test::torus_mesh(Real(1), Real(0.35), 96, 48));
  const TriangleMesh mesh = TriangleMesh::create(m.mesh).value();
  ASSERT_EQ(mesh.triangle_count(), m.mesh.triangles.size());
  const detail::MeshView view = m.view(true);
  test::Random rng(5150);
  for (int i = 0; i < test::sweep_size(400); ++i) {
    const Vec3 p = i % 4 == 0 ? rng.vec3(Real(-20), Real(20)) : random_point_near(rng, m.box);
    const SurfacePoint a = mesh.closest_point(p);
    const SurfacePoint b = detail::mesh_closest_point(view, Bvh{}, p);
    EXPECT_EQ(a.signed_distance, b.signed_distance);
    EXPECT_EQ(mesh.contains(p), detail::mesh_contains(view, Bvh{}, p));
  }
}

// ---- containment through the BSP (closed) and the fast winding number (open) --------------

// Points on and near the surface: on faces, edges and vertices, pushed off them by a few
// multiples of the tolerance in random directions, and random points in the padded box.
std::vector<Vec3> probe_points(const IndexedMesh& m, const Aabb& box, Real tol, test::Random& rng, int count) {
  std::vector<Vec3> out;
  for (int i = 0; i < count; ++i) {
    const TriangleIndices& t = m.triangles[std::size_t(rng.integer(0, int(m.triangles.size()) - 1))];
    const Vec3 a = m.vertices[t[0]];
    const Vec3 b = m.vertices[t[1]];
    const Vec3 c = m.vertices[t[2]];
    Vec3 base;
    switch (i % 4) {
      case 0: base = a; break;
      case 1: base = a + rng.uniform(Real(0), Real(1)) * (b - a); break;
      case 2: {
        Real u = rng.uniform(Real(0), Real(1));
        Real v = rng.uniform(Real(0), Real(1));
        if (u + v > Real(1)) {
          u = Real(1) - u;
          v = Real(1) - v;
        }
        base = a + u * (b - a) + v * (c - a);
        break;
      }
      default: out.push_back(random_point_near(rng, box)); continue;
    }
    const Real scale = i % 3 == 0 ? Real(0) : tol * rng.uniform(Real(-8), Real(8));
    out.push_back(base + scale * rng.unit_vector());
  }
  return out;
}

TEST(TriangleMeshContains, BspAnswersEqualTheReference) {
  test::Random rng(4711);
  std::vector<Prepared> meshes = closed_meshes();
  meshes.push_back(prepare("uv_sphere", test::tessellate_sphere(Real(1), 24, 12)));
  meshes.push_back(prepare("grid_box", test::welded(test::tessellate_box(Vec3(1, 0.5f, 2), 6))));
  meshes.push_back(
      prepare("far_torus", test::translated(test::torus_mesh(Real(1), Real(0.35), 16, 10), Vec3(50, -20, 9))));
  for (const Prepared& m : meshes) {
    SCOPED_TRACE(m.name);
    MeshCreateOptions options;
    options.repair = false;
    const TriangleMesh mesh = TriangleMesh::create(m.mesh, options).value();
    ASSERT_TRUE(mesh.is_closed());
    const detail::MeshView view = m.view(true);
    const Real tol = linear_tolerance(max_abs_component(m.box.extents()));
    int far_checked = 0;
    for (const Vec3& p : probe_points(m.mesh, m.box, tol, rng, 800)) {
      const bool got = mesh.contains(p);
      ASSERT_EQ(got, detail::mesh_contains(view, Bvh{}, p)) << p.x << " " << p.y << " " << p.z;
      const double d = test::surface_distance(m.mesh, p).first;
      if (d > 2 * double(tol)) {
        EXPECT_EQ(got, test::winding_number(m.mesh, p) > 0.5);
        ++far_checked;
      } else if (d < 0.5 * double(tol)) {
        EXPECT_TRUE(got) << "on the surface, distance " << d;
      }
    }
    EXPECT_GT(far_checked, 200);
  }
}

TEST(TriangleMeshContains, LazyBuildFromManyThreads) {
  const Prepared m = prepare("torus", test::torus_mesh(Real(1), Real(0.35), 48, 24));
  const TriangleMesh mesh = TriangleMesh::create(m.mesh).value();
  test::Random rng(17);
  std::vector<Vec3> points;
  for (int i = 0; i < 400; ++i) points.push_back(random_point_near(rng, m.box));
  std::vector<std::vector<char>> answers(4, std::vector<char>(points.size()));
  {
    std::vector<std::thread> threads;
    for (std::size_t k = 0; k < answers.size(); ++k) {
      threads.emplace_back([&, k] {
        for (std::size_t i = 0; i < points.size(); ++i) answers[k][i] = mesh.contains(points[i]) ? 1 : 0;
      });
    }
    for (std::thread& t : threads) t.join();
  }
  const detail::MeshView view = m.view(true);
  for (std::size_t i = 0; i < points.size(); ++i) {
    const bool want = detail::mesh_contains(view, Bvh{}, points[i]);
    for (const auto& a : answers) EXPECT_EQ(a[i] != 0, want);
  }
  // A deformed copy builds its own tree for its own vertices (here: moved by +3 along x).
  std::vector<Vec3> moved(mesh.vertices().begin(), mesh.vertices().end());
  for (Vec3& v : moved) v.x += Real(3);
  const TriangleMesh shifted = mesh.deformed(moved).value();
  EXPECT_TRUE(mesh.contains(Vec3(1, 0, 0)));
  EXPECT_FALSE(shifted.contains(Vec3(1, 0, 0)));
  EXPECT_TRUE(shifted.contains(Vec3(4, 0, 0)));
}

// Open meshes: the shared-style icosphere without its top cap, a torus with a slot cut out,
// a flat grid (winding number 0 off the sheet) and an open box (five faces).
std::vector<Prepared> open_meshes() {
  std::vector<Prepared> v;
  auto without = [](IndexedMesh m, auto drop) {
    std::vector<TriangleIndices> kept;
    for (const TriangleIndices& t : m.triangles) {
      const Vec3 c = (m.vertices[t[0]] + m.vertices[t[1]] + m.vertices[t[2]]) / Real(3);
      if (!drop(c)) kept.push_back(t);
    }
    m.triangles = kept;
    return m;
  };
  v.push_back(prepare("capless_sphere",
                      without(test::icosphere_mesh(4, Real(1)), [](const Vec3& c) { return c.z > Real(0.6); })));
  v.push_back(prepare("slotted_torus", without(test::torus_mesh(Real(1), Real(0.4), 48, 24), [](const Vec3& c) {
                        return c.x > Real(0.9) && std::abs(c.y) < Real(0.2);
                      })));
  v.push_back(prepare("grid", test::flat_grid(12, 12, Real(0.25), Real(-1.5), Real(-1.5))));
  v.push_back(prepare("open_box", without(test::welded(test::tessellate_box(Vec3(1), 8)),
                                          [](const Vec3& c) { return c.z > Real(0.99); })));
  return v;
}

TEST(TriangleMeshContains, OpenMeshesFastWindingNumberIsExactWhereDefined) {
  test::Random rng(1234);
  for (const Prepared& m : open_meshes()) {
    SCOPED_TRACE(m.name);
    const TriangleMesh mesh = TriangleMesh::create(m.mesh).value();
    ASSERT_FALSE(mesh.is_closed());
    detail::MeshView view = m.view(false);
    view.vertices = mesh.vertices();
    view.triangles = mesh.triangles();
    const std::vector<detail::WindingNode> nodes = detail::build_winding_nodes(view, mesh.bvh());
    int undecided = 0;
    double worst = 0;
    const int n = 600;
    for (int i = 0; i < n; ++i) {
      const Vec3 p = i % 5 == 0 ? rng.vec3(Real(-4), Real(4)) : random_point_near(rng, m.box);
      const double exact = detail::mesh_winding_number(view, p);
      double bound = 0;
      const double fast = detail::mesh_fast_winding_number(view, mesh.bvh(), nodes, p, 2.0, 1e-3, bound);
      EXPECT_LE(std::abs(fast - exact), bound + 1e-9) << p.x << " " << p.y << " " << p.z;
      worst = std::max(worst, std::abs(fast - exact));
      // Left to the finer passes although well away from 1/2 (a flat sheet gives w near 1/2
      // close to it, where any method must look closely).
      undecided += std::abs(fast - 0.5) <= bound + 1e-9 && std::abs(exact - 0.5) > 0.02;
      // Exact agreement with the brute-force decision (a tie within rounding of 1/2 aside).
      if (std::abs(exact - 0.5) > 1e-9) {
        EXPECT_EQ(mesh.contains(p), exact >= 0.5) << "w " << exact;
        EXPECT_EQ(detail::mesh_contains_open(view, mesh.bvh(), nodes, p), exact >= 0.5);
      }
    }
    EXPECT_LT(worst, 0.05);
    EXPECT_LE(undecided, n / 20) << "points left to the finer passes";
    std::printf("%s: worst error %.2e, %d of %d points with |w - 1/2| > 0.02 left to the finer passes\n",
                m.name.c_str(), worst, undecided, n);
  }
}

}  // namespace test_triangle_mesh_point_queries
}  // namespace proxima
