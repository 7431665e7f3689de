// ConvexHull: construction (structure, errors) and queries, each checked against a
// reference written here: the input points themselves (planes, support by linear scan
// over every input point), a fan triangulation with a brute-force point-triangle
// distance and ray-parity inside test (contains, closest_point), and marching plus
// bisection on contains (raycast).
#include <gtest/gtest.h>

#include <proxima/core/tolerance.hpp>
#include <proxima/shapes/convex_hull.hpp>
#include <proxima/shapes/placed.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <set>
#include <string>
#include <tuple>
#include <vector>

#include "support/random.hpp"

namespace proxima {
namespace test_convex_hull {

using D3 = std::array<double, 3>;

constexpr Real kEps = std::numeric_limits<Real>::epsilon();

D3 to_d(const Vec3& v) { return {double(v.x), double(v.y), double(v.z)}; }
D3 sub(const D3& a, const D3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
D3 add(const D3& a, const D3& b) { return {a[0] + b[0], a[1] + b[1], a[2] + b[2]}; }
D3 mul(const D3& a, double s) { return {a[0] * s, a[1] * s, a[2] * s}; }
double dot(const D3& a, const D3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
D3 cross(const D3& a, const D3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double norm(const D3& a) { return std::sqrt(dot(a, a)); }

// Largest |coordinate| and extent of the hull's box: the scale of every rounding error.
Real magnitude(const ConvexHull& h) {
  const Aabb b = h.local_aabb();
  const Vec3 far = glm::max(glm::abs(b.min), glm::abs(b.max));
  return std::max({h.scale(), far.x, far.y, far.z});
}

// Tolerance of checks that only involve rounding of a few operations on the data.
Real rounding_tol(const ConvexHull& h) { return Real(16) * kEps * magnitude(h); }

// ---------------------------------------------------------------------------------------
// Reference geometry, in double, over a fan triangulation of the faces.

struct Tri {
  D3 a, b, c;
};

std::vector<Tri> fan_triangles(const ConvexHull& h) {
  std::vector<Tri> tris;
  for (std::uint32_t f = 0; f < h.faces().size(); ++f) {
    const auto loop = h.face_vertices(f);
    for (std::size_t k = 1; k + 1 < loop.size(); ++k) {
      tris.push_back({to_d(h.vertices()[loop[0]]), to_d(h.vertices()[loop[k]]), to_d(h.vertices()[loop[k + 1]])});
    }
  }
  return tris;
}

// Closest point on triangle abc to p (Voronoi regions, written out for the test).
D3 closest_on_triangle(const D3& p, const D3& a, const D3& b, const D3& c) {
  const D3 ab = sub(b, a), ac = sub(c, a), ap = sub(p, a);
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= 0 && d2 <= 0) return a;
  const D3 bp = sub(p, b);
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return add(a, mul(ab, d1 / (d1 - d3)));
  const D3 cp = sub(p, c);
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return add(a, mul(ac, d2 / (d2 - d6)));
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    return add(b, mul(sub(c, b), (d4 - d3) / ((d4 - d3) + (d5 - d6))));
  }
  const double denom = va + vb + vc;
  if (!(std::abs(denom) > 0)) return a;  // degenerate sliver: its vertices bound the error
  return add(a, add(mul(ab, vb / denom), mul(ac, vc / denom)));
}

// Closest point on segment ab to p.
D3 closest_on_segment(const D3& p, const D3& a, const D3& b) {
  const D3 ab = sub(b, a);
  const double len2 = dot(ab, ab);
  if (!(len2 > 0)) return a;
  return add(a, mul(ab, std::clamp(dot(sub(p, a), ab) / len2, 0.0, 1.0)));
}

double surface_distance(const std::vector<Tri>& tris, const D3& p) {
  double best = std::numeric_limits<double>::max();
  for (const Tri& t : tris) best = std::min(best, norm(sub(p, closest_on_triangle(p, t.a, t.b, t.c))));
  return best;
}

// Largest signed distance of q in front of a face plane: 0 on the surface.
Real plane_residual(const ConvexHull& h, const Vec3& q) {
  Real worst = -kRealMax;
  for (const HullFace& f : h.faces()) worst = std::max(worst, glm::dot(f.normal, q) - f.offset);
  return worst;
}

// Ray parity: p is inside when a ray from it crosses the closed surface an odd number of
// times. Directions that pass too close to a triangle edge are retried. Returns -1 when
// undecidable (p on the surface).
int parity_inside(const std::vector<Tri>& tris, const D3& p, test::Random& rng) {
  for (int attempt = 0; attempt < 20; ++attempt) {
    const Vec3 dr = rng.unit_vector();
    const D3 d = to_d(dr);
    int crossings = 0;
    bool ambiguous = false;
    for (const Tri& t : tris) {
      // Moller-Trumbore with barycentric margins.
      const D3 e1 = sub(t.b, t.a), e2 = sub(t.c, t.a);
      const D3 pv = cross(d, e2);
      const double det = dot(e1, pv);
      const double scale = norm(e1) * norm(e2);
      if (std::abs(det) <= 1e-12 * scale) continue;  // parallel: a neighbour is crossed instead
      const D3 tv = sub(p, t.a);
      const double u = dot(tv, pv) / det;
      const D3 qv = cross(tv, e1);
      const double v = dot(d, qv) / det;
      const double s = dot(e2, qv) / det;
      constexpr double m = 1e-7;
      if (u < -m || v < -m || u + v > 1 + m) continue;
      if (u < m || v < m || u + v > 1 - m || std::abs(s) < 1e-9 * (norm(e1) + norm(e2))) {
        ambiguous = true;
        break;
      }
      if (s > 0) ++crossings;
    }
    if (!ambiguous) return crossings % 2;
  }
  return -1;
}

// ---------------------------------------------------------------------------------------
// Point clouds.

enum class Cloud { Sphere, Box, CubeFacesEdges, Cylinder, Flat, Lattice, Small, Count };

std::vector<Vec3> make_cloud(Cloud kind, test::Random& rng) {
  std::vector<Vec3> p;
  switch (kind) {
    case Cloud::Sphere:
      for (int i = 0; i < 300; ++i) p.push_back(rng.unit_vector());
      break;
    case Cloud::Box: {
      const Vec3 h = rng.vec3(Real(0.3), Real(1));
      for (int i = 0; i < 300; ++i) p.push_back(rng.vec3(Real(-1), Real(1)) * h);
      break;
    }
    case Cloud::CubeFacesEdges: {
      // Corners, points on every face (coplanar) and on every edge (collinear), interior.
      for (int i = 0; i < 8; ++i) p.push_back(Vec3(i & 1 ? 1 : -1, i & 2 ? 1 : -1, i & 4 ? 1 : -1));
      for (int i = 0; i < 240; ++i) {
        Vec3 q = rng.vec3(Real(-1), Real(1));
        const int a = i % 3;
        q[a] = q[a] > 0 ? Real(1) : Real(-1);
        if (i % 4 == 0) q[(a + 1) % 3] = q[(a + 1) % 3] > 0 ? Real(1) : Real(-1);
        p.push_back(q);
      }
      for (int i = 0; i < 30; ++i) p.push_back(rng.vec3(Real(-0.9), Real(0.9)));
      break;
    }
    case Cloud::Cylinder: {
      const int n = 24;
      for (int i = 0; i < n; ++i) {
        const Real a = Real(2) * kPi * Real(i) / Real(n);
        for (Real z : {Real(-1), Real(1), Real(0.25)}) p.push_back(Vec3(std::cos(a), std::sin(a), z));
      }
      for (int i = 0; i < 60; ++i) {  // on the caps (coplanar)
        Vec3 q = rng.in_ball(Real(0.9));
        q.z = i % 2 ? Real(1) : Real(-1);
        p.push_back(q);
      }
      break;
    }
    case Cloud::Flat:
      for (int i = 0; i < 200; ++i) {
        Vec3 q = rng.vec3(Real(-1), Real(1));
        q.z *= Real(1e-3);
        p.push_back(q);
      }
      break;
    case Cloud::Lattice:
      for (int x = -2; x <= 2; ++x) {
        for (int y = -2; y <= 2; ++y) {
          for (int z = -2; z <= 2; ++z) p.push_back(Vec3(Real(x), Real(y), Real(z)) * Real(0.5));
        }
      }
      break;
    case Cloud::Small: {
      const int n = rng.integer(4, 9);
      for (int i = 0; i < n; ++i) p.push_back(rng.vec3(Real(-1), Real(1)));
      break;
    }
    case Cloud::Count: break;
  }
  return p;
}

struct Placement {
  Real scale;
  Real offset;
  bool rotate;
};

// Scales, far-from-origin offsets and rotations applied to every cloud kind.
const std::vector<Placement>& placements() {
  static const std::vector<Placement> kPlacements{
      {Real(1), Real(0), false},  {Real(1), Real(0), true},    {Real(1e-4), Real(0), false},
      {Real(1e4), Real(0), true}, {Real(1), Real(1e4), false}, {Real(100), Real(1e4), true},
      {Real(3), Real(-20), true},
  };
  return kPlacements;
}

std::vector<Vec3> place(std::vector<Vec3> pts, const Placement& pl, test::Random& rng) {
  const Quat q = pl.rotate ? rng.rotation() : kIdentityQuat;
  const Vec3 off = pl.offset == Real(0) ? Vec3(Real(0)) : Vec3(pl.offset, -pl.offset, Real(0.5) * pl.offset);
  for (Vec3& v : pts) v = (pl.rotate ? q * v : v) * pl.scale + off;
  return pts;
}

struct Case {
  std::string name;
  std::vector<Vec3> points;
};

std::vector<Case> sweep_cases(std::uint64_t seed, int repeats) {
  test::Random rng(seed);
  std::vector<Case> cases;
  for (int r = 0; r < repeats; ++r) {
    for (int k = 0; k < static_cast<int>(Cloud::Count); ++k) {
      for (std::size_t pi = 0; pi < placements().size(); ++pi) {
        // A slab 2e-3 thick is below float's resolution 1e4 from the origin (Degenerate,
        // see FlatBelowTheInputResolutionIsDegenerate).
        const Placement& pl = placements()[pi];
        if (k == static_cast<int>(Cloud::Flat) && sizeof(Real) == 4 && pl.offset > Real(1e3) * pl.scale) continue;
        Case c;
        c.name = "cloud " + std::to_string(k) + " placement " + std::to_string(pi) + " repeat " + std::to_string(r);
        c.points = place(make_cloud(static_cast<Cloud>(k), rng), placements()[pi], rng);
        cases.push_back(std::move(c));
      }
    }
  }
  return cases;
}

ConvexHull build(const std::vector<Vec3>& pts) {
  auto r = ConvexHull::create(pts);
  if (!r) ADD_FAILURE() << r.error().what();
  return r.value();
}

// ---------------------------------------------------------------------------------------
// Structure.

void check_structure(const ConvexHull& h, const std::vector<Vec3>& input) {
  const auto verts = h.vertices();
  const auto faces = h.faces();
  const auto edges = h.edges();
  // Merged faces are planar, and hold every input point, within the hull's tolerance.
  const Real tol = h.tolerance() + rounding_tol(h);
  ASSERT_GE(verts.size(), 4u);

  // Every hull vertex is an input point; no vertex twice.
  std::set<std::tuple<Real, Real, Real>> in;
  for (const Vec3& p : input) in.insert({p.x, p.y, p.z});
  std::set<std::tuple<Real, Real, Real>> seen;
  for (const Vec3& v : verts) {
    EXPECT_TRUE(in.count({v.x, v.y, v.z})) << "vertex is not an input point";
    EXPECT_TRUE(seen.insert({v.x, v.y, v.z}).second) << "duplicate vertex";
  }

  // Euler characteristic of a sphere.
  EXPECT_EQ(static_cast<long>(verts.size()) - static_cast<long>(edges.size()) + static_cast<long>(faces.size()), 2);

  // Every input point satisfies every face plane; faces planar, convex, CCW from outside.
  std::size_t index_total = 0;
  for (std::uint32_t fi = 0; fi < faces.size(); ++fi) {
    const HullFace& f = faces[fi];
    index_total += f.index_count;
    ASSERT_GE(f.index_count, 3u);
    EXPECT_NEAR(glm::length(f.normal), Real(1), Real(8) * kEps);
    for (const Vec3& p : input) {
      ASSERT_LE(glm::dot(f.normal, p) - f.offset, tol) << "input point outside face " << fi;
    }
    const auto loop = h.face_vertices(fi);
    D3 c{0, 0, 0};
    for (std::uint32_t vi : loop) c = add(c, to_d(verts[vi]));
    c = mul(c, 1.0 / double(loop.size()));
    D3 area{0, 0, 0};
    const D3 n = to_d(f.normal);
    for (std::size_t k = 0; k < loop.size(); ++k) {
      const D3 a = to_d(verts[loop[k]]);
      const D3 b = to_d(verts[loop[(k + 1) % loop.size()]]);
      const D3 cc = to_d(verts[loop[(k + 2) % loop.size()]]);
      area = add(area, cross(sub(a, c), sub(b, c)));
      EXPECT_NEAR(glm::dot(f.normal, verts[loop[k]]), f.offset, tol) << "face " << fi << " is not planar";
      // Convex: turns left at every vertex, up to the tolerance (b within it of line ac).
      EXPECT_GT(dot(cross(sub(b, a), sub(cc, b)), n), -double(tol) * (norm(sub(b, a)) + norm(sub(cc, b))))
          << "face " << fi << " loop is not convex";
    }
    const double al = norm(area);
    ASSERT_GT(al, 0.0);
    // CCW from outside: the loop's area vector along the outward normal (how closely is
    // bounded by the planarity check above: a piece of a merged face can tilt within it).
    EXPECT_GT(dot(area, n) / al, 0.5) << "face " << fi << " loop is not CCW seen from outside";
  }
  EXPECT_EQ(index_total, h.face_indices().size());

  // Edges: two distinct faces, traversed v0 -> v1 in face0 and v1 -> v0 in face1.
  auto has_directed = [&](std::uint32_t face, std::uint32_t a, std::uint32_t b) {
    const auto loop = h.face_vertices(face);
    for (std::size_t k = 0; k < loop.size(); ++k) {
      if (loop[k] == a && loop[(k + 1) % loop.size()] == b) return true;
    }
    return false;
  };
  std::set<std::pair<std::uint32_t, std::uint32_t>> edge_set;
  for (const HullEdge& e : edges) {
    EXPECT_NE(e.face0, e.face1);
    EXPECT_NE(e.v0, e.v1);
    EXPECT_TRUE(has_directed(e.face0, e.v0, e.v1));
    EXPECT_TRUE(has_directed(e.face1, e.v1, e.v0));
    EXPECT_TRUE(edge_set.insert({std::min(e.v0, e.v1), std::max(e.v0, e.v1)}).second) << "edge listed twice";
  }
  // Every directed loop edge is one of the listed edges (2E directed edges in the loops).
  EXPECT_EQ(h.face_indices().size(), 2 * edges.size());

  // Adjacency is exactly the edge set, symmetric.
  std::size_t adjacency_total = 0;
  for (std::uint32_t v = 0; v < verts.size(); ++v) {
    const auto nb = h.vertex_neighbors(v);
    adjacency_total += nb.size();
    EXPECT_GE(nb.size(), 3u);
    for (std::uint32_t w : nb) EXPECT_TRUE(edge_set.count({std::min(v, w), std::max(v, w)}));
  }
  EXPECT_EQ(adjacency_total, 2 * edges.size());

  // Local box = box of the input points.
  Aabb box = Aabb::empty();
  for (const Vec3& p : input) box.grow(p);
  for (int a = 0; a < 3; ++a) {
    EXPECT_NEAR(h.local_aabb().min[a], box.min[a], tol);
    EXPECT_NEAR(h.local_aabb().max[a], box.max[a], tol);
  }
}

TEST(ConvexHull, StructureOverRandomClouds) {
  int built = 0;
  for (const Case& c : sweep_cases(101, 3)) {
    SCOPED_TRACE(c.name);
    auto r = ConvexHull::create(c.points);
    ASSERT_TRUE(r.ok()) << r.error().what();
    check_structure(*r, c.points);
    ++built;
  }
  EXPECT_GE(built, 3 * (static_cast<int>(Cloud::Count) * static_cast<int>(placements().size()) - 1));
}

// ---------------------------------------------------------------------------------------
// Named cases with known topology.

std::vector<Vec3> cube_corners(Real h, const Vec3& c = Vec3(Real(0))) {
  std::vector<Vec3> p;
  for (int i = 0; i < 8; ++i) p.push_back(c + Vec3(i & 1 ? h : -h, i & 2 ? h : -h, i & 4 ? h : -h));
  return p;
}

TEST(ConvexHull, CubeWithFaceEdgeInteriorAndDuplicatePointsHasSixQuads) {
  test::Random rng(7);
  std::vector<Vec3> p = cube_corners(Real(1));
  for (int i = 0; i < 8; ++i) p.push_back(p[i]);  // duplicates
  for (int i = 0; i < 500; ++i) {
    Vec3 q = rng.vec3(Real(-1), Real(1));
    if (i % 3 != 0) q[i % 3] = q[i % 3] > 0 ? Real(1) : Real(-1);
    if (i % 5 == 0) q[(i + 1) % 3] = q[(i + 1) % 3] > 0 ? Real(1) : Real(-1);
    p.push_back(q);
  }
  const ConvexHull h = build(p);
  EXPECT_EQ(h.vertices().size(), 8u);
  EXPECT_EQ(h.edges().size(), 12u);
  ASSERT_EQ(h.faces().size(), 6u);
  for (const HullFace& f : h.faces()) {
    EXPECT_EQ(f.index_count, 4u);
    EXPECT_NEAR(std::abs(f.normal.x) + std::abs(f.normal.y) + std::abs(f.normal.z), Real(1), Real(8) * kEps);
    EXPECT_NEAR(f.offset, Real(1), Real(8) * kEps);
  }
  check_structure(h, p);
}

TEST(ConvexHull, LatticeHasEightCorners) {
  std::vector<Vec3> p;
  for (int x = 0; x <= 10; ++x) {
    for (int y = 0; y <= 10; ++y) {
      for (int z = 0; z <= 10; ++z) p.push_back(Vec3(Real(x), Real(y), Real(z)));
    }
  }
  const ConvexHull h = build(p);
  EXPECT_EQ(h.vertices().size(), 8u);
  EXPECT_EQ(h.faces().size(), 6u);
  check_structure(h, p);
}

TEST(ConvexHull, CylinderHasPolygonalCaps) {
  const int n = 48;
  std::vector<Vec3> p;
  for (int i = 0; i < n; ++i) {
    const Real a = Real(2) * kPi * Real(i) / Real(n);
    for (Real z : {Real(-2), Real(2), Real(0), Real(1)}) p.push_back(Vec3(std::cos(a), std::sin(a), z));
  }
  const ConvexHull h = build(p);
  EXPECT_EQ(h.vertices().size(), std::size_t(2 * n));
  EXPECT_EQ(h.faces().size(), std::size_t(n + 2));
  int caps = 0;
  for (const HullFace& f : h.faces()) {
    if (f.index_count == std::uint32_t(n)) {
      ++caps;
      EXPECT_NEAR(std::abs(f.normal.z), Real(1), Real(8) * kEps);
    } else {
      EXPECT_EQ(f.index_count, 4u);
    }
  }
  EXPECT_EQ(caps, 2);
  check_structure(h, p);
}

TEST(ConvexHull, TetrahedronAndOctahedron) {
  const std::vector<Vec3> tet{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
  const ConvexHull t = build(tet);
  EXPECT_EQ(t.vertices().size(), 4u);
  EXPECT_EQ(t.edges().size(), 6u);
  EXPECT_EQ(t.faces().size(), 4u);
  check_structure(t, tet);
  const std::vector<Vec3> oct{Vec3(1, 0, 0), Vec3(-1, 0, 0), Vec3(0, 1, 0), Vec3(0, -1, 0),
                              Vec3(0, 0, 1), Vec3(0, 0, -1), Vec3(0)};
  const ConvexHull o = build(oct);
  EXPECT_EQ(o.vertices().size(), 6u);
  EXPECT_EQ(o.edges().size(), 12u);
  EXPECT_EQ(o.faces().size(), 8u);
  check_structure(o, oct);
}

TEST(ConvexHull, HugeTinyAndFarCubes) {
  for (const auto& [h, c] : {std::pair{Real(1e4), Vec3(Real(0))}, std::pair{Real(1e-4), Vec3(Real(0))},
                             std::pair{Real(1), Vec3(Real(1e4), Real(-1e4), Real(1e4))},
                             std::pair{Real(1e-4), Vec3(Real(1), Real(2), Real(3))}}) {
    SCOPED_TRACE(h);
    const std::vector<Vec3> p = cube_corners(h, c);
    const ConvexHull hull = build(p);
    EXPECT_EQ(hull.vertices().size(), 8u);
    EXPECT_EQ(hull.faces().size(), 6u);
    check_structure(hull, p);
    // The corners are rounded to Real at |c| + h: that bounds what the volume can match.
    const Real side = Real(2) * h;
    const Real quantum = Real(4) * kEps * (std::max({std::abs(c.x), std::abs(c.y), std::abs(c.z)}) + h) / h;
    EXPECT_NEAR(hull.mass_properties().volume, side * side * side, (Real(1e-5) + quantum) * side * side * side);
    EXPECT_TRUE(hull.contains(c));
    EXPECT_FALSE(hull.contains(c + Vec3(Real(1.5) * h, Real(0), Real(0))));
    EXPECT_TRUE(hull.contains(c + Vec3(Real(0.5) * h, Real(0.9) * h, Real(-0.9) * h)));
  }
}

TEST(ConvexHull, NearlyFlatCloudBuilds) {
  test::Random rng(11);
  std::vector<Vec3> p;
  for (int i = 0; i < 100; ++i) {
    Vec3 q = rng.vec3(Real(-1), Real(1));
    q.z *= Real(1e-3);
    p.push_back(q);
  }
  p.push_back(Vec3(0, 0, Real(1e-3)));
  p.push_back(Vec3(0, 0, Real(-1e-3)));
  const ConvexHull h = build(p);
  check_structure(h, p);
  EXPECT_TRUE(h.contains(Vec3(0)));
  EXPECT_FALSE(h.contains(Vec3(0, 0, Real(2e-3))));
}

TEST(ConvexHull, FlatBelowTheInputResolutionIsDegenerate) {
  // 1e4 from the origin the coordinates are only known to ~eps * 1e4: a slab a few such
  // roundings thick is flat, one a hundred roundings thick is a solid.
  test::Random rng(12);
  for (const Real thickness_in_roundings : {Real(4), Real(100)}) {
    const Real thickness = thickness_in_roundings * kEps * Real(1e4);
    std::vector<Vec3> p;
    for (int i = 0; i < 100; ++i) {
      Vec3 q = rng.vec3(Real(-1), Real(1));
      q.z *= Real(0.5) * thickness;
      p.push_back(q + Vec3(Real(1e4), Real(-1e4), Real(1e4)));
    }
    p.push_back(Vec3(Real(1e4), Real(-1e4), Real(1e4) + Real(0.5) * thickness));
    p.push_back(Vec3(Real(1e4), Real(-1e4), Real(1e4) - Real(0.5) * thickness));
    auto r = ConvexHull::create(p);
    if (thickness_in_roundings < Real(10)) {
      ASSERT_FALSE(r.ok());
      EXPECT_EQ(r.error().code, ErrorCode::Degenerate);
    } else {
      ASSERT_TRUE(r.ok()) << r.error().what();
      check_structure(*r, p);
    }
  }
}

// Regression: the corners of a rotated box are coplanar only to the rounding of Real;
// merging at the input's resolution keeps six quadrilaterals, also far from the origin.
TEST(ConvexHull, RotatedBoxKeepsSixFaces) {
  test::Random rng(13);
  for (const Real offset : {Real(0), Real(1e4)}) {
    for (int k = 0; k < 20; ++k) {
      const Quat q = rng.rotation();
      const Vec3 half = rng.vec3(Real(50), Real(100));
      std::vector<Vec3> p;
      for (int i = 0; i < 8; ++i) {
        p.push_back(q * Vec3(i & 1 ? half.x : -half.x, i & 2 ? half.y : -half.y, i & 4 ? half.z : -half.z) +
                    Vec3(offset, -offset, offset));
      }
      for (int i = 0; i < 200; ++i) {  // points on the faces and edges
        Vec3 l = rng.vec3(Real(-1), Real(1));
        l[i % 3] = l[i % 3] > 0 ? Real(1) : Real(-1);
        if (i % 4 == 0) l[(i + 1) % 3] = l[(i + 1) % 3] > 0 ? Real(1) : Real(-1);
        p.push_back(q * (l * half) + Vec3(offset, -offset, offset));
      }
      const ConvexHull h = build(p);
      EXPECT_EQ(h.vertices().size(), 8u);
      EXPECT_EQ(h.faces().size(), 6u);
      check_structure(h, p);
    }
  }
}

// Regression: far from the origin in float the dot products of absolute coordinates lose
// the differences between neighbouring vertices; hill-climbing works relative to the box
// centre and over whole merged facets, and must reach the maximum from every vertex.
TEST(ConvexHull, HillClimbingFarFromTheOrigin) {
  test::Random rng(14);
  std::vector<Vec3> p;
  for (int i = 0; i < 400; ++i) p.push_back(rng.unit_vector() + Vec3(Real(1e4), Real(-1e4), Real(5e3)));
  const ConvexHull h = build(p);
  const Real tol = h.tolerance() + rounding_tol(h);
  for (int k = 0; k < 50; ++k) {
    const Vec3 d = rng.unit_vector();
    Real best = -kRealMax;
    for (const Vec3& q : p) best = std::max(best, glm::dot(q - h.local_aabb().center(), d));
    for (std::uint32_t s = 0; s < h.vertices().size(); ++s) {
      const Vec3 v = h.vertices()[h.support_index(d, s)];
      ASSERT_NEAR(glm::dot(v - h.local_aabb().center(), d), best, tol) << "start " << s;
    }
  }
}

// Regression: a thin slab merged by plane distance would lose its rim sideways; the
// merge radius is capped by the thickness, so the extreme points stay vertices.
TEST(ConvexHull, ThinSlabKeepsItsRim) {
  test::Random rng(15);
  std::vector<Vec3> p;
  // 1e3 roundings of Real, at least 1e-10 (double builds refuse slabs thinner than about
  // 1e4 roundings of double, where qhull's output is no longer reliable).
  const Real thickness = std::max(Real(1e3) * kEps, Real(1e-10));
  for (int i = 0; i < 300; ++i) {
    Vec3 q = rng.vec3(Real(-1), Real(1));
    q.z *= thickness;
    p.push_back(q);
  }
  const ConvexHull h = build(p);
  check_structure(h, p);
}

TEST(ConvexHull, CopiesShareTheirData) {
  const ConvexHull a = build(cube_corners(Real(1)));
  const ConvexHull b = a;  // NOLINT(performance-unnecessary-copy-initialization)
  EXPECT_EQ(a.vertices().data(), b.vertices().data());
  EXPECT_EQ(ConvexHull::kType, ShapeType::ConvexHull);
  EXPECT_EQ(a.core_radius(), Real(0));
}

// ---------------------------------------------------------------------------------------
// Bad input: one test per error.

TEST(ConvexHullErrors, TooFewPoints) {
  const std::vector<Vec3> three{Vec3(0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
  auto r = ConvexHull::create(three);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().code, ErrorCode::TooFew);
  EXPECT_EQ(r.error().field, "points");
  auto empty = ConvexHull::create({});
  ASSERT_FALSE(empty.ok());
  EXPECT_EQ(empty.error().code, ErrorCode::TooFew);
}

TEST(ConvexHullErrors, NaNCoordinateNamesTheField) {
  test::ScopedNoFpTraps no_traps;
  std::vector<Vec3> p = cube_corners(Real(1));
  p[2].y = std::numeric_limits<Real>::quiet_NaN();
  auto r = ConvexHull::create(p);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().code, ErrorCode::NotFinite);
  EXPECT_EQ(r.error().field, "points[2].y");
}

TEST(ConvexHullErrors, InfiniteCoordinateNamesTheField) {
  test::ScopedNoFpTraps no_traps;
  std::vector<Vec3> p = cube_corners(Real(1));
  p[5].z = std::numeric_limits<Real>::infinity();
  auto r = ConvexHull::create(p);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().code, ErrorCode::NotFinite);
  EXPECT_EQ(r.error().field, "points[5].z");
  p[5].z = Real(0);
  p[7].x = -std::numeric_limits<Real>::infinity();
  auto r2 = ConvexHull::create(p);
  ASSERT_FALSE(r2.ok());
  EXPECT_EQ(r2.error().field, "points[7].x");
}

TEST(ConvexHullErrors, OutOfRangeCoordinate) {
  std::vector<Vec3> p = cube_corners(Real(1));
  p[3].x = kMaxCoordinate * Real(2);
  auto r = ConvexHull::create(p);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().code, ErrorCode::OutOfRange);
  EXPECT_EQ(r.error().field, "points[3].x");
}

TEST(ConvexHullErrors, CoplanarPointsAreDegenerate) {
  test::Random rng(5);
  const Quat q = rng.rotation();
  std::vector<Vec3> p;
  for (int i = 0; i < 50; ++i) {
    Vec3 v = rng.vec3(Real(-1), Real(1));
    v.z = Real(0);
    p.push_back(q * v + Vec3(Real(3), Real(4), Real(5)));
  }
  auto r = ConvexHull::create(p);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().code, ErrorCode::Degenerate);
  EXPECT_EQ(r.error().field, "points");
  // Exactly planar square corners (4 points).
  auto sq = ConvexHull::create(std::vector<Vec3>{Vec3(0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0)});
  ASSERT_FALSE(sq.ok());
  EXPECT_EQ(sq.error().code, ErrorCode::Degenerate);
  // Flatter than the precision allows.
  std::vector<Vec3> thin = p;
  thin.push_back(q * Vec3(Real(0), Real(0), Real(10) * kEps) + Vec3(Real(3), Real(4), Real(5)));
  auto t = ConvexHull::create(thin);
  ASSERT_FALSE(t.ok());
  EXPECT_EQ(t.error().code, ErrorCode::Degenerate);
}

TEST(ConvexHullErrors, CollinearPointsAreDegenerate) {
  std::vector<Vec3> p;
  for (int i = 0; i < 20; ++i) p.push_back(Vec3(Real(1), Real(2), Real(3)) * Real(i) + Vec3(Real(-5)));
  auto r = ConvexHull::create(p);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().code, ErrorCode::Degenerate);
  EXPECT_EQ(r.error().field, "points");
}

