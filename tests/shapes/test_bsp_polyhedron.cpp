// BspPolyhedron (src/midphase/bsp_polyhedron.cpp) checked against the generalised winding
// number (Jacobson et al. 2013, solid-angle sum in double, written in solid_test_meshes.hpp)
// and brute-force distances to the surface.
//
// Meshes: boxes, tetrahedra, an icosphere (320 and 1280 triangles), an L-shaped prism and a
// square ring (voxel boundaries, many coplanar faces), a parametric torus, and one of them far
// from the origin. Checked: seeded random points classify as the winding number says (a
// disagreement is allowed only within a few tolerances of the surface, where OnBoundary is
// the expected answer); OnBoundary is never given farther than a few tolerances from the
// surface; points on faces, edges and vertices are OnBoundary; the inside intervals of random
// segments agree with dense sampling of the winding number; invalid meshes are rejected.
// Tree quality: on convex solids (icosphere, UV sphere, tessellated box) pure autopartition
// (axis_planes = false) gives a chain as deep as the number of face planes, while the
// default (axis-aligned candidate planes) stays within a small multiple of log2(n), and both
// classify alike. Coplanar faces facing each other (two boxes touching face to face) keep the
// right inside/outside on both sides.
#include <gtest/gtest.h>

#include <proxima/core/tolerance.hpp>
#include <proxima/shapes/bsp_polyhedron.hpp>

#include <cmath>
#include <string>
#include <vector>

#include "support/random.hpp"
#include "support/solid_test_meshes.hpp"

