#pragma once
// Tessellators for the midphase tests: closed, outward-oriented triangle meshes of a sphere,
// capsule and cylinder (surfaces of revolution about local z, vertices on the primitive's
// surface, so the mesh lies inside the primitive), of a box with its faces subdivided into
// grids (flat inner edges), and an open flat grid (for ghost-contact tests). Each returns an
// IndexedMesh in the primitive's local frame (the frame of Sphere, Capsule, Cylinder, Box).
#include <proxima/core/math.hpp>
#include <proxima/shapes/indexed_mesh.hpp>

#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

namespace proxima::test {

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