TEST(ConvexHullErrors, CoincidentPointsAreDegenerate) {
  const std::vector<Vec3> p(12, Vec3(Real(1), Real(-2), Real(3)));
  auto r = ConvexHull::create(p);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().code, ErrorCode::Degenerate);
  EXPECT_EQ(r.error().field, "points");
}

// ---------------------------------------------------------------------------------------
// Support.

TEST(ConvexHull, SupportIndexMatchesLinearScanOverInputPoints) {
  test::Random rng(202);
  long checks = 0;
  for (const Case& c : sweep_cases(203, 1)) {
    SCOPED_TRACE(c.name);
    const ConvexHull h = build(c.points);
    // Input points dropped by merging lie within the hull's tolerance of its faces.
    const Real tol = h.tolerance() + rounding_tol(h);
    auto brute = [&](const Vec3& d) {
      Real best = -kRealMax;
      for (const Vec3& p : c.points) best = std::max(best, glm::dot(p, d));
      return best;
    };
    const auto n = static_cast<std::uint32_t>(h.vertices().size());
    // From every start vertex.
    for (std::uint32_t s = 0; s < n; ++s) {
      for (int k = 0; k < 4; ++k) {
        const Vec3 d = rng.unit_vector();
        const std::uint32_t i = h.support_index(d, s);
        ASSERT_LT(i, n);
        ASSERT_NEAR(glm::dot(h.vertices()[i], d), brute(d), tol) << "start " << s;
        ++checks;
      }
    }
    // Many directions with a warm start, plus the support point itself.
    std::uint32_t warm = 0;
    for (int k = 0; k < 300; ++k) {
      const Vec3 d = rng.vector_of_length(Real(0.1), Real(10));
      warm = h.support_index(d, warm);
      ASSERT_NEAR(glm::dot(h.vertices()[warm], d), brute(d), tol * glm::length(d));
      EXPECT_EQ(h.support(d), h.vertices()[h.support_index(d)]);
      EXPECT_EQ(h.core_support(d), h.support(d));
      ++checks;
    }
    // Axis directions (ties between coplanar vertices) and a zero / out-of-range start.
    for (int a = 0; a < 3; ++a) {
      for (Real s : {Real(-1), Real(1)}) {
        Vec3 d(Real(0));
        d[a] = s;
        EXPECT_NEAR(glm::dot(h.vertices()[h.support_index(d, n + 5)], d), brute(d), tol);
      }
    }
    EXPECT_LT(h.support_index(Vec3(Real(0)), 3), n);
  }
  EXPECT_GT(checks, 20000);
}

