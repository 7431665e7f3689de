#pragma once
// The test meshes of every midphase test, in one place. Closed, outward-oriented meshes
// (boxes, tetrahedra, icospheres, voxel solids such as an L-shape and a square ring, a
// parametric torus; tessellated spheres, capsules, cylinders and grid-faced boxes whose
// vertices lie on the primitive, in the primitive's local frame), an open flat grid (for
// ghost-contact tests), and independent references computed in
// double: the generalised winding number (Jacobson, Kavan, Sorkine-Hornung, "Robust
// inside-outside segmentation using generalized winding numbers", SIGGRAPH 2013; solid angle
// of a triangle by Van Oosterom and Strackee 1983) and the brute-force distance to the
// surface (Ericson's closest point on a triangle, rewritten here in double).
#include <proxima/core/math.hpp>
#include <proxima/shapes/indexed_mesh.hpp>

#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <set>
#include <tuple>
#include <utility>
#include <vector>

namespace proxima::test {

using D3 = std::array<double, 3>;

inline D3 to_d3(const Vec3& v) { return {double(v.x), double(v.y), double(v.z)}; }
inline D3 sub(const D3& a, const D3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
inline double dot(const D3& a, const D3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
inline D3 cross(const D3& a, const D3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
inline double norm(const D3& a) { return std::sqrt(dot(a, a)); }

/// Signed volume by the divergence theorem (double).
inline double signed_volume(const IndexedMesh& m) {
  double v = 0;
  for (const TriangleIndices& t : m.triangles) {
    v += dot(to_d3(m.vertices[t[0]]), cross(to_d3(m.vertices[t[1]]), to_d3(m.vertices[t[2]]))) / 6.0;
  }
  return v;
}

/// Flips every triangle when the mesh faces inward.
inline void orient_outward(IndexedMesh& m) {
  if (signed_volume(m) < 0) {
    for (TriangleIndices& t : m.triangles) std::swap(t[1], t[2]);
  }
}

/// Moves every vertex by `offset`.
inline IndexedMesh translated(IndexedMesh m, const Vec3& offset) {
  for (Vec3& v : m.vertices) v += offset;
  return m;
}

/// The mesh with exactly equal vertices merged (e.g. tessellate_box, whose faces have their
/// own vertices), so that it is closed without repair_mesh.
inline IndexedMesh welded(const IndexedMesh& m) {
  std::map<std::tuple<Real, Real, Real>, std::uint32_t> index;
  IndexedMesh out;
  std::vector<std::uint32_t> remap(m.vertices.size());
  for (std::size_t i = 0; i < m.vertices.size(); ++i) {
    const Vec3& v = m.vertices[i];
    const auto [it, fresh] = index.emplace(std::make_tuple(v.x, v.y, v.z), std::uint32_t(out.vertices.size()));
    if (fresh) out.vertices.push_back(v);
    remap[i] = it->second;
  }
  for (TriangleIndices t : m.triangles) {
    for (std::uint32_t& k : t) k = remap[k];
    out.triangles.push_back(t);
  }
  return out;
}

/// Axis-aligned box [lo, hi], 12 triangles.
inline IndexedMesh box_mesh(const Vec3& lo, const Vec3& hi) {
  IndexedMesh m;
  for (int i = 0; i < 8; ++i) {
    m.vertices.push_back({(i & 1) ? hi.x : lo.x, (i & 2) ? hi.y : lo.y, (i & 4) ? hi.z : lo.z});
  }
  const std::uint32_t quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                                     {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& q : quads) {
    m.triangles.push_back({q[0], q[1], q[2]});
    m.triangles.push_back({q[0], q[2], q[3]});
  }
  orient_outward(m);
  return m;
}

/// Tetrahedron on four points (oriented outward).
inline IndexedMesh tetra_mesh(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  IndexedMesh m;
  m.vertices = {a, b, c, d};
  m.triangles = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {2, 0, 3}};
  orient_outward(m);
  return m;
}

/// Subdivided icosahedron projected on the sphere of `radius` about `center`
/// (20 * 4^levels triangles).
inline IndexedMesh icosphere_mesh(int levels, Real radius, const Vec3& center = Vec3(0)) {
  const double p = 1.6180339887498949;
  std::vector<D3> v = {{-1, p, 0},  {1, p, 0},  {-1, -p, 0}, {1, -p, 0}, {0, -1, p},  {0, 1, p},
                       {0, -1, -p}, {0, 1, -p}, {p, 0, -1},  {p, 0, 1},  {-p, 0, -1}, {-p, 0, 1}};
  std::vector<TriangleIndices> tris = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                       {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                       {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                       {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  for (int l = 0; l < levels; ++l) {
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> mid;
    auto midpoint = [&](std::uint32_t i, std::uint32_t j) {
      const auto key = std::minmax(i, j);
      const auto it = mid.find(key);
      if (it != mid.end()) return it->second;
      v.push_back({(v[i][0] + v[j][0]) / 2, (v[i][1] + v[j][1]) / 2, (v[i][2] + v[j][2]) / 2});
      const auto id = static_cast<std::uint32_t>(v.size() - 1);
      mid.emplace(key, id);
      return id;
    };
    std::vector<TriangleIndices> next;
    for (const TriangleIndices& t : tris) {
      const std::uint32_t a = midpoint(t[0], t[1]);
      const std::uint32_t b = midpoint(t[1], t[2]);
      const std::uint32_t c = midpoint(t[2], t[0]);
      next.push_back({t[0], a, c});
      next.push_back({t[1], b, a});
      next.push_back({t[2], c, b});
      next.push_back({a, b, c});
    }
    tris = std::move(next);
  }
  IndexedMesh m;
  for (const D3& x : v) {
    const double s = double(radius) / norm(x);
    m.vertices.push_back(Vec3(Real(x[0] * s), Real(x[1] * s), Real(x[2] * s)) + center);
  }
  m.triangles = std::move(tris);
  orient_outward(m);
  return m;
}

/// Boundary of a union of unit voxels (integer cells scaled by `cell`): a square for every
/// face between a filled and an empty cell. Manifold when no two cells touch along an edge
/// or a corner only.
inline IndexedMesh voxel_mesh(const std::vector<std::array<int, 3>>& cells, Real cell) {
  std::set<std::array<int, 3>> filled(cells.begin(), cells.end());
  std::map<std::array<int, 3>, std::uint32_t> index;
  IndexedMesh m;
  auto vertex = [&](std::array<int, 3> g) {
    const auto it = index.find(g);
    if (it != index.end()) return it->second;
    m.vertices.push_back(Vec3(Real(g[0]) * cell, Real(g[1]) * cell, Real(g[2]) * cell));
    const auto id = static_cast<std::uint32_t>(m.vertices.size() - 1);
    index.emplace(g, id);
    return id;
  };
  for (const auto& c : cells) {
    for (int axis = 0; axis < 3; ++axis) {
      for (int dir = -1; dir <= 1; dir += 2) {
        std::array<int, 3> n = c;
        n[static_cast<std::size_t>(axis)] += dir;
        if (filled.count(n) != 0) continue;
        // The face at c[axis] + (dir > 0), spanned by the two other axes u, w with u x w =
        // +axis: counter-clockwise seen from outside is (0,0) (1,0) (1,1) (0,1) in (u, w)
        // for dir > 0 and the reverse for dir < 0.
        const int u = (axis + 1) % 3;
        const int w = (axis + 2) % 3;
        std::array<std::uint32_t, 4> q{};
        const int corners[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
        for (int k = 0; k < 4; ++k) {
          std::array<int, 3> g = c;
          g[static_cast<std::size_t>(axis)] += dir > 0 ? 1 : 0;
          g[static_cast<std::size_t>(u)] += corners[k][0];
          g[static_cast<std::size_t>(w)] += corners[k][1];
          q[static_cast<std::size_t>(k)] = vertex(g);
        }
        if (dir < 0) std::swap(q[1], q[3]);
        m.triangles.push_back({q[0], q[1], q[2]});
        m.triangles.push_back({q[0], q[2], q[3]});
      }
    }
  }
  return m;
}

/// A non-convex L-shaped prism: three voxels of a 2x2 square, two cells deep.
inline IndexedMesh l_shape_mesh() {
  return voxel_mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {0, 1, 1}}, Real(0.5));
}

/// A square ring (3x3 cells minus the centre), genus one.
inline IndexedMesh ring_mesh() {
  std::vector<std::array<int, 3>> cells;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      if (i != 1 || j != 1) cells.push_back({i, j, 0});
    }
  }
  return voxel_mesh(cells, Real(0.5));
}

/// Parametric torus about z: major radius `big`, minor `small`, n x m quads.
inline IndexedMesh torus_mesh(Real big, Real small, int n, int m) {
  IndexedMesh mesh;
  for (int i = 0; i < n; ++i) {
    const double u = 2 * 3.14159265358979323846 * i / n;
    for (int j = 0; j < m; ++j) {
      const double v = 2 * 3.14159265358979323846 * j / m;
      const double r = double(big) + double(small) * std::cos(v);
      mesh.vertices.push_back(Vec3(Real(r * std::cos(u)), Real(r * std::sin(u)), Real(double(small) * std::sin(v))));
    }
  }
  auto id = [&](int i, int j) { return static_cast<std::uint32_t>(((i % n) * m) + (j % m)); };
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < m; ++j) {
      mesh.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      mesh.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  }
  orient_outward(mesh);
  return mesh;
}

/// Generalised winding number of `p` (1 inside, 0 outside a closed outward mesh), in double.
inline double winding_number(const IndexedMesh& m, const Vec3& point) {
  const D3 p = to_d3(point);
  double sum = 0;
  for (const TriangleIndices& t : m.triangles) {
    const D3 a = sub(to_d3(m.vertices[t[0]]), p);
    const D3 b = sub(to_d3(m.vertices[t[1]]), p);
    const D3 c = sub(to_d3(m.vertices[t[2]]), p);
    const double la = norm(a);
    const double lb = norm(b);
    const double lc = norm(c);
    const double num = dot(a, cross(b, c));
    const double den = la * lb * lc + dot(a, b) * lc + dot(b, c) * la + dot(c, a) * lb;
    sum += 2 * std::atan2(num, den);
  }
  return sum / (4 * 3.14159265358979323846);
}

/// Closest point on triangle abc to p (Ericson 5.1.5, in double).
inline D3 closest_on_triangle(const D3& p, const D3& a, const D3& b, const D3& c) {
  const D3 ab = sub(b, a);
  const D3 ac = sub(c, a);
  const D3 ap = sub(p, a);
  const double d1 = dot(ab, ap);
  const double d2 = dot(ac, ap);
  if (d1 <= 0 && d2 <= 0) return a;
  const D3 bp = sub(p, b);
  const double d3 = dot(ab, bp);
  const double d4 = dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    const double v = d1 / (d1 - d3);
    return {a[0] + v * ab[0], a[1] + v * ab[1], a[2] + v * ab[2]};
  }
  const D3 cp = sub(p, c);
  const double d5 = dot(ab, cp);
  const double d6 = dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    const double w = d2 / (d2 - d6);
    return {a[0] + w * ac[0], a[1] + w * ac[1], a[2] + w * ac[2]};
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return {b[0] + w * (c[0] - b[0]), b[1] + w * (c[1] - b[1]), b[2] + w * (c[2] - b[2])};
  }
  const double denom = 1 / (va + vb + vc);
  const double v = vb * denom;
  const double w = vc * denom;
  return {a[0] + ab[0] * v + ac[0] * w, a[1] + ab[1] * v + ac[1] * w, a[2] + ab[2] * v + ac[2] * w};
}