namespace proxima {
namespace test_bsp_polyhedron {

struct NamedMesh {
  std::string name;
  IndexedMesh mesh;
};

std::vector<NamedMesh> solids() {
  std::vector<NamedMesh> v;
  v.push_back({"box", test::box_mesh(Vec3(-1, -0.5, -0.25), Vec3(1, 0.5, 0.25))});
  v.push_back({"tetra", test::tetra_mesh(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0.2f, 1, 0), Vec3(0.3f, 0.3f, 1))});
  v.push_back({"sphere", test::icosphere_mesh(3, Real(1))});
  v.push_back({"l_shape", test::l_shape_mesh()});
  v.push_back({"ring", test::ring_mesh()});
  v.push_back({"torus", test::torus_mesh(Real(1), Real(0.35), 24, 12)});
  v.push_back({"far_torus", test::translated(test::torus_mesh(Real(1), Real(0.35), 16, 10), Vec3(100, -50, 20))});
  return v;
}

Aabb box_of(const IndexedMesh& m) {
  Aabb b;
  for (const Vec3& v : m.vertices) b.grow(v);
  return b;
}

TEST(BspPolyhedron, RandomPointsAgreeWithWindingNumber) {
  test::Random rng(20261121);
  for (const NamedMesh& nm : solids()) {
    SCOPED_TRACE(nm.name);
    const Result<BspPolyhedron> built = BspPolyhedron::create(nm.mesh);
    ASSERT_TRUE(built.ok()) << built.error().what();
    const BspPolyhedron& bsp = *built;
    const Aabb box = box_of(nm.mesh);
    const Vec3 pad = box.extents() * Real(0.2);
    const double tol = double(bsp.tolerance());
    int inside = 0;
    int outside = 0;
    int boundary = 0;
    const int n = 1000;
    for (int i = 0; i < n; ++i) {
      const Vec3 p = rng.in_box(box.min - pad, box.max + pad);
      const PointClass c = bsp.classify(p);
      const double w = test::winding_number(nm.mesh, p);
      const PointClass expected = w > 0.5 ? PointClass::Inside : PointClass::Outside;
      ASSERT_TRUE(std::abs(w) < 1e-6 || std::abs(w - 1) < 1e-6 || test::surface_distance(nm.mesh, p).first < 1e-6)
          << "winding number " << w;
      if (c != expected) {
        const double d = test::surface_distance(nm.mesh, p).first;
        EXPECT_EQ(c, PointClass::OnBoundary) << "point " << p.x << " " << p.y << " " << p.z << " w " << w;
        EXPECT_LE(d, 4 * tol) << "point " << p.x << " " << p.y << " " << p.z;
      }
      EXPECT_EQ(bsp.contains(p), c != PointClass::Outside);
      inside += c == PointClass::Inside;
      outside += c == PointClass::Outside;
      boundary += c == PointClass::OnBoundary;
    }
    EXPECT_GT(inside, n / 40);  // the tetrahedron fills about 5% of its padded box
    EXPECT_GT(outside, n / 20);
    EXPECT_LE(boundary, n / 100);
  }
}

TEST(BspPolyhedron, PointsNearTheSurface) {
  // Points at random small offsets from the surface: within the tolerance they must be
  // OnBoundary, beyond a few tolerances they must agree with the winding number.
  test::Random rng(77);
  for (const NamedMesh& nm : solids()) {
    SCOPED_TRACE(nm.name);
    const BspPolyhedron bsp = BspPolyhedron::create(nm.mesh).value();
    const double tol = double(bsp.tolerance());
    for (int i = 0; i < 250; ++i) {
      const auto& t = nm.mesh.triangles[static_cast<std::size_t>(rng.integer(0, int(nm.mesh.triangles.size()) - 1))];
      Real u = rng.uniform(Real(0), Real(1));
      Real v = rng.uniform(Real(0), Real(1));
      if (u + v > Real(1)) {
        u = Real(1) - u;
        v = Real(1) - v;
      }
      const Vec3 a = nm.mesh.vertices[t[0]];
      const Vec3 b = nm.mesh.vertices[t[1]];
      const Vec3 c = nm.mesh.vertices[t[2]];
      const Vec3 on = a + u * (b - a) + v * (c - a);
      const Vec3 dir = rng.unit_vector();
      const Real offset = Real(tol) * rng.uniform(Real(-20), Real(20));
      const Vec3 p = on + offset * dir;
      const PointClass cls = bsp.classify(p);
      const double d = test::surface_distance(nm.mesh, p).first;
      if (d <= 0.5 * tol) {
        EXPECT_EQ(cls, PointClass::OnBoundary) << "distance " << d << " tol " << tol;
      } else if (d > 4 * tol) {
        const double w = test::winding_number(nm.mesh, p);
        EXPECT_EQ(cls, w > 0.5 ? PointClass::Inside : PointClass::Outside) << "distance " << d << " tol " << tol;
      } else if (cls == PointClass::OnBoundary) {
        EXPECT_LE(d, 4 * tol);
      }
    }
  }
}

TEST(BspPolyhedron, VerticesEdgesAndFacesAreOnBoundary) {
  for (const NamedMesh& nm : solids()) {
    SCOPED_TRACE(nm.name);
    const BspPolyhedron bsp = BspPolyhedron::create(nm.mesh).value();
    for (const Vec3& v : nm.mesh.vertices) EXPECT_EQ(bsp.classify(v), PointClass::OnBoundary);
    const std::size_t stride = nm.mesh.triangles.size() > 600 ? 5 : 1;  // keeps sanitizer runs short
    for (std::size_t i = 0; i < nm.mesh.triangles.size(); i += stride) {
      const TriangleIndices& t = nm.mesh.triangles[i];
      const Vec3 a = nm.mesh.vertices[t[0]];
      const Vec3 b = nm.mesh.vertices[t[1]];
      const Vec3 c = nm.mesh.vertices[t[2]];
      EXPECT_EQ(bsp.classify((a + b) * Real(0.5)), PointClass::OnBoundary);
      EXPECT_EQ(bsp.classify(a + Real(0.3) * (c - a)), PointClass::OnBoundary);
      EXPECT_EQ(bsp.classify((a + b + c) / Real(3)), PointClass::OnBoundary);
      EXPECT_TRUE(bsp.contains((a + b + c) / Real(3)));
    }
  }
}

TEST(BspPolyhedron, SegmentsAgreeWithSampledWindingNumber) {
  test::Random rng(4242);
  for (const NamedMesh& nm : solids()) {
    SCOPED_TRACE(nm.name);
    if (nm.mesh.triangles.size() > 600) continue;  // keep the sampling affordable
    const BspPolyhedron bsp = BspPolyhedron::create(nm.mesh).value();
    const double tol = double(bsp.tolerance());
    const Aabb box = box_of(nm.mesh);
    const Vec3 pad = box.extents() * Real(0.3);
    int with_intervals = 0;
    for (int s = 0; s < 40; ++s) {
      auto random_point = [&] { return rng.in_box(box.min - pad, box.max + pad); };
      const Vec3 p = random_point();
      const Vec3 q = random_point();
      const Ray ray{p, q - p};
      std::vector<BspInterval> intervals;
      bsp.classify_segment(ray, Real(1), intervals);
      with_intervals += !intervals.empty();
      for (std::size_t i = 0; i < intervals.size(); ++i) {
        EXPECT_LT(intervals[i].t_enter, intervals[i].t_exit);
        EXPECT_GE(intervals[i].t_enter, Real(0));
        EXPECT_LE(intervals[i].t_exit, Real(1));
        if (i > 0) {
          EXPECT_LT(intervals[i - 1].t_exit, intervals[i].t_enter);
        }
        // Interval ends strictly inside the segment lie on the surface.
        for (const Real t : {intervals[i].t_enter, intervals[i].t_exit}) {
          if (t > Real(0) && t < Real(1)) {
            EXPECT_LE(test::surface_distance(nm.mesh, ray.at(t)).first, 4 * tol);
          }
        }
      }
      const std::optional<BspInterval> first = bsp.first_interval(ray, Real(1));
      ASSERT_EQ(first.has_value(), !intervals.empty());
      if (first) {
        EXPECT_EQ(first->t_enter, intervals[0].t_enter);
        EXPECT_EQ(first->t_exit, intervals[0].t_exit);
      }
      const double length = double(glm::length(q - p));
      const int samples = 100;
      for (int k = 0; k <= samples; ++k) {
        const Real t = Real(k) / Real(samples);
        bool in = false;
        for (const BspInterval& iv : intervals) in = in || (t >= iv.t_enter && t <= iv.t_exit);
        const double w = test::winding_number(nm.mesh, ray.at(t));
        if (in != (w > 0.5)) {
          // Only where the sample is within rounding of an interval end.
          double gap = 1e30;
          for (const BspInterval& iv : intervals) {
            gap = std::min({gap, std::abs(double(t - iv.t_enter)), std::abs(double(t - iv.t_exit))});
          }
          EXPECT_LE(gap * length, 4 * tol) << "t " << t << " w " << w;
        }
      }
    }
    EXPECT_GT(with_intervals, 10);
  }
}

TEST(BspPolyhedron, RayThroughBoxAnalytic) {
  const IndexedMesh mesh = test::box_mesh(Vec3(-1), Vec3(1));
  const BspPolyhedron bsp = BspPolyhedron::create(mesh).value();
  EXPECT_EQ(bsp.stats().node_count, 6u);  // one plane per face; no split
  EXPECT_EQ(bsp.stats().split_faces, 0u);
  const std::optional<BspInterval> hit = bsp.first_interval({Vec3(-3, 0.2f, 0.1f), Vec3(1, 0, 0)}, Real(10));
  ASSERT_TRUE(hit.has_value());
  EXPECT_NEAR(hit->t_enter, 2, 1e-5);
  EXPECT_NEAR(hit->t_exit, 4, 1e-5);
  // Starting inside: enters at 0; ending inside: leaves at max_t.
  const std::optional<BspInterval> inner = bsp.first_interval({Vec3(0), Vec3(0, 0, 1)}, Real(0.5));
  ASSERT_TRUE(inner.has_value());
  EXPECT_EQ(inner->t_enter, 0);
  EXPECT_EQ(inner->t_exit, Real(0.5));
  // Infinite max_t is allowed; NaN or negative max_t and non-finite rays give nothing.
  const std::optional<BspInterval> far = bsp.first_interval({Vec3(0, 0, -5), Vec3(0, 0, 2)}, kRealMax * Real(2));
  ASSERT_TRUE(far.has_value());
  EXPECT_NEAR(far->t_enter, 2, 1e-5);
  EXPECT_NEAR(far->t_exit, 3, 1e-5);
  EXPECT_FALSE(bsp.first_interval({Vec3(0), Vec3(1, 0, 0)}, Real(-1)).has_value());
  {
    test::ScopedNoFpTraps no_traps;
    const Real nan = std::numeric_limits<Real>::quiet_NaN();
    EXPECT_FALSE(bsp.first_interval({Vec3(0), Vec3(1, 0, 0)}, nan).has_value());
    EXPECT_FALSE(bsp.first_interval({Vec3(nan), Vec3(1, 0, 0)}, Real(1)).has_value());
    EXPECT_EQ(bsp.classify(Vec3(nan)), PointClass::Outside);
  }
  // A ray missing the box.
  EXPECT_FALSE(bsp.first_interval({Vec3(-3, 2, 0), Vec3(1, 0, 0)}, Real(10)).has_value());
}

TEST(BspPolyhedron, TwoIntervalsThroughTheRing) {
  const IndexedMesh mesh = test::ring_mesh();  // [0, 1.5]^2 x [0, 0.5] minus [0.5, 1]^2 x [0, 0.5]
  const BspPolyhedron bsp = BspPolyhedron::create(mesh).value();
  std::vector<BspInterval> iv;
  bsp.classify_segment({Vec3(-1, 0.75f, 0.25f), Vec3(1, 0, 0)}, Real(4), iv);
  ASSERT_EQ(iv.size(), 2u);
  EXPECT_NEAR(iv[0].t_enter, 1.0, 1e-5);
  EXPECT_NEAR(iv[0].t_exit, 1.5, 1e-5);
  EXPECT_NEAR(iv[1].t_enter, 2.0, 1e-5);
  EXPECT_NEAR(iv[1].t_exit, 2.5, 1e-5);
  EXPECT_EQ(bsp.classify(Vec3(0.75f, 0.75f, 0.25f)), PointClass::Outside);  // the hole
  EXPECT_EQ(bsp.classify(Vec3(0.25f, 0.75f, 0.25f)), PointClass::Inside);
}

TEST(BspPolyhedron, RejectsInvalidMeshes) {
  IndexedMesh box = test::box_mesh(Vec3(-1), Vec3(1));
  {
    IndexedMesh open = box;
    open.triangles.pop_back();
    const Result<BspPolyhedron> r = BspPolyhedron::create(open);
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(r.error().field, "mesh");
  }
  {
    IndexedMesh inward = box;
    for (TriangleIndices& t : inward.triangles) std::swap(t[1], t[2]);
    const Result<BspPolyhedron> r = BspPolyhedron::create(inward);
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(r.error().field, "mesh");
  }
  {
    IndexedMesh inconsistent = box;
    std::swap(inconsistent.triangles[3][1], inconsistent.triangles[3][2]);
    EXPECT_FALSE(BspPolyhedron::create(inconsistent).ok());
  }
  EXPECT_FALSE(BspPolyhedron::create(IndexedMesh{}).ok());
  {
    IndexedMesh bad_index = box;
    bad_index.triangles[0][0] = 99;
    EXPECT_FALSE(BspPolyhedron::create(bad_index).ok());
  }
  BspBuildOptions options;
  options.split_weight = Real(2);
  EXPECT_FALSE(BspPolyhedron::create(box, options).ok());
}

TEST(BspPolyhedron, SplitWeightExtremesStayCorrect) {
  // Pure balance (0) and pure split avoidance (1) build different trees that classify alike.
  const IndexedMesh mesh = test::torus_mesh(Real(1), Real(0.4), 16, 8);
  test::Random rng(9);
  for (const Real k : {Real(0), Real(0.5), Real(1)}) {
    BspBuildOptions options;
    options.split_weight = k;
    options.max_candidates = 1000;
    const BspPolyhedron bsp = BspPolyhedron::create(mesh, options).value();
    for (int i = 0; i < 300; ++i) {
      const Vec3 p = rng.vec3(Real(-1.6), Real(1.6));
      const PointClass c = bsp.classify(p);
      if (c == PointClass::OnBoundary) continue;
      EXPECT_EQ(c == PointClass::Inside, test::winding_number(mesh, p) > 0.5) << "k " << k;
    }
  }
}

TEST(BspPolyhedron, AxisPlanesBalanceConvexSolids) {
  struct Convex {
    std::string name;
    IndexedMesh mesh;
    std::uint32_t planes;  // distinct face planes
  };
  std::vector<Convex> convex;
  convex.push_back({"icosphere", test::icosphere_mesh(3, Real(1)), 1280u});
  convex.push_back({"uv_sphere", test::tessellate_sphere(Real(1), 32, 16), 32u * 16u});  // planar quads, cap fans
  test::Random rng(606);
  for (const Convex& c : convex) {
    SCOPED_TRACE(c.name);
    BspBuildOptions chain_options;
    chain_options.axis_planes = false;
    const BspPolyhedron chain = BspPolyhedron::create(c.mesh, chain_options).value();
    const BspPolyhedron balanced = BspPolyhedron::create(c.mesh).value();
    // Every face plane leaves all other faces behind it: a chain of one node per plane
    // (nearly flat neighbours within the plane thickness are consumed with it).
    EXPECT_EQ(chain.stats().depth, chain.stats().node_count);
    EXPECT_LE(chain.stats().node_count, c.planes);
    EXPECT_GE(chain.stats().node_count, c.planes * 9 / 10);
    // Balanced: a few times log2(n) (the cap fans of the UV sphere, whose triangles all meet
    // at the pole, still take a short chain of face planes each).
    const double log_n = std::log2(double(c.mesh.triangles.size()));
    EXPECT_LE(double(balanced.stats().depth), 6 * log_n) << "nodes " << balanced.stats().node_count;
    EXPECT_LE(balanced.stats().depth * 8, chain.stats().depth);
    EXPECT_LE(balanced.stats().node_count, 4 * c.mesh.triangles.size());
    for (int i = 0; i < 500; ++i) {
      const Vec3 p = rng.vec3(Real(-1.2), Real(1.2));
      const PointClass a = chain.classify(p);
      const PointClass b = balanced.classify(p);
      if (a == PointClass::OnBoundary || b == PointClass::OnBoundary) continue;
      EXPECT_EQ(a, b);
      EXPECT_EQ(b == PointClass::Inside, test::winding_number(c.mesh, p) > 0.5);
    }
  }
  // A box whose faces are 8 x 8 grids: the six face planes (each consuming 128 coplanar
  // triangles) beat every axis plane, as with autopartition.
  const BspPolyhedron box = BspPolyhedron::create(test::welded(test::tessellate_box(Vec3(1, 2, 3), 8))).value();
  EXPECT_EQ(box.stats().node_count, 6u);
  EXPECT_EQ(box.stats().split_faces, 0u);
}

TEST(BspPolyhedron, FacesTouchingFaceToFace) {
  // Two boxes touching along z = 0 (separate vertices): the top face of the lower one and the
  // bottom face of the upper one are coplanar and face each other.
  IndexedMesh two = test::box_mesh(Vec3(-1, -1, -1), Vec3(1, 1, 0));
  const IndexedMesh upper = test::box_mesh(Vec3(-0.5f, -0.5f, 0), Vec3(0.5f, 0.5f, 1));
  const auto base = static_cast<std::uint32_t>(two.vertices.size());
  two.vertices.insert(two.vertices.end(), upper.vertices.begin(), upper.vertices.end());
  for (TriangleIndices t : upper.triangles) {
    for (std::uint32_t& i : t) i += base;
    two.triangles.push_back(t);
  }
  const BspPolyhedron bsp = BspPolyhedron::create(two).value();
  test::Random rng(31337);
  int inside = 0;
  for (int i = 0; i < 2000; ++i) {
    const Vec3 p = rng.vec3(Real(-1.3), Real(1.3));
    const PointClass c = bsp.classify(p);
    if (c == PointClass::OnBoundary) {
      EXPECT_LE(test::surface_distance(two, p).first, 4 * double(bsp.tolerance()));
      continue;
    }
    // The winding number is 1 in either box, 0 outside (and 1/2 + 1/2 on the shared patch).
    EXPECT_EQ(c == PointClass::Inside, test::winding_number(two, p) > 0.5) << p.x << " " << p.y << " " << p.z;
    inside += c == PointClass::Inside;
  }
  EXPECT_GT(inside, 200);
  EXPECT_EQ(bsp.classify(Vec3(0.2f, 0.1f, 0.3f)), PointClass::Inside);
  EXPECT_EQ(bsp.classify(Vec3(0.2f, 0.1f, -0.3f)), PointClass::Inside);
  EXPECT_EQ(bsp.classify(Vec3(0.8f, 0.8f, 0.3f)), PointClass::Outside);
}

}  // namespace test_bsp_polyhedron
}  // namespace proxima