// ---------------------------------------------------------------------------------------
// Bounds.

TEST(ConvexHull, WorldAabbIsTheBoxOfTheTransformedInputPoints) {
  test::Random rng(303);
  for (const Case& c : sweep_cases(304, 1)) {
    SCOPED_TRACE(c.name);
    const ConvexHull h = build(c.points);
    for (int k = 0; k < 5; ++k) {
      const Transform pose = rng.pose(Real(50));
      Aabb ref = Aabb::empty();
      for (const Vec3& p : c.points) ref.grow(pose.apply(p));
      const Aabb box = h.world_aabb(pose);
      const Real tol = Real(64) * kEps * (magnitude(h) + Real(50));
      for (int a = 0; a < 3; ++a) {
        EXPECT_NEAR(box.min[a], ref.min[a], tol);
        EXPECT_NEAR(box.max[a], ref.max[a], tol);
      }
    }
  }
}

// ---------------------------------------------------------------------------------------
// contains and closest_point against the fan triangulation.

// A point strictly inside: a random convex combination of input points pulled towards
// their mean.
Vec3 inside_point(const std::vector<Vec3>& pts, test::Random& rng) {
  D3 mean{0, 0, 0};
  for (const Vec3& p : pts) mean = add(mean, to_d(p));
  mean = mul(mean, 1.0 / double(pts.size()));
  D3 acc{0, 0, 0};
  double wsum = 0;
  for (int k = 0; k < 4; ++k) {
    const double w = double(rng.uniform(Real(0.01), Real(1)));
    acc = add(acc, mul(to_d(pts[std::size_t(rng.integer(0, int(pts.size()) - 1))]), w));
    wsum += w;
  }
  acc = mul(acc, 1.0 / wsum);
  const D3 q = add(mean, mul(sub(acc, mean), 0.9));
  return Vec3(Real(q[0]), Real(q[1]), Real(q[2]));
}

