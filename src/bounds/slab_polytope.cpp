// Vertex enumeration and volume of slab polytopes (k-DOPs).
//
// Steps: (1) for every triple of slab directions with a non-zero determinant and each of
// the 8 choices of lower/upper plane, solve the 3x3 system by Cramer's rule
// (x = (b_i (d_j x d_k) + b_j (d_k x d_i) + b_k (d_i x d_j)) / det); (2) keep the points
// inside every slab (with slack) and merge duplicates; (3) for the volume, gather the
// vertices of each face plane, order them by angle around the face centroid and sum the
// pyramids from the vertices' mean (divergence theorem on a convex polytope).
// Source: Ericson, Real-Time Collision Detection, 4.6 (k-DOPs) and 5.4 (intersection of
// three planes); brute-force enumeration is fine for the at most 26 planes of a k-DOP.
#include "bounds/slab_polytope.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <utility>

namespace proxima::detail {

std::vector<glm::dvec3> slab_polytope_vertices(std::span<const glm::dvec3> dirs, std::span<const double> lo,
                                               std::span<const double> hi, double slack, double merge,
                                               bool stop_at_first) {
  std::vector<glm::dvec3> out;
  const std::size_t n = dirs.size();
  auto feasible = [&](const glm::dvec3& x) {
    for (std::size_t m = 0; m < n; ++m) {
      const double p = glm::dot(dirs[m], x);
      if (!(p >= lo[m] - slack && p <= hi[m] + slack)) return false;
    }
    return true;
  };
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = i + 1; j < n; ++j) {
      const glm::dvec3 cij = glm::cross(dirs[i], dirs[j]);
      for (std::size_t k = j + 1; k < n; ++k) {
        const double det = glm::dot(dirs[k], cij);
        if (std::abs(det) < 1e-9) continue;  // directions are small integer vectors: det is exact
        const glm::dvec3 cjk = glm::cross(dirs[j], dirs[k]);
        const glm::dvec3 cki = glm::cross(dirs[k], dirs[i]);
        for (int s = 0; s < 8; ++s) {
          const double bi = (s & 1) ? hi[i] : lo[i];
          const double bj = (s & 2) ? hi[j] : lo[j];
          const double bk = (s & 4) ? hi[k] : lo[k];
          const glm::dvec3 x = (bi * cjk + bj * cki + bk * cij) / det;
          if (!feasible(x)) continue;
          bool duplicate = false;
          for (const glm::dvec3& v : out) {
            const glm::dvec3 d = glm::abs(v - x);
            if (d.x <= merge && d.y <= merge && d.z <= merge) {
              duplicate = true;
              break;
            }
          }
          if (duplicate) continue;
          out.push_back(x);
          if (stop_at_first) return out;
        }
      }
    }
  }
  return out;
}

double slab_polytope_volume(std::span<const glm::dvec3> dirs, std::span<const double> lo, std::span<const double> hi,
                            std::span<const glm::dvec3> vertices, double on_plane) {
  if (vertices.size() < 4) return 0.0;
  glm::dvec3 mean(0.0);
  for (const glm::dvec3& v : vertices) mean += v;
  mean /= static_cast<double>(vertices.size());
  double volume = 0.0;
  std::vector<glm::dvec3> face;
  std::vector<std::pair<double, glm::dvec3>> ordered;
  for (std::size_t i = 0; i < dirs.size(); ++i) {
    const double len = glm::length(dirs[i]);
    const glm::dvec3 n = dirs[i] / len;
    for (int side = 0; side < 2; ++side) {
      const double b = side == 0 ? lo[i] : hi[i];
      const glm::dvec3 outward = side == 0 ? -n : n;
      face.clear();
      for (const glm::dvec3& v : vertices) {
        if (std::abs(glm::dot(dirs[i], v) - b) <= on_plane * len) face.push_back(v);
      }
      if (face.size() < 3) continue;
      glm::dvec3 c(0.0);
      for (const glm::dvec3& v : face) c += v;
      c /= static_cast<double>(face.size());
      // In-plane basis (any two orthonormal vectors orthogonal to n).
      const glm::dvec3 helper = std::abs(n.x) < 0.6 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
      const glm::dvec3 u = glm::normalize(glm::cross(n, helper));
      const glm::dvec3 w = glm::cross(n, u);
      ordered.clear();
      for (const glm::dvec3& v : face) ordered.emplace_back(std::atan2(glm::dot(v - c, w), glm::dot(v - c, u)), v);
      std::sort(ordered.begin(), ordered.end(), [](const auto& a, const auto& b2) { return a.first < b2.first; });
      glm::dvec3 area_vector(0.0);
      for (std::size_t k = 0; k < ordered.size(); ++k) {
        const glm::dvec3& a = ordered[k].second;
        const glm::dvec3& b2 = ordered[(k + 1) % ordered.size()].second;
        area_vector += glm::cross(a - c, b2 - c);
      }
      const double area = 0.5 * std::abs(glm::dot(area_vector, n));
      const double height = glm::dot(outward, c - mean);
      volume += area * std::max(height, 0.0) / 3.0;
    }
  }
  return volume;
}

}  // namespace proxima::detail