/// Brute-force distance from p to the surface and the index of a nearest triangle.
inline std::pair<double, std::uint32_t> surface_distance(const IndexedMesh& m, const Vec3& point) {
  const D3 p = to_d3(point);
  double best = std::numeric_limits<double>::infinity();
  std::uint32_t best_t = 0;
  for (std::uint32_t i = 0; i < m.triangles.size(); ++i) {
    const TriangleIndices& t = m.triangles[i];
    const D3 q = closest_on_triangle(p, to_d3(m.vertices[t[0]]), to_d3(m.vertices[t[1]]), to_d3(m.vertices[t[2]]));
    const double d = norm(sub(p, q));
    if (d < best) {
      best = d;
      best_t = i;
    }
  }
  return {best, best_t};
}

// ---- tessellated primitives ------------------------------------------------------------

inline constexpr Real kTessPi = Real(3.14159265358979323846);

/// Surface of revolution about z: `profile` lists (radius, z) from top to bottom; the first
/// and last entries must have radius 0 (poles); `slices` segments around.
inline IndexedMesh lathe(const std::vector<std::pair<Real, Real>>& profile, int slices) {
  IndexedMesh m;
  const int rings = static_cast<int>(profile.size()) - 2;
  m.vertices.push_back({Real(0), Real(0), profile.front().second});
  for (int i = 1; i <= rings; ++i) {
    for (int j = 0; j < slices; ++j) {
      const Real phi = Real(2) * kTessPi * Real(j) / Real(slices);
      m.vertices.push_back({profile[static_cast<std::size_t>(i)].first * std::cos(phi),
                            profile[static_cast<std::size_t>(i)].first * std::sin(phi),
                            profile[static_cast<std::size_t>(i)].second});
    }
  }
  m.vertices.push_back({Real(0), Real(0), profile.back().second});
  const auto ring = [&](int i, int j) { return static_cast<std::uint32_t>(1 + (i - 1) * slices + (j % slices)); };
  const auto bottom = static_cast<std::uint32_t>(m.vertices.size() - 1);
  for (int j = 0; j < slices; ++j) m.triangles.push_back({0u, ring(1, j), ring(1, j + 1)});
  for (int i = 1; i < rings; ++i) {
    for (int j = 0; j < slices; ++j) {
      const std::uint32_t a = ring(i, j), b = ring(i + 1, j), c = ring(i + 1, j + 1), d = ring(i, j + 1);
      m.triangles.push_back({a, b, c});
      m.triangles.push_back({a, c, d});
    }
  }
  for (int j = 0; j < slices; ++j) m.triangles.push_back({bottom, ring(rings, j + 1), ring(rings, j)});
  return m;
}