TEST(ConvexHull, ContainsMatchesConstructionAndParity) {
  test::Random rng(404);
  long checks = 0;
  for (const Case& c : sweep_cases(405, 1)) {
    SCOPED_TRACE(c.name);
    const ConvexHull h = build(c.points);
    const auto tris = fan_triangles(h);
    const Real size = h.scale();
    const Vec3 center = h.local_aabb().center();
    // By construction: convex combinations inside, points beyond the support plane outside.
    for (int k = 0; k < 100; ++k) {
      EXPECT_TRUE(h.contains(inside_point(c.points, rng)));
      const Vec3 d = rng.unit_vector();
      Real m = -kRealMax;
      for (const Vec3& p : c.points) m = std::max(m, glm::dot(p, d));
      const Vec3 q = center + rng.in_ball(size);
      const Vec3 out = q + (m + Real(1e-3) * size + Real(2) * h.tolerance() - glm::dot(q, d)) * d;
      EXPECT_FALSE(h.contains(out)) << h.closest_point(out).signed_distance << " tol " << h.tolerance() << " m " << m
                                    << " " << glm::dot(out, d);
      checks += 2;
    }
    // Random points against ray parity, away from the surface.
    const Real margin = Real(1e-3) * size + Real(4) * h.tolerance();
    for (int k = 0; k < 150; ++k) {
      const Vec3 p = center + rng.vec3(Real(-0.8), Real(0.8)) * size;
      const D3 pd = to_d(p);
      if (surface_distance(tris, pd) < double(margin)) continue;
      const int inside = parity_inside(tris, pd, rng);
      ASSERT_NE(inside, -1);
      EXPECT_EQ(h.contains(p), inside == 1);
      EXPECT_EQ(contains(h, Transform::identity(), p), inside == 1);
      ++checks;
    }
  }
  EXPECT_GT(checks, 10000);
}

