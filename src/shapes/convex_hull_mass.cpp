// Mass properties of a ConvexHull: volume, centroid and inertia tensor of the solid
// polyhedron at unit density, computed once when the hull is built.
//
// Steps (divergence theorem over a tetrahedral decomposition; Tonon, "Explicit Exact
// Formulas for the 3-D Tetrahedron Inertia Tensor in Terms of its Vertex Coordinates",
// J. Math. Stat. 2004; Eberly, "Polyhedral Mass Properties (Revisited)", 2009; the
// canonical-tetrahedron form of Blow and Binstock, "How to find the inertia tensor of a
// 3D solid body represented by a triangle mesh", 2004):
//  1. Pick a reference point r inside the hull (the mean of the vertices) and work in
//     double relative to r, which keeps far-from-origin hulls accurate.
//  2. Fan-triangulate every CCW face loop; each triangle (a, b, c) with r forms a
//     tetrahedron of signed volume det[a b c] / 6 (positive for an outward triangle).
//  3. Accumulate the volume, the first moment vol * (a + b + c) / 4 and the second moment
//     (covariance about r) det / 120 * (a a^T + b b^T + c c^T + s s^T), s = a + b + c.
//  4. Centroid = r + first moment / volume; shift the covariance to the centroid
//     (C_c = C - V c c^T) and convert: inertia = trace(C_c) E - C_c.

#include <array>

#include "shapes/convex_hull_data.hpp"
#include "shapes/double_vector.hpp"

namespace proxima::detail {

bool compute_hull_mass(HullData& data) {
  const std::size_t nv = data.vertices.size();
  if (nv < 4) return false;
  D3 r{0, 0, 0};
  for (const Vec3& v : data.vertices) {
    for (int a = 0; a < 3; ++a) r[a] += double(v[a]);
  }
  for (int a = 0; a < 3; ++a) r[a] /= double(nv);
  auto rel = [&](std::uint32_t i) {
    const Vec3& v = data.vertices[i];
    return D3{double(v.x) - r[0], double(v.y) - r[1], double(v.z) - r[2]};
  };

  double volume = 0;
  D3 first{0, 0, 0};
  double cov[3][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
  for (const HullFace& f : data.faces) {
    const D3 a = rel(data.face_indices[f.first_index]);
    for (std::uint32_t k = 1; k + 1 < f.index_count; ++k) {
      const D3 b = rel(data.face_indices[f.first_index + k]);
      const D3 c = rel(data.face_indices[f.first_index + k + 1]);
      const double det =
          a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) + a[2] * (b[0] * c[1] - b[1] * c[0]);
      const D3 s{a[0] + b[0] + c[0], a[1] + b[1] + c[1], a[2] + b[2] + c[2]};
      volume += det / 6.0;
      for (int i = 0; i < 3; ++i) first[i] += det / 24.0 * s[i];
      for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) {
          cov[i][j] += det / 120.0 * (a[i] * a[j] + b[i] * b[j] + c[i] * c[j] + s[i] * s[j]);
        }
      }
    }
  }
  // Flatness was rejected before (the hull's width); this only guards the divisions.
  if (!(volume > 0)) return false;

  const D3 c{first[0] / volume, first[1] / volume, first[2] / volume};
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) cov[i][j] -= volume * c[i] * c[j];
  }
  const double trace = cov[0][0] + cov[1][1] + cov[2][2];
  data.volume = Real(volume);
  data.centroid = Vec3(Real(r[0] + c[0]), Real(r[1] + c[1]), Real(r[2] + c[2]));
  for (int col = 0; col < 3; ++col) {
    for (int row = 0; row < 3; ++row) {
      data.unit_inertia[col][row] = Real((col == row ? trace : 0.0) - cov[row][col]);
    }
  }
  return true;
}

}  // namespace proxima::detail