/// UV sphere of `radius`: `stacks` bands of latitude, `slices` of longitude.
inline IndexedMesh tessellate_sphere(Real radius, int slices, int stacks) {
  std::vector<std::pair<Real, Real>> p;
  for (int i = 0; i <= stacks; ++i) {
    const Real t = kTessPi * Real(i) / Real(stacks);
    p.emplace_back(i == 0 || i == stacks ? Real(0) : radius * std::sin(t), radius * std::cos(t));
  }
  return lathe(p, slices);
}

/// Capsule (radius, half_length along z): two hemispheres of `stacks`/2 bands each.
inline IndexedMesh tessellate_capsule(Real radius, Real half_length, int slices, int stacks) {
  std::vector<std::pair<Real, Real>> p;
  const int half = stacks / 2;
  for (int i = 0; i <= half; ++i) {
    const Real t = kTessPi * Real(i) / Real(2 * half);
    p.emplace_back(i == 0 ? Real(0) : radius * std::sin(t), half_length + radius * std::cos(t));
  }
  for (int i = half; i <= 2 * half; ++i) {
    const Real t = kTessPi * Real(i) / Real(2 * half);
    p.emplace_back(i == 2 * half ? Real(0) : radius * std::sin(t), -half_length + radius * std::cos(t));
  }
  return lathe(p, slices);
}