TEST(ConvexHull, ClosestPointMatchesBruteForceOverTriangles) {
  test::Random rng(505);
  long checks = 0;
  for (const Case& c : sweep_cases(506, 1)) {
    SCOPED_TRACE(c.name);
    const ConvexHull h = build(c.points);
    const auto tris = fan_triangles(h);
    const Real size = h.scale();
    const Vec3 center = h.local_aabb().center();
    const Real tol = Real(2) * h.tolerance() + rounding_tol(h);
    const Real margin = Real(1e-3) * size + Real(4) * h.tolerance();
    for (int k = 0; k < 120; ++k) {
      const Vec3 p = center + rng.vec3(Real(-1), Real(1)) * size;
      const D3 pd = to_d(p);
      const double dist = surface_distance(tris, pd);
      const SurfacePoint sp = h.closest_point(p);
      EXPECT_NEAR(glm::length(sp.normal), Real(1), Real(1e-3));
      // Distance magnitude and the point on the surface.
      ASSERT_NEAR(std::abs(double(sp.signed_distance)), dist, double(tol));
      // On the surface: on or inside every face plane and on at least one (the fan
      // triangles of thin slivers are too ill-conditioned to measure this).
      EXPECT_NEAR(plane_residual(h, sp.point), Real(0), tol);
      EXPECT_NEAR(glm::length(p - sp.point), std::abs(sp.signed_distance), tol);
      if (dist > double(margin)) {
        const int inside = parity_inside(tris, pd, rng);
        ASSERT_NE(inside, -1);
        EXPECT_EQ(sp.signed_distance < Real(0), inside == 1);
        if (inside == 1) {
          // Projection on the nearest face plane along its outward normal.
          bool is_face_normal = false;
          for (const HullFace& f : h.faces()) is_face_normal = is_face_normal || f.normal == sp.normal;
          EXPECT_TRUE(is_face_normal);
          const Vec3 back = sp.point + sp.signed_distance * sp.normal;
          for (int a = 0; a < 3; ++a) EXPECT_NEAR(back[a], p[a], tol);
        } else {
          const Vec3 n = (p - sp.point) / sp.signed_distance;
          // Both are differences of rounded points: error ~ rounding / distance.
          const Real ntol = Real(1e-4) + Real(2) * rounding_tol(h) / sp.signed_distance;
          for (int a = 0; a < 3; ++a) EXPECT_NEAR(sp.normal[a], n[a], ntol);
        }
      }
      ++checks;
    }
    // Every vertex is on the surface: distance ~0, the point itself.
    for (const Vec3& v : h.vertices()) {
      const SurfacePoint sp = h.closest_point(v);
      EXPECT_NEAR(sp.signed_distance, Real(0), tol);
    }
  }
  EXPECT_GT(checks, 5000);
}

