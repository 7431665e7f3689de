// Watertightness of ray_triangle: closed triangulated meshes (a subdivided icosphere and a
// grid-tessellated box, at the origin, rotated, and 1e4 away) shot with rays aimed at
// their shared vertices, at points of their shared edges, and at random. Every ray that
// passes through the mesh's solid — decided independently of the triangle test, with a
// margin — must hit at least one triangle, at a parameter between its entry into an outer
// and an inner bound of the solid; every ray that clearly misses must hit none.
#include <gtest/gtest.h>

#include <proxima/core/tolerance.hpp>
#include <proxima/geometry/raycast.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <utility>
#include <vector>

#include "support/random.hpp"

namespace proxima::geometry {
namespace test_raycast_watertight {

using D3 = glm::dvec3;
constexpr Real kInf = std::numeric_limits<Real>::infinity();

struct Mesh {
  std::vector<Vec3> vertices;
  std::vector<std::array<int, 3>> triangles;
};

/// The sorted list of edges (vertex index pairs) shared by two triangles.
std::vector<std::pair<int, int>> edges_of(const Mesh& mesh) {
  std::map<std::pair<int, int>, int> count;
  for (const auto& t : mesh.triangles) {
    for (int i = 0; i < 3; ++i) {
      const int a = t[i];
      const int b = t[(i + 1) % 3];
      ++count[{std::min(a, b), std::max(a, b)}];
    }
  }
  std::vector<std::pair<int, int>> edges;
  for (const auto& [edge, n] : count) {
    EXPECT_EQ(n, 2) << "the test mesh is not closed";
    edges.push_back(edge);
  }
  return edges;
}

/// Icosahedron subdivided `levels` times, vertices on the unit sphere (in double, then
/// rounded once).
Mesh icosphere(int levels) {
  const double g = (1 + std::sqrt(5.0)) / 2;
  std::vector<D3> v = {{-1, g, 0},  {1, g, 0},  {-1, -g, 0}, {1, -g, 0}, {0, -1, g},  {0, 1, g},
                       {0, -1, -g}, {0, 1, -g}, {g, 0, -1},  {g, 0, 1},  {-g, 0, -1}, {-g, 0, 1}};
  for (D3& p : v) p = glm::normalize(p);
  std::vector<std::array<int, 3>> f = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                       {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                       {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                       {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  for (int level = 0; level < levels; ++level) {
    std::map<std::pair<int, int>, int> mid;
    auto midpoint = [&](int a, int b) {
      const auto key = std::make_pair(std::min(a, b), std::max(a, b));
      const auto it = mid.find(key);
      if (it != mid.end()) return it->second;
      v.push_back(glm::normalize(v[a] + v[b]));
      return mid[key] = int(v.size()) - 1;
    };
    std::vector<std::array<int, 3>> next;
    for (const auto& t : f) {
      const int ab = midpoint(t[0], t[1]);
      const int bc = midpoint(t[1], t[2]);
      const int ca = midpoint(t[2], t[0]);
      next.push_back({t[0], ab, ca});
      next.push_back({t[1], bc, ab});
      next.push_back({t[2], ca, bc});
      next.push_back({ab, bc, ca});
    }
    f = std::move(next);
  }
  Mesh m;
  for (const D3& p : v) m.vertices.push_back(Vec3(p));
  m.triangles = f;
  return m;
}

/// The box [-1, 1]^3 with each face an n x n grid of squares split along alternating
/// diagonals; vertex coordinates are multiples of 2/n (exact for n a power of two).
Mesh grid_box(int n) {
  Mesh m;
  std::map<std::array<int, 3>, int> index;
  auto vertex = [&](std::array<int, 3> g) {
    const auto it = index.find(g);
    if (it != index.end()) return it->second;
    m.vertices.push_back(
        Vec3(Real(2 * g[0] - n) / Real(n), Real(2 * g[1] - n) / Real(n), Real(2 * g[2] - n) / Real(n)));
    return index[g] = int(m.vertices.size()) - 1;
  };
  for (int axis = 0; axis < 3; ++axis) {
    for (int side = 0; side <= 1; ++side) {
      const int u = (axis + 1) % 3;
      const int w = (axis + 2) % 3;
      for (int i = 0; i < n; ++i) {
        for (int j = 0; j < n; ++j) {
          auto at = [&](int di, int dj) {
            std::array<int, 3> g{};
            g[axis] = side * n;
            g[u] = i + di;
            g[w] = j + dj;
            return vertex(g);
          };
          const int a = at(0, 0), b = at(1, 0), c = at(1, 1), d = at(0, 1);
          if ((i + j) % 2 == 0) {
            m.triangles.push_back({a, b, c});
            m.triangles.push_back({a, c, d});
          } else {
            m.triangles.push_back({a, b, d});
            m.triangles.push_back({b, c, d});
          }
        }
      }
    }
  }
  return m;
}

/// Nearest hit over all triangles (the mesh query, by brute force).
std::optional<RayHit> cast_mesh(const Mesh& mesh, const Ray& ray, Real max_t) {
  const TriangleRay prepared = TriangleRay::prepare(ray);
  std::optional<RayHit> best;
  for (const auto& t : mesh.triangles) {
    const auto hit = ray_triangle(prepared, max_t, mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]]);
    if (hit && (!best || hit->t < best->t)) best = hit;
  }
  return best;
}

/// The independent judge of a ray against the mesh's solid: the parameter interval in
/// which the first hit must lie when the ray clearly enters, or a clear miss.
struct Verdict {
  enum class Kind { Hit, Miss, Unclear } kind = Kind::Unclear;
  double t_lo = 0;  ///< earliest acceptable entry (entry into an outer bound)
  double t_hi = 0;  ///< latest acceptable entry (entry into an inner bound)
};

/// Entry and exit parameters of the line o + t d into the ball (c, r); false if it misses.
bool ball_span(const D3& o, const D3& d, const D3& c, double r, double& t0, double& t1) {
  const D3 m = o - c;
  const double a = glm::dot(d, d);
  const double b = glm::dot(m, d);
  const D3 f = m - (b / a) * d;
  const double h = r * r - glm::dot(f, f);
  if (h <= 0) return false;
  const double s = std::sqrt(h / a);
  t0 = -b / a - s;
  t1 = -b / a + s;
  return true;
}

/// Entry and exit parameters of the line into a box given by centre, unit axes and half
/// extents (slabs, in double); false if it misses.
bool box_span(const D3& o, const D3& d, const D3& c, const glm::dmat3& axes, double half, double& t0, double& t1) {
  t0 = -1e300;
  t1 = 1e300;
  for (int i = 0; i < 3; ++i) {
    const double oi = glm::dot(o - c, axes[i]);
    const double di = glm::dot(d, axes[i]);
    if (di == 0) {
      if (std::abs(oi) > half) return false;
      continue;
    }
    double a = (-half - oi) / di;
    double b = (half - oi) / di;
    if (a > b) std::swap(a, b);
    t0 = std::max(t0, a);
    t1 = std::min(t1, b);
  }
  return t0 <= t1;
}

/// A placed copy of a test mesh and its independent solid description.
struct Placed {
  Mesh mesh;
  bool sphere = true;  ///< icosphere (else box)
  D3 center{0};        ///< centre of the solid
  glm::dmat3 axes{1};  ///< box axes
  double size = 1;     ///< box half extent / circumscribed radius
  double inner = 1;    ///< icosphere: radius of a ball inside the solid
  double margin = 0;   ///< classification margin

  Verdict judge(const Ray& ray) const {
    const D3 o(ray.origin);
    const D3 d(ray.direction);
    Verdict v;
    double a0, a1, b0, b1;
    if (sphere) {
      const bool outer = ball_span(o, d, center, size + margin, a0, a1);
      const bool in = ball_span(o, d, center, inner - margin, b0, b1);
      if (!outer || a1 < 0) v.kind = Verdict::Kind::Miss;
      if (in && b1 > 0) v = {Verdict::Kind::Hit, std::max(0.0, a0), std::max(0.0, b0)};
    } else {
      const bool outer = box_span(o, d, center, axes, size + margin, a0, a1);
      const bool in = box_span(o, d, center, axes, size - margin, b0, b1);
      if (!outer || a1 < 0) v.kind = Verdict::Kind::Miss;
      if (in && b1 > 0 && b1 - std::max(b0, 0.0) > margin) {
        v = {Verdict::Kind::Hit, std::max(0.0, a0), std::max(0.0, b0)};
      }
    }
    return v;
  }
};

/// Places `mesh` (unit size, centred at the origin) at `scale`, rotated by `rotation` and
/// moved to `offset`; each vertex is transformed once, so shared vertices stay shared.
Placed place(const Mesh& mesh, bool sphere, Real scale, const Quat& rotation, const Vec3& offset) {
  Placed p;
  p.sphere = sphere;
  p.mesh.triangles = mesh.triangles;
  const glm::dquat q(rotation);
  for (const Vec3& v : mesh.vertices) p.mesh.vertices.push_back(Vec3(q * (D3(v) * double(scale)) + D3(offset)));
  p.center = D3(offset);
  p.axes = glm::mat3_cast(q);
  p.size = double(scale);
  // The solid check must not depend on the rounding of the placed vertices.
  p.margin = double(scale) * 1e-3 + 8 * double(kEpsilon) * glm::length(D3(offset));
  if (sphere) {
    double r_in = 1e300;
    double r_out = 0;
    for (const auto& t : p.mesh.triangles) {
      const D3 a(p.mesh.vertices[t[0]]), b(p.mesh.vertices[t[1]]), c(p.mesh.vertices[t[2]]);
      const D3 n = glm::normalize(glm::cross(b - a, c - a));
      r_in = std::min(r_in, std::abs(glm::dot(a - p.center, n)));
    }
    for (const Vec3& v : p.mesh.vertices) r_out = std::max(r_out, glm::length(D3(v) - p.center));
    p.inner = r_in;
    p.size = r_out;
  }
  return p;
}

struct Tally {
  int must_hit = 0, must_miss = 0, unclear = 0;
};

/// Shoots `ray` and checks it against the verdict.
void shoot(const Placed& p, const Ray& ray, Tally& tally, const char* what, int index) {
  const Verdict v = p.judge(ray);
  const auto hit = cast_mesh(p.mesh, ray, kInf);
  const D3 o(ray.origin);
  const D3 d(ray.direction);
  const double dl = glm::length(d);
  switch (v.kind) {
    case Verdict::Kind::Hit: {
      ++tally.must_hit;
      ASSERT_TRUE(hit.has_value()) << what << " " << index << ": ray (" << o.x << ", " << o.y << ", " << o.z
                                   << ") + t (" << d.x << ", " << d.y << ", " << d.z << ") slipped through the mesh";
      const double tol = p.margin;
      EXPECT_GE(double(hit->t) * dl, v.t_lo * dl - tol) << what << " " << index;
      EXPECT_LE(double(hit->t) * dl, v.t_hi * dl + tol) << what << " " << index;
      EXPECT_LE(glm::dot(D3(hit->normal), d), 0.0) << what << " " << index;
      break;
    }
    case Verdict::Kind::Miss:
      ++tally.must_miss;
      EXPECT_FALSE(hit.has_value()) << what << " " << index;
      break;
    case Verdict::Kind::Unclear: ++tally.unclear; break;
  }
}

/// A ray aimed at `target` from a random point 2.5 to 6 sizes away from it and outside
/// the solid's bounding sphere (1.8 sizes from the centre covers the box's corners).
Ray aimed(test::Random& rng, const Placed& p, const Vec3& target) {
  for (;;) {
    const double reach = double(rng.uniform(Real(2.5), Real(6)));
    const D3 from = D3(target) + D3(rng.unit_vector()) * p.size * reach;
    if (glm::length(from - p.center) < 1.8 * p.size) continue;
    const Vec3 origin(from);
    return {origin, target - origin};
  }
}

void run_mesh(const Placed& p, std::uint64_t seed, Tally& tally) {
  test::Random rng(seed);
  const auto edges = edges_of(p.mesh);
  for (int i = 0; i < int(p.mesh.vertices.size()); ++i) {
    for (int k = 0; k < 3; ++k) shoot(p, aimed(rng, p, p.mesh.vertices[i]), tally, "vertex", i);
  }
  for (int i = 0; i < int(edges.size()); ++i) {
    const Vec3 a = p.mesh.vertices[edges[i].first];
    const Vec3 b = p.mesh.vertices[edges[i].second];
    shoot(p, aimed(rng, p, (a + b) * Real(0.5)), tally, "edge midpoint", i);
    shoot(p, aimed(rng, p, a + (b - a) * rng.uniform(Real(0), Real(1))), tally, "edge point", i);
  }
  for (int i = 0; i < 1000; ++i) {
    const Vec3 target = Vec3(p.center + D3(rng.in_ball(Real(2))) * p.size);
    shoot(p, aimed(rng, p, target), tally, "random", i);
  }
}

std::vector<Placed> placements(const Mesh& mesh, bool sphere) {
  test::Random rng(sphere ? 21 : 22);
  std::vector<Placed> out;
  out.push_back(place(mesh, sphere, Real(1), kIdentityQuat, Vec3(0)));
  out.push_back(place(mesh, sphere, Real(3), rng.rotation(), Vec3(Real(0.3), Real(-0.7), Real(0.2))));
  out.push_back(place(mesh, sphere, Real(1), kIdentityQuat, Vec3(Real(1e4), Real(-1e4), Real(1e4))));
  out.push_back(place(mesh, sphere, Real(2), rng.rotation(), Vec3(Real(-1e4), Real(1e4), Real(1e4))));
  out.push_back(place(mesh, sphere, Real(1e-3), rng.rotation(), Vec3(Real(0.01), 0, 0)));
  return out;
}

TEST(RayTriangleWatertight, Icosphere) {
  const Mesh mesh = icosphere(2);
  int index = 0;
  for (const Placed& p : placements(mesh, true)) {
    SCOPED_TRACE(::testing::Message() << "placement " << index);
    Tally tally;
    run_mesh(p, 30 + index++, tally);
    EXPECT_GT(tally.must_hit, 1200);
    EXPECT_GT(tally.must_miss, 150);
    EXPECT_LT(tally.unclear, tally.must_hit / 3);
  }
}

TEST(RayTriangleWatertight, GridBox) {
  const Mesh mesh = grid_box(4);
  int index = 0;
  for (const Placed& p : placements(mesh, false)) {
    SCOPED_TRACE(::testing::Message() << "placement " << index);
    Tally tally;
    run_mesh(p, 40 + index++, tally);
    EXPECT_GT(tally.must_hit, 500);
    EXPECT_GT(tally.must_miss, 100);
    EXPECT_LT(tally.unclear, tally.must_hit / 3);
  }
}

// Rays passing exactly through vertices and edge midpoints of the axis-aligned grid box:
// origin = point + a small dyadic vector, so direction and origin are exact and the line
// contains the point exactly (the edge functions hit exact zeros), at the origin and 1e4
// away.
TEST(RayTriangleWatertight, ExactlyThroughSharedVerticesAndEdges) {
  const Mesh unit = grid_box(4);
  const auto edges = edges_of(unit);
  test::Random rng(50);
  int checked = 0;
  for (const Vec3 offset : {Vec3(0), Vec3(Real(1e4), Real(-1e4), Real(1e4))}) {
    const Placed p = place(unit, false, Real(1), kIdentityQuat, offset);
    std::vector<Vec3> targets = p.mesh.vertices;
    for (const auto& e : edges) targets.push_back((p.mesh.vertices[e.first] + p.mesh.vertices[e.second]) * Real(0.5));
    for (const Vec3& target : targets) {
      for (int k = 0; k < 4; ++k) {
        // Quarter steps, up to 6 units per axis, starting outside the box.
        Vec3 w(0);
        while (std::max({std::abs(w.x), std::abs(w.y), std::abs(w.z)}) < Real(2.25)) {
          for (int i = 0; i < 3; ++i) w[i] = Real(rng.integer(-24, 24)) * Real(0.25);
        }
        const Ray ray{target + w, -w};
        if (!(ray.origin - w == target)) continue;  // not exact (cannot happen at these sizes)
        const Verdict v = p.judge(ray);
        if (v.kind != Verdict::Kind::Hit) continue;
        ++checked;
        const auto hit = cast_mesh(p.mesh, ray, kInf);
        ASSERT_TRUE(hit.has_value()) << "through (" << target.x << ", " << target.y << ", " << target.z << ") from ("
                                     << ray.origin.x << ", " << ray.origin.y << ", " << ray.origin.z << ")";
      }
    }
  }
  EXPECT_GT(checked, 1000);
}

}  // namespace test_raycast_watertight
}  // namespace proxima::geometry
