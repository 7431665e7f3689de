// The symmetric 3x3 eigen solver and orthonormal frames.
//
// Steps of the eigen solver: cyclic Jacobi sweeps (zero each off-diagonal entry by a plane
// rotation, accumulate the rotations) until the off-diagonal norm is negligible, then sort
// the eigenpairs and make the frame right-handed (Golub and Van Loan, Matrix Computations,
// 8.5; Press et al., Numerical Recipes, 11.1).
#include "geometry/eigen_frame.hpp"

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include <algorithm>
#include <array>
#include <cmath>

namespace proxima::detail {

glm::dmat3 symmetric_eigen(const glm::dmat3& m, glm::dvec3& values) {
  glm::dmat3 a = m;
  glm::dmat3 v(1.0);
  for (int sweep = 0; sweep < 50; ++sweep) {
    const double off = a[1][0] * a[1][0] + a[2][0] * a[2][0] + a[2][1] * a[2][1];
    const double diag = a[0][0] * a[0][0] + a[1][1] * a[1][1] + a[2][2] * a[2][2];
    if (!(off > 1e-30 * diag) || off == 0.0) break;
    for (int p = 0; p < 2; ++p) {
      for (int q = p + 1; q < 3; ++q) {
        const double apq = a[q][p];
        if (apq == 0.0) continue;
        const double theta = (a[q][q] - a[p][p]) / (2.0 * apq);
        const double t = (theta >= 0.0 ? 1.0 : -1.0) / (std::abs(theta) + std::sqrt(theta * theta + 1.0));
        const double c = 1.0 / std::sqrt(t * t + 1.0);
        const double s = t * c;
        // A' = J^T A J with J the rotation in the (p, q) plane.
        for (int k = 0; k < 3; ++k) {
          const double akp = a[p][k];
          const double akq = a[q][k];
          a[p][k] = c * akp - s * akq;
          a[q][k] = s * akp + c * akq;
        }
        for (int k = 0; k < 3; ++k) {
          const double apk = a[k][p];
          const double aqk = a[k][q];
          a[k][p] = c * apk - s * aqk;
          a[k][q] = s * apk + c * aqk;
        }
        for (int k = 0; k < 3; ++k) {
          const double vkp = v[p][k];
          const double vkq = v[q][k];
          v[p][k] = c * vkp - s * vkq;
          v[q][k] = s * vkp + c * vkq;
        }
      }
    }
  }
  std::array<int, 3> order{0, 1, 2};
  std::sort(order.begin(), order.end(), [&](int x, int y) { return a[x][x] > a[y][y]; });
  glm::dmat3 out;
  for (int i = 0; i < 3; ++i) {
    out[i] = glm::normalize(v[order[i]]);
    values[i] = a[order[i]][order[i]];
  }
  return orthonormalize(out);
}

glm::dmat3 orthonormalize(const glm::dmat3& frame) {
  glm::dmat3 q;
  const double l0 = glm::length(frame[0]);
  if (!(l0 > 0.0)) return glm::dmat3(1.0);
  q[0] = frame[0] / l0;
  glm::dvec3 u = frame[1] - glm::dot(frame[1], q[0]) * q[0];
  double l1 = glm::length(u);
  if (!(l1 > 1e-12)) {
    return frame_from_axis(q[0]);
  }
  q[1] = u / l1;
  q[2] = glm::normalize(glm::cross(q[0], q[1]));
  // One more pass for accuracy.
  q[1] = glm::normalize(glm::cross(q[2], q[0]));
  return q;
}

glm::dmat3 frame_from_axis(const glm::dvec3& axis) {
  const double len = glm::length(axis);
  if (!(len > 0.0) || !std::isfinite(len)) return glm::dmat3(1.0);
  const glm::dvec3 n = axis / len;
  // Duff et al., "Building an Orthonormal Basis, Revisited" (JCGT 2017).
  const double sign = std::copysign(1.0, n.z);
  const double a = -1.0 / (sign + n.z);
  const double b = n.x * n.y * a;
  const glm::dvec3 t1(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x);
  const glm::dvec3 t2(b, sign + n.y * n.y * a, -n.y);
  glm::dmat3 f;
  f[0] = n;
  f[1] = glm::normalize(t1);
  f[2] = glm::normalize(glm::cross(n, f[1]));
  return f;
}

}  // namespace proxima::detail