TEST(ConvexHull, PlacedClosestPointAndSupportMapFrames) {
  test::Random rng(606);
  const ConvexHull h = build(make_cloud(Cloud::Box, rng));
  for (int k = 0; k < 200; ++k) {
    const Transform pose = rng.pose(Real(10));
    const Vec3 p = rng.vec3(Real(-12), Real(12));
    const SurfacePoint w = closest_point(h, pose, p);
    const SurfacePoint l = h.closest_point(pose.inverse_apply(p));
    EXPECT_NEAR(w.signed_distance, l.signed_distance, Real(1e-3));
    EXPECT_NEAR(glm::length(w.point - p), std::abs(w.signed_distance), Real(1e-3));
    const Vec3 d = rng.unit_vector();
    const Vec3 s = support(h, pose, d);
    const Aabb box = h.world_aabb(pose);
    EXPECT_TRUE(box.inflated(Real(1e-4)).contains(s));
  }
}

// Large hulls bound their world box by six hill-climbing support queries: the box must be
// the exact box of the transformed vertices (reference: a scan written here).
TEST(ConvexHull, WorldAabbOfLargeHullEqualsVertexScan) {
  test::Random rng(4242);
  std::vector<Vec3> cloud;
  for (int i = 0; i < 3000; ++i) cloud.push_back(rng.unit_vector() * Vec3(Real(3), Real(1), Real(0.5)));
  const ConvexHull h = ConvexHull::create(cloud).value();
  ASSERT_GT(h.vertices().size(), 512u);
  for (int k = 0; k < 300; ++k) {
    const Transform pose = rng.pose(Real(100));
    Aabb ref = Aabb::empty();
    for (const Vec3& v : h.vertices()) ref.grow(pose.apply(v));
    const Aabb box = h.world_aabb(pose);
    for (int i = 0; i < 3; ++i) {
      EXPECT_NEAR(box.min[i], ref.min[i], Real(64) * kEpsilon * Real(200)) << "pose " << k;
      EXPECT_NEAR(box.max[i], ref.max[i], Real(64) * kEpsilon * Real(200)) << "pose " << k;
    }
  }
}