/// Capped cylinder (radius, half_length along z): cap fans around the cap centres.
inline IndexedMesh tessellate_cylinder(Real radius, Real half_length, int slices) {
  return lathe({{Real(0), half_length}, {radius, half_length}, {radius, -half_length}, {Real(0), -half_length}},
               slices);
}

/// Box of `half` extents, each face a k x k grid of quads (two triangles each); shared
/// edge vertices are computed by the same formula so they coincide exactly.
inline IndexedMesh tessellate_box(const Vec3& half, int k) {
  IndexedMesh m;
  const auto coord = [&](int axis, int i) { return -half[axis] + Real(2) * half[axis] * Real(i) / Real(k); };
  for (int axis = 0; axis < 3; ++axis) {
    for (int s = -1; s <= 1; s += 2) {
      const int u = (axis + 1) % 3, v = (axis + 2) % 3;
      const auto base = static_cast<std::uint32_t>(m.vertices.size());
      for (int i = 0; i <= k; ++i) {
        for (int j = 0; j <= k; ++j) {
          Vec3 p;
          p[axis] = Real(s) * half[axis];
          p[u] = coord(u, i);
          p[v] = coord(v, j);
          m.vertices.push_back(p);
        }
      }
      const auto at = [&](int i, int j) { return base + static_cast<std::uint32_t>(i * (k + 1) + j); };
      for (int i = 0; i < k; ++i) {
        for (int j = 0; j < k; ++j) {
          // u x v = +axis, so (i,j)->(i+1,j)->(i+1,j+1) faces +axis; flip for the -axis face.
          if (s > 0) {
            m.triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
            m.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
          } else {
            m.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i + 1, j)});
            m.triangles.push_back({at(i, j), at(i, j + 1), at(i + 1, j + 1)});
          }
        }
      }
    }
  }
  return m;
}

/// Open flat grid in the plane z = 0 facing +z: nx x ny square cells of size `cell`,
/// starting at (x0, y0); the diagonal alternates from cell to cell.
inline IndexedMesh flat_grid(int nx, int ny, Real cell, Real x0, Real y0) {
  IndexedMesh m;
  for (int i = 0; i <= nx; ++i)
    for (int j = 0; j <= ny; ++j) m.vertices.push_back({x0 + cell * Real(i), y0 + cell * Real(j), Real(0)});
  const auto at = [&](int i, int j) { return static_cast<std::uint32_t>(i * (ny + 1) + j); };
  for (int i = 0; i < nx; ++i) {
    for (int j = 0; j < ny; ++j) {
      if ((i + j) % 2 == 0) {
        m.triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
        m.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
      } else {
        m.triangles.push_back({at(i, j), at(i + 1, j), at(i, j + 1)});
        m.triangles.push_back({at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)});
      }
    }
  }
  return m;
}

}  // namespace proxima::test
