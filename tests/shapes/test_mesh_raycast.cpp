// Tests of TriangleMesh creation (adjacency, active edges), deformation, bounds and ray casts.
// References: brute force over every triangle with the same watertight ray_triangle (closest,
// any, all, with culling), analytic adjacency and edge convexity of boxes and an L prism,
// transformed vertices for world_aabb; the batch API against a serial loop.

#include <gtest/gtest.h>

#include <proxima/geometry/raycast.hpp>
#include <proxima/shapes/ray_batch.hpp>
#include <proxima/shapes/triangle_mesh.hpp>

#include <algorithm>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/executor_set.hpp"
#include "support/random.hpp"
#include "support/solid_test_meshes.hpp"
#include "tessellation.hpp"

namespace proxima {
namespace test_mesh_raycast {

/// Brute force: every triangle, same tie rule (lower index), same culling rule.
bool passes(FaceCulling culling, const RayHit& h, const std::array<Vec3, 3>& t) {
  if (culling == FaceCulling::None) return true;
  const Real side = glm::dot(h.normal, glm::cross(t[1] - t[0], t[2] - t[0]));
  return culling == FaceCulling::Back ? side > 0 : side < 0;
}

std::vector<RayHit> brute_all(const TriangleMesh& mesh, const Ray& ray, Real max_t, FaceCulling culling) {
  std::vector<RayHit> out;
  for (std::uint32_t i = 0; i < mesh.triangle_count(); ++i) {
    const auto t = mesh.triangle(i);
    const auto h = geometry::ray_triangle(ray, max_t, t[0], t[1], t[2]);
    if (h && passes(culling, *h, t)) {
      out.push_back(*h);
      out.back().sub.triangle = i;
    }
  }
  std::sort(out.begin(), out.end(), [](const RayHit& a, const RayHit& b) {
    return a.t < b.t || (a.t == b.t && a.sub.triangle < b.sub.triangle);
  });
  return out;
}

/// Compares the three casts with brute force; returns whether the ray hit.
bool check_ray(const TriangleMesh& mesh, const Ray& ray, Real max_t, FaceCulling culling = FaceCulling::None) {
  const std::vector<RayHit> want = brute_all(mesh, ray, max_t, culling);
  const std::optional<RayHit> got = mesh.raycast(ray, max_t, culling);
  EXPECT_EQ(got.has_value(), !want.empty());
  if (got && !want.empty()) {
    EXPECT_EQ(got->t, want[0].t);
    EXPECT_EQ(got->sub.triangle, want[0].sub.triangle);
    EXPECT_EQ(got->point, want[0].point);
    EXPECT_EQ(got->normal, want[0].normal);
  }
  EXPECT_EQ(mesh.raycast_any(ray, max_t, culling), !want.empty());
  std::vector<RayHit> all{RayHit{}};  // appended after what is there
  mesh.raycast_all(ray, max_t, all, culling);
  EXPECT_EQ(all.size(), want.size() + 1);
  if (all.size() == want.size() + 1) {
    for (std::size_t i = 0; i < want.size(); ++i) {
      EXPECT_EQ(all[i + 1].sub.triangle, want[i].sub.triangle);
      EXPECT_EQ(all[i + 1].t, want[i].t);
    }
  }
  return !want.empty();
}

TriangleMesh make(IndexedMesh m, bool repair = true) {
  MeshCreateOptions opt;
  opt.repair = repair;
  Result<TriangleMesh> r = TriangleMesh::create(std::move(m), opt);
  EXPECT_TRUE(r.ok()) << (r.ok() ? "" : r.error().what());
  return std::move(r).value();
}

/// A soup of random, overlapping, open triangles (some tiny, some long).
IndexedMesh random_soup(test::Random& rng, int n) {
  IndexedMesh m;
  for (int i = 0; i < n; ++i) {
    const Vec3 c = rng.vec3(-4, 4);
    const Real s = rng.uniform(Real(0.05), Real(1.5));
    const auto base = static_cast<std::uint32_t>(m.vertices.size());
    for (int k = 0; k < 3; ++k) m.vertices.push_back(c + rng.in_ball(s));
    m.triangles.push_back({base, base + 1, base + 2});
  }
  return m;
}

TEST(TriangleMeshCreate, NeighboursMatchBruteForce) {
  for (const IndexedMesh& input : {test::tessellate_sphere(1, 16, 8), test::flat_grid(6, 5, Real(0.5), 0, 0),
                                   test::l_shape_mesh(), test::tessellate_box(Vec3(1, 2, 3), 3)}) {
    const TriangleMesh mesh = make(input);
    const auto tris = mesh.triangles();
    for (std::uint32_t i = 0; i < tris.size(); ++i) {
      for (int e = 0; e < 3; ++e) {
        const std::uint32_t u = tris[i][std::size_t(e)], v = tris[i][std::size_t((e + 1) % 3)];
        std::vector<std::uint32_t> users;  // other triangles using edge {u, v}
        for (std::uint32_t j = 0; j < tris.size(); ++j) {
          if (j == i) continue;
          const auto& t = tris[j];
          const bool has_u = t[0] == u || t[1] == u || t[2] == u;
          const bool has_v = t[0] == v || t[1] == v || t[2] == v;
          if (has_u && has_v) users.push_back(j);
        }
        const std::uint32_t expected = users.size() == 1 ? users[0] : kNoIndex;
        EXPECT_EQ(mesh.neighbors(i)[std::size_t(e)], expected);
      }
    }
  }
}

TEST(TriangleMeshCreate, ActiveEdgesOfSubdividedBoxAndGrid) {
  const Vec3 half(1, 2, 3);
  const TriangleMesh box = make(test::tessellate_box(half, 3));
  auto on_box_edge = [&](const Vec3& p) {  // at least two coordinates at +-half
    int n = 0;
    for (int a = 0; a < 3; ++a) n += std::abs(std::abs(p[a]) - half[a]) < Real(1e-5) ? 1 : 0;
    return n >= 2;
  };
  for (std::uint32_t i = 0; i < box.triangle_count(); ++i) {
    const auto t = box.triangle(i);
    for (int e = 0; e < 3; ++e) {
      const Vec3 mid = (t[std::size_t(e)] + t[std::size_t((e + 1) % 3)]) * Real(0.5);
      const bool convex = on_box_edge(mid);
      EXPECT_EQ(((box.active_edges(i) >> e) & 1) != 0, convex) << "triangle " << i << " edge " << e;
    }
  }
  const TriangleMesh grid = make(test::flat_grid(5, 5, Real(1), 0, 0));
  for (std::uint32_t i = 0; i < grid.triangle_count(); ++i) {
    for (int e = 0; e < 3; ++e) {
      const bool boundary = grid.neighbors(i)[std::size_t(e)] == kNoIndex;
      EXPECT_EQ(((grid.active_edges(i) >> e) & 1) != 0, boundary);
    }
  }
}

TEST(TriangleMeshCreate, ConcaveEdgesOfAnLPrismAreInactive) {
  // L prism of cells [0,1]x[0,0.5] U [0,0.5]x[0,1], z in [0,1]: the reflex edge is the line
  // x = y = 0.5; every other edge between non-coplanar faces is convex.
  const TriangleMesh mesh = make(test::l_shape_mesh());
  int concave = 0, convex = 0;
  for (std::uint32_t i = 0; i < mesh.triangle_count(); ++i) {
    const auto t = mesh.triangle(i);
    const Vec3 ni = glm::normalize(glm::cross(t[1] - t[0], t[2] - t[0]));
    for (int e = 0; e < 3; ++e) {
      const std::uint32_t j = mesh.neighbors(i)[std::size_t(e)];
      ASSERT_NE(j, kNoIndex);
      const auto u = mesh.triangle(j);
      const Vec3 nj = glm::normalize(glm::cross(u[1] - u[0], u[2] - u[0]));
      const Vec3 p = t[std::size_t(e)], q = t[std::size_t((e + 1) % 3)];
      const bool flat = glm::dot(ni, nj) > Real(0.999);
      const bool reflex = std::abs(p.x - Real(0.5)) < Real(1e-6) && std::abs(p.y - Real(0.5)) < Real(1e-6) &&
                          std::abs(q.x - Real(0.5)) < Real(1e-6) && std::abs(q.y - Real(0.5)) < Real(1e-6);
      const bool expected = !flat && !reflex;
      concave += (!flat && reflex) ? 1 : 0;
      convex += expected ? 1 : 0;
      EXPECT_EQ(((mesh.active_edges(i) >> e) & 1) != 0, expected) << "triangle " << i << " edge " << e;
    }
  }
  EXPECT_GT(concave, 0);
  EXPECT_GT(convex, 0);
}

TEST(TriangleMeshCreate, FlatEdgeAngleOption) {
  // A sphere with 16 slices has dihedral angles of at most about 2 pi / 16 between its
  // (planar) quads: those edges are active by default, every edge inactive with a threshold
  // above that; the diagonals inside a quad are flat, so inactive either way.
  MeshCreateOptions opt;
  const TriangleMesh fine = make(test::tessellate_sphere(1, 16, 8));
  opt.flat_edge_angle = Real(0.6);
  const TriangleMesh coarse = TriangleMesh::create(test::tessellate_sphere(1, 16, 8), opt).value();
  int active = 0;
  for (std::uint32_t i = 0; i < fine.triangle_count(); ++i) {
    const auto t = fine.triangle(i);
    const Vec3 ni = glm::normalize(glm::cross(t[1] - t[0], t[2] - t[0]));
    for (int e = 0; e < 3; ++e) {
      const auto u = fine.triangle(fine.neighbors(i)[std::size_t(e)]);
      const Vec3 nu = glm::normalize(glm::cross(u[1] - u[0], u[2] - u[0]));
      const bool flat = glm::dot(ni, nu) > Real(1) - Real(1e-4);
      EXPECT_EQ(((fine.active_edges(i) >> e) & 1) != 0, !flat) << i << " " << e;
      active += flat ? 0 : 1;
    }
    EXPECT_EQ(coarse.active_edges(i), 0);
  }
  EXPECT_GT(active, int(fine.triangle_count()));
}

TEST(TriangleMeshCreate, Errors) {
  IndexedMesh empty;
  EXPECT_FALSE(TriangleMesh::create(empty).ok());
  IndexedMesh bad;
  bad.vertices = {Vec3(0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
  bad.triangles = {{0, 1, 3}};
  EXPECT_FALSE(TriangleMesh::create(bad).ok());
}

TEST(TriangleMeshRaycast, RandomRaysMatchBruteForce) {
  test::Random rng(11);
  const std::vector<TriangleMesh> meshes{make(test::tessellate_sphere(1, 24, 12)), make(random_soup(rng, 300), false),
                                         make(test::flat_grid(12, 12, Real(0.5), -3, -3)),
                                         make(test::torus_mesh(2, Real(0.6), 24, 12))};
  int hits = 0, total = 0;
  for (const TriangleMesh& mesh : meshes) {
    for (int k = 0; k < 1500; ++k) {
      Ray ray{rng.vec3(-5, 5), rng.vector_of_length(Real(0.2), Real(3))};
      if (k % 3 == 0) ray.direction = rng.vec3(-1, 1) - ray.origin;  // aimed at the middle
      if (k % 50 == 0) ray.direction.y = 0;                          // axis-parallel components
      const Real max_t = k % 4 == 0 ? kRealMax : rng.uniform(0, 20);
      const FaceCulling culling =
          k % 5 == 0 ? FaceCulling::Back : (k % 5 == 1 ? FaceCulling::Front : FaceCulling::None);
      hits += check_ray(mesh, ray, max_t, culling) ? 1 : 0;
      ++total;
    }
  }
  EXPECT_GT(hits, total / 5);
  EXPECT_LT(hits, total);
}

TEST(TriangleMeshRaycast, RaysThroughVerticesAndEdgesNeverSlipThrough) {
  // From inside a closed mesh, towards every vertex and every edge midpoint (exactly the
  // cases where a non-watertight test lets a ray pass between triangles): always a hit.
  // From outside through the centre as well.
  test::Random rng(12);
  for (const IndexedMesh& input : {test::tessellate_box(Vec3(1, 1, 1), 4), test::tessellate_sphere(1, 20, 10),
                                   test::icosphere_mesh(2, Real(1.5))}) {
    const TriangleMesh mesh = make(input);
    ASSERT_TRUE(mesh.report().closed);
    std::vector<Vec3> targets(mesh.vertices().begin(), mesh.vertices().end());
    for (std::uint32_t i = 0; i < mesh.triangle_count(); ++i) {
      const auto t = mesh.triangle(i);
      for (int e = 0; e < 3; ++e) targets.push_back((t[std::size_t(e)] + t[std::size_t((e + 1) % 3)]) * Real(0.5));
    }
    for (const Vec3& target : targets) {
      for (const Vec3& origin : {Vec3(0), Vec3(Real(0.1), Real(-0.2), Real(0.05)), rng.in_ball(Real(0.5))}) {
        const Ray ray{origin, target - origin};
        EXPECT_TRUE(check_ray(mesh, ray, kRealMax)) << target.x << " " << target.y << " " << target.z;
        const Ray outside{target * Real(3), origin - target * Real(3)};
        EXPECT_TRUE(check_ray(mesh, outside, kRealMax));
        EXPECT_TRUE(mesh.raycast_any(outside, Real(1)));
      }
    }
  }
}

TEST(TriangleMeshRaycast, Culling) {
  const TriangleMesh sphere = make(test::tessellate_sphere(1, 24, 12));
  const Ray outside{Vec3(0, 0, -5), Vec3(0.01, 0.02, 1)};
  const auto none = sphere.raycast(outside, kRealMax);
  const auto back = sphere.raycast(outside, kRealMax, FaceCulling::Back);
  const auto front = sphere.raycast(outside, kRealMax, FaceCulling::Front);
  ASSERT_TRUE(none && back && front);
  EXPECT_EQ(none->sub.triangle, back->sub.triangle);
  EXPECT_NEAR(double(back->t), 4.0, 0.02);
  EXPECT_NEAR(double(front->t), 6.0, 0.02);  // leaves through the far side's back face
  const Ray inside{Vec3(0.1, 0, 0), Vec3(0, 1, 0)};
  EXPECT_FALSE(sphere.raycast(inside, kRealMax, FaceCulling::Back));
  EXPECT_FALSE(sphere.raycast_any(inside, kRealMax, FaceCulling::Back));
  EXPECT_TRUE(sphere.raycast(inside, kRealMax, FaceCulling::Front));
  std::vector<RayHit> all;
  sphere.raycast_all(outside, kRealMax, all, FaceCulling::Back);
  EXPECT_EQ(all.size(), 1u);
}

TEST(TriangleMeshRaycast, DegenerateRays) {
  const TriangleMesh sphere = make(test::tessellate_sphere(1, 12, 6));
  EXPECT_FALSE(sphere.raycast({Vec3(0), Vec3(0)}, kRealMax));
  EXPECT_FALSE(sphere.raycast({Vec3(0), Vec3(1, 0, 0)}, Real(-1)));
  EXPECT_FALSE(sphere.raycast({Vec3(0), Vec3(1, 0, 0)}, Real(0.5)));  // stops short of the surface
  EXPECT_TRUE(sphere.raycast({Vec3(0), Vec3(1, 0, 0)}, Real(1.5)));
  EXPECT_FALSE(sphere.raycast_any({Vec3(0), Vec3(0)}, kRealMax));
  // Origins beyond kMaxCoordinate (the inline rejection is skipped there) and tiny directions.
  check_ray(sphere, {Vec3(Real(1e20), Real(0.1), 0), Vec3(-1, 0, 0)}, kRealMax);
  check_ray(sphere, {Vec3(-3, Real(0.2), Real(0.1)), Vec3(Real(1e-30), 0, 0)}, kRealMax);
  check_ray(sphere, {Vec3(-3, Real(0.2), Real(0.1)), Vec3(Real(1e-30), 0, 0)}, Real(1e30));
  // Tie: a ray through a shared edge hits both triangles at the same t; the lower index wins.
  const TriangleMesh grid = make(test::flat_grid(2, 2, Real(1), 0, 0));
  const Ray down{Vec3(Real(0.5), Real(0.5), 1), Vec3(0, 0, -1)};  // the diagonal of cell (0, 0)
  const auto all = brute_all(grid, down, kRealMax, FaceCulling::None);
  ASSERT_GE(all.size(), 2u);
  EXPECT_EQ(grid.raycast(down, kRealMax)->sub.triangle, std::min(all[0].sub.triangle, all[1].sub.triangle));
}

/// The 4-wide traversal against the binary reference: closest (same triangle, t, point and
/// normal, bit for bit), any, and all (same list) agree. Returns whether the ray hit.
bool expect_same_traversals(const TriangleMesh& mesh, const Ray& ray, Real max_t, FaceCulling culling) {
  const std::optional<RayHit> wide = mesh.raycast(ray, max_t, culling, RayTraversal::Wide);
  const std::optional<RayHit> binary = mesh.raycast(ray, max_t, culling, RayTraversal::Binary);
  EXPECT_EQ(wide.has_value(), binary.has_value());
  if (wide && binary) {
    EXPECT_EQ(wide->sub.triangle, binary->sub.triangle);
    EXPECT_EQ(wide->t, binary->t);
    EXPECT_EQ(wide->point, binary->point);
    EXPECT_EQ(wide->normal, binary->normal);
  }
  EXPECT_EQ(mesh.raycast_any(ray, max_t, culling, RayTraversal::Wide),
            mesh.raycast_any(ray, max_t, culling, RayTraversal::Binary));
  std::vector<RayHit> all_wide, all_binary;
  mesh.raycast_all(ray, max_t, all_wide, culling, RayTraversal::Wide);
  mesh.raycast_all(ray, max_t, all_binary, culling, RayTraversal::Binary);
  EXPECT_EQ(all_wide.size(), all_binary.size());
  if (all_wide.size() == all_binary.size()) {
    for (std::size_t i = 0; i < all_wide.size(); ++i) {
      EXPECT_EQ(all_wide[i].sub.triangle, all_binary[i].sub.triangle);
      EXPECT_EQ(all_wide[i].t, all_binary[i].t);
    }
  }
  return binary.has_value();
}

TEST(TriangleMeshRaycast, WideTraversalEqualsBinaryReference) {
  // Random rays (aimed and not, bounded and unbounded, every culling mode), rays from inside
  // through every vertex and edge midpoint (watertightness: they must hit), grazing rays
  // from outside through vertices, and rays the wide path hands to the binary one (zero,
  // tiny and huge direction components, far origins); leaf sizes 1, 4, 8 and 13 (leaves of
  // several four-triangle blocks).
  test::Random rng(21);
  int hits = 0, total = 0;
  for (std::uint32_t leaf : {1u, 4u, 8u, 13u}) {
    MeshCreateOptions opt;
    opt.bvh.max_leaf_size = leaf;
    std::vector<TriangleMesh> meshes;
    for (IndexedMesh input : {test::torus_mesh(2, Real(0.6), 32, 16), test::icosphere_mesh(3, Real(1.5)),
                              test::flat_grid(10, 10, Real(0.5), -2, -2), random_soup(rng, 200)}) {
      opt.repair = input.triangles.size() != 200;
      meshes.push_back(TriangleMesh::create(std::move(input), opt).value());
    }
    for (std::size_t m = 0; m < meshes.size(); ++m) {
      const TriangleMesh& mesh = meshes[m];
      for (int k = 0; k < 400; ++k) {
        Ray ray{rng.vec3(-5, 5), rng.vector_of_length(Real(0.2), Real(3))};
        if (k % 2 == 0) ray.direction = rng.vec3(-1, 1) - ray.origin;
        if (k % 40 == 0) ray.direction.x = 0;
        if (k % 40 == 1) ray.direction.z = Real(1e-31);
        if (k % 40 == 2) ray.direction *= Real(1e31);
        if (k % 40 == 3) ray.origin.y = Real(1e20);
        if (k % 40 == 4) ray.origin.x = Real(1e35);
        const Real max_t = k % 3 == 0 ? kRealMax : rng.uniform(0, 12);
        const auto culling = static_cast<FaceCulling>(k % 3);
        hits += expect_same_traversals(mesh, ray, max_t, culling) ? 1 : 0;
        ++total;
      }
      if (m != 1) continue;  // the closed icosphere: rays through vertices and edges
      for (std::uint32_t i = 0; i < mesh.triangle_count(); i += 3) {
        const auto t = mesh.triangle(i);
        for (int e = 0; e < 3; ++e) {
          const Vec3 vertex = t[std::size_t(e)];
          const Vec3 mid = (vertex + t[std::size_t((e + 1) % 3)]) * Real(0.5);
          for (const Vec3& target : {vertex, mid}) {
            const Vec3 origin = rng.in_ball(Real(0.5));
            EXPECT_TRUE(expect_same_traversals(mesh, {origin, target - origin}, kRealMax, FaceCulling::None));
            EXPECT_TRUE(expect_same_traversals(mesh, {origin, target - origin}, kRealMax, FaceCulling::Front));
            expect_same_traversals(mesh, {target * Real(2) + rng.vec3(-1, 1), target - origin}, kRealMax,
                                   FaceCulling::Back);
          }
        }
      }
    }
  }
  EXPECT_GT(hits, total / 5);
  EXPECT_LT(hits, total);
#if PROXIMA_DOUBLE
  {  // bounds beyond the float layout: the binary path serves
    IndexedMesh huge = test::icosphere_mesh(2, Real(1.5));
    for (Vec3& v : huge.vertices) v *= Real(1e40);
    const TriangleMesh mesh = make(huge);
    int huge_hits = 0;
    for (int k = 0; k < 200; ++k) {
      const Vec3 o = rng.vec3(-3, 3);
      huge_hits += expect_same_traversals(mesh, {o * Real(1e40), rng.vec3(-1, 1) - o}, kRealMax, FaceCulling::None);
    }
    EXPECT_GT(huge_hits, 0);
  }
#endif
}

TEST(TriangleMeshDeform, RefittedRaysMatchBruteForce) {
  test::Random rng(13);
  const TriangleMesh mesh = make(test::tessellate_sphere(1, 24, 12));
  std::vector<Vec3> moved(mesh.vertices().begin(), mesh.vertices().end());
  for (Vec3& v : moved) v = v * Vec3(2, Real(0.5), 1) + rng.vec3(Real(-0.05), Real(0.05));
  const TriangleMesh deformed = mesh.deformed(moved).value();
  EXPECT_EQ(deformed.bvh().nodes().size(), mesh.bvh().nodes().size());
  EXPECT_EQ(deformed.vertices()[5], moved[5]);
  EXPECT_EQ(mesh.vertices()[5], TriangleMesh(mesh).vertices()[5]);  // original untouched
  for (int k = 0; k < 1000; ++k) {
    const Vec3 origin = rng.vec3(-4, 4);
    const Vec3 from = rng.vec3(-4, 4);
    check_ray(deformed, {origin, rng.vec3(-1, 1) - from}, kRealMax);
  }
  EXPECT_NEAR(double(deformed.report().volume), 4.18879 * 1.0, 0.2);
  EXPECT_FALSE(mesh.deformed(std::span<const Vec3>(moved).first(3)).ok());
  {
    test::ScopedNoFpTraps no_traps;
    moved[2].y = std::numeric_limits<Real>::quiet_NaN();
  }
  EXPECT_FALSE(mesh.deformed(moved).ok());
}

TEST(TriangleMeshBounds, WorldAabbIsTheBoxOfTheTransformedVertices) {
  test::Random rng(14);
  const TriangleMesh mesh = make(test::torus_mesh(2, Real(0.5), 16, 8));
  for (int k = 0; k < 50; ++k) {
    const Transform pose = rng.pose(10);
    Aabb want = Aabb::empty();
    for (const Vec3& v : mesh.vertices()) want.grow(pose.apply(v));
    const Aabb got = mesh.world_aabb(pose);
    for (int a = 0; a < 3; ++a) {
      EXPECT_NEAR(double(got.min[a]), double(want.min[a]), 1e-4);
      EXPECT_NEAR(double(got.max[a]), double(want.max[a]), 1e-4);
    }
  }
  const Aabb local = mesh.local_aabb();
  EXPECT_NEAR(double(local.max.x), 2.5, 1e-5);
  EXPECT_NEAR(double(local.max.z), 0.5, 1e-5);
}

TEST(RayBatch, EqualsSerialOnEveryExecutor) {
  test::Random rng(15);
  const TriangleMesh mesh = make(test::torus_mesh(2, Real(0.6), 48, 24));
  std::vector<BatchRay> rays(3000);
  for (BatchRay& r : rays) {
    const Vec3 origin = rng.vec3(-4, 4);
    const Vec3 from = rng.vec3(-4, 4);
    r.ray = {origin, rng.vec3(-2, 2) - from};
    r.max_t = rng.uniform(0, 3);
  }
  std::vector<RayHit> serial(rays.size());
  std::size_t serial_hits = 0;
  for (std::size_t i = 0; i < rays.size(); ++i) {
    const auto h = mesh.raycast(rays[i].ray, rays[i].max_t, FaceCulling::Back);
    if (h) ++serial_hits;
    serial[i] = h ? *h : RayHit{};
  }
  EXPECT_GT(serial_hits, 100u);
  RayBatchOptions opt;
  opt.min_rays_per_task = 100;
  opt.culling = FaceCulling::Back;
  auto expect_serial = [&](const std::vector<RayHit>& out, const std::string& name) {
    for (std::size_t i = 0; i < rays.size(); ++i) {
      ASSERT_EQ(out[i].sub.triangle, serial[i].sub.triangle) << name << " ray " << i;
      ASSERT_EQ(out[i].t, serial[i].t) << name << " ray " << i;
      ASSERT_EQ(out[i].point, serial[i].point) << name << " ray " << i;
    }
  };
  for (test::NamedExecutor& e : test::test_executors()) {
    std::vector<RayHit> out(rays.size());
    const Result<std::size_t> n = raycast_batch(mesh, rays, out, *e.executor, opt);
    ASSERT_TRUE(n.ok());
    EXPECT_EQ(n.value(), serial_hits) << e.name;
    expect_serial(out, e.name);
  }
  std::vector<RayHit> out(rays.size());
  ASSERT_EQ(raycast_batch(mesh, rays, out, opt).value(), serial_hits);  // serial default
  expect_serial(out, "default");
  std::vector<RayHit> small(10);
  EXPECT_FALSE(raycast_batch(mesh, rays, small).ok());
  EXPECT_FALSE(raycast_batch(mesh, rays, small, test::shared_pool(2)).ok());
}

}  // namespace test_mesh_raycast
}  // namespace proxima