// ---------------------------------------------------------------------------------------
// Ray casts against marching + bisection on contains.

// First t in [0, max_t] where the ray is inside (contains), by marching `steps` samples
// then bisecting; nullopt when no sample is inside.
std::optional<Real> march(const ConvexHull& h, const Ray& ray, Real max_t, int steps) {
  Real prev = Real(0);
  if (h.contains(ray.origin)) return Real(0);
  for (int i = 1; i <= steps; ++i) {
    const Real t = max_t * Real(i) / Real(steps);
    if (h.contains(ray.at(t))) {
      Real lo = prev, hi = t;
      for (int it = 0; it < 80; ++it) {
        const Real mid = Real(0.5) * (lo + hi);
        if (mid <= lo || mid >= hi) break;
        (h.contains(ray.at(mid)) ? hi : lo) = mid;
      }
      return hi;
    }
    prev = t;
  }
  return std::nullopt;
}

TEST(ConvexHull, RaycastMatchesMarchingOnContains) {
  test::Random rng(707);
  long hits = 0, misses = 0, grazes = 0;
  for (const Case& c : sweep_cases(708, 1)) {
    SCOPED_TRACE(c.name);
    const ConvexHull h = build(c.points);
    const auto tris = fan_triangles(h);
    const Real size = h.scale();
    const Vec3 center = h.local_aabb().center();
    const Real surface_tol = Real(2) * h.tolerance() + rounding_tol(h);
    for (int k = 0; k < 100; ++k) {
      const Real reach = rng.uniform(Real(1.2), Real(2));
      const Vec3 origin = center + rng.unit_vector() * (size * reach);
      Vec3 target = (k % 3 == 0) ? center + rng.vec3(Real(-0.7), Real(0.7)) * size : inside_point(c.points, rng);
      const Vec3 dir = (target - origin) * rng.uniform(Real(0.2), Real(3));
      const Real max_t = Real(4) * (size * Real(3)) / glm::length(dir);
      const auto hit = h.raycast({origin, dir}, max_t);
      const auto ref = march(h, {origin, dir}, max_t, 2000);
      if (!ref) {
        // Nothing inside along the ray at the sampling resolution: a hit can only graze.
        if (hit) {
          EXPECT_NEAR(plane_residual(h, hit->point), Real(0), surface_tol);
        }
        ++misses;
        continue;
      }
      if (!hit) {
        // contains is tolerant and the cast exact: they may differ only on a ray that
        // grazes the hull within tolerance, never on one that goes in deeper.
        double depth = 0;
        for (int i = 0; i <= 400; ++i) {
          const D3 q = to_d(Ray{origin, dir}.at(max_t * Real(i) / Real(400)));
          const double sd = surface_distance(tris, q);
          if (sd > depth && parity_inside(tris, q, rng) == 1) depth = sd;
        }
        EXPECT_LE(depth, double(surface_tol));
        ++grazes;
        continue;
      }
      ++hits;
      EXPECT_NEAR(glm::length(hit->normal), Real(1), Real(1e-4));
      EXPECT_LT(glm::dot(hit->normal, dir), Real(0));
      EXPECT_NEAR(plane_residual(h, hit->point), Real(0), surface_tol);
      const Real cos_in = -glm::dot(hit->normal, dir) / glm::length(dir);
      if (cos_in > Real(0.05)) {
        EXPECT_NEAR(hit->t * glm::length(dir), *ref * glm::length(dir), surface_tol / cos_in + surface_tol);
      }
      // The reported normal is the plane of a face through the hit point.
      bool on_face = false;
      for (const HullFace& f : h.faces()) {
        on_face =
            on_face || (f.normal == hit->normal && std::abs(glm::dot(f.normal, hit->point) - f.offset) <= surface_tol);
      }
      EXPECT_TRUE(on_face);
      // The same ray cut short of the hit misses.
      if (hit->t > Real(0.01)) {
        EXPECT_FALSE(h.raycast({origin, dir}, hit->t * Real(0.99)).has_value());
      }
      // Placed version: the same t, up to the rounding of the round trip through the world
      // frame, which a ray at grazing incidence turns into a large change of t.
      if (cos_in > Real(0.05)) {
        const Transform pose = rng.pose(Real(5) * size);
        const auto wh = raycast(h, pose, Ray{pose.apply(origin), pose.apply_vector(dir)}, max_t);
        if (wh) {
          EXPECT_NEAR(wh->t * glm::length(dir), hit->t * glm::length(dir),
                      (Real(8) * rounding_tol(h) + h.tolerance()) / cos_in);
        } else {
          // Missed after the round trip: only a ray entering within rounding of an edge.
          double to_edge = std::numeric_limits<double>::max();
          for (const HullEdge& e : h.edges()) {
            const D3 a = to_d(h.vertices()[e.v0]), b = to_d(h.vertices()[e.v1]);
            to_edge = std::min(to_edge, norm(sub(to_d(hit->point), closest_on_segment(to_d(hit->point), a, b))));
          }
          EXPECT_LT(to_edge, double(Real(8) * rounding_tol(h) + h.tolerance()) / double(cos_in));
        }
      }
    }
    // Rays pointing away from the hull miss.
    for (int k = 0; k < 30; ++k) {
      const Vec3 d = rng.unit_vector();
      const Vec3 origin = center + d * (size * Real(2));
      EXPECT_FALSE(h.raycast({origin, d * size}, Real(100)).has_value());
      ++misses;
    }
    // Origins inside: t = 0, normal = -direction / |direction|; zero direction too.
    for (int k = 0; k < 30; ++k) {
      const Vec3 o = inside_point(c.points, rng);
      const Vec3 d = rng.unit_vector() * Real(3);
      const auto hit = h.raycast({o, d}, Real(1));
      ASSERT_TRUE(hit.has_value());
      EXPECT_EQ(hit->t, Real(0));
      EXPECT_EQ(hit->point, o);
      for (int a = 0; a < 3; ++a) EXPECT_NEAR(hit->normal[a], -d[a] / Real(3), Real(1e-5));
      const auto still = h.raycast({o, Vec3(Real(0))}, Real(1));
      ASSERT_TRUE(still.has_value());
      EXPECT_EQ(still->t, Real(0));
      EXPECT_NEAR(glm::length(still->normal), Real(1), Real(1e-4));
    }
    EXPECT_FALSE(h.raycast({center + Vec3(Real(3) * size), Vec3(Real(0))}, Real(1)).has_value());
  }
  EXPECT_GT(hits, 3000);
  EXPECT_GT(misses, 1000);
  EXPECT_LT(grazes, 20);
}

TEST(ConvexHull, RayFromInsideKeepsMinusTheDirectionAtAnyLength) {
  // Issue 18 (defect 4): from inside, the normal is -direction / |direction|, as for every
  // other shape. The hull squared the direction's length, which underflows to 0 for a
  // direction of 1e-30 in float (and overflows for 1e30), and then answered the nearest
  // face's normal, (0.577, -0.577, -0.577) here.
  const ConvexHull h = build({Vec3(1, 1, 1), Vec3(-1, 1, 1), Vec3(1, -1, 1), Vec3(1, 1, -1), Vec3(-1, -1, -1)});
  const Vec3 origin(Real(0.1), Real(0), Real(0));
  const double expected[3] = {-1.0 / std::sqrt(1.09), -0.3 / std::sqrt(1.09), 0.0};
  for (const Real scale : {Real(1), Real(1e-30), std::numeric_limits<Real>::denorm_min() * Real(10), Real(1e30),
                           std::numeric_limits<Real>::max() / Real(2)}) {
    const Vec3 d = Vec3(Real(1), Real(0.3), Real(0)) * scale;
    const auto hit = h.raycast({origin, d}, Real(1));
    ASSERT_TRUE(hit.has_value()) << "scale " << scale;
    EXPECT_EQ(hit->t, Real(0));
    // A subnormal direction keeps few digits: 10 * denorm_min * 0.3 is 3 * denorm_min.
    const double tol = scale < std::numeric_limits<Real>::min() ? 0.05 : 1e-6;
    for (int a = 0; a < 3; ++a) EXPECT_NEAR(double(hit->normal[a]), expected[a], tol) << "scale " << scale;
  }
}

TEST(ConvexHull, RaycastAnalyticCube) {
  const ConvexHull h = build(cube_corners(Real(1)));
  // Straight on, along an edge (grazing a face), through a corner, parallel outside.
  auto hit = h.raycast({Vec3(-5, 0, 0), Vec3(2, 0, 0)}, Real(10));
  ASSERT_TRUE(hit.has_value());
  EXPECT_NEAR(hit->t, Real(2), Real(1e-6));
  EXPECT_EQ(hit->normal, Vec3(-1, 0, 0));
  auto graze = h.raycast({Vec3(-5, 1, 0), Vec3(1, 0, 0)}, Real(10));
  ASSERT_TRUE(graze.has_value());
  EXPECT_NEAR(graze->t, Real(4), Real(1e-6));
  auto corner = h.raycast({Vec3(-3, -3, -3), Vec3(1, 1, 1)}, Real(10));
  ASSERT_TRUE(corner.has_value());
  EXPECT_NEAR(corner->t, Real(2), Real(1e-5));
  EXPECT_FALSE(h.raycast({Vec3(-5, Real(1.001), 0), Vec3(1, 0, 0)}, Real(10)).has_value());
  EXPECT_FALSE(h.raycast({Vec3(-5, 0, 0), Vec3(1, 0, 0)}, Real(3.9)).has_value());
  auto segment = h.raycast({Vec3(-5, 0, 0), Vec3(10, 0, 0)}, Real(1));
  ASSERT_TRUE(segment.has_value());
  EXPECT_NEAR(segment->t, Real(0.4), Real(1e-6));
}

}  // namespace test_convex_hull
}  // namespace proxima
