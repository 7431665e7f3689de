#pragma once
// Separating-axis tests of two oriented boxes, shared by the closed-form Obb overlap
// (overlap_closed_form.cpp) and the mesh-mesh descent (midphase/mesh_mesh.cpp). Internal.
//
// Both take box B in box A's frame: r[i][j] = a_i . b_j (A's axis i against B's axis j),
// abs_r = |r| + epsilon (so that the near-zero cross products of parallel edges cannot report
// a false separation), t = B's centre minus A's centre in A's axes; ea, eb are the half
// extents. The 15 candidate axes are A's three face normals, B's three and the nine edge
// cross products a_i x b_j (Gottschalk, Lin, Manocha, "OBBTree", SIGGRAPH 1996; Ericson,
// Real-Time Collision Detection, 4.4.1).

#include <proxima/core/math.hpp>
#include <proxima/core/tolerance.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace proxima::detail {

/// B's rotation and centre in A's frame for the separating-axis tests.
struct BoxPairFrame {
  Real r[3][3];      ///< r[i][j] = a_i . b_j
  Real abs_r[3][3];  ///< |r[i][j]| + epsilon
  Real t[3];         ///< (centre of B - centre of A) . a_i
};

/// The frame of B = (axes_b, center_b) seen from A = (axes_a, center_a), all four in one
/// frame; `parallel_epsilon` is added to |r|.
inline BoxPairFrame box_pair_frame(const Vec3 (&axes_a)[3], const Vec3& center_a, const Vec3 (&axes_b)[3],
                                   const Vec3& center_b, Real parallel_epsilon) {
  BoxPairFrame f;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      f.r[i][j] = glm::dot(axes_a[i], axes_b[j]);
      f.abs_r[i][j] = std::abs(f.r[i][j]) + parallel_epsilon;
    }
  }
  const Vec3 d = center_b - center_a;
  for (int i = 0; i < 3; ++i) f.t[i] = glm::dot(d, axes_a[i]);
  return f;
}

/// The unnormalised edge axis a_i x b_j in A's frame: the centre offset projected on it and
/// the sum of the boxes' projected radii on it (Gottschalk et al., "OBBTree", 1996).
struct EdgeAxisTerms {
  Real projection;
  Real radii;
};

inline EdgeAxisTerms edge_axis_terms(const Real (&r)[3][3], const Real (&abs_r)[3][3], const Real (&t)[3],
                                     const Vec3& ea, const Vec3& eb, int i, int j) {
  const int i1 = (i + 1) % 3;
  const int i2 = (i + 2) % 3;
  const int j1 = (j + 1) % 3;
  const int j2 = (j + 2) % 3;
  const Real ra = ea[i1] * abs_r[i2][j] + ea[i2] * abs_r[i1][j];
  const Real rb = eb[j1] * abs_r[i][j2] + eb[j2] * abs_r[i][j1];
  return {t[i2] * r[i1][j] - t[i1] * r[i2][j], ra + rb};
}

/// True when no candidate axis separates the boxes by more than `margin` (>= 0). The edge
/// axes are not normalised: their length is at most 1, so an unscaled margin is
/// conservative.
inline bool boxes_within(const Real (&r)[3][3], const Real (&abs_r)[3][3], const Real (&t)[3], const Vec3& ea,
                         const Vec3& eb, Real margin) {
  for (int i = 0; i < 3; ++i) {
    const Real rb = abs_r[i][0] * eb[0] + abs_r[i][1] * eb[1] + abs_r[i][2] * eb[2];
    if (std::abs(t[i]) > ea[i] + rb + margin) return false;
  }
  for (int j = 0; j < 3; ++j) {
    const Real ra = abs_r[0][j] * ea[0] + abs_r[1][j] * ea[1] + abs_r[2][j] * ea[2];
    const Real tj = t[0] * r[0][j] + t[1] * r[1][j] + t[2] * r[2][j];
    if (std::abs(tj) > ra + eb[j] + margin) return false;
  }
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      const EdgeAxisTerms e = edge_axis_terms(r, abs_r, t, ea, eb, i, j);
      if (std::abs(e.projection) > e.radii + margin) return false;
    }
  }
  return true;
}

/// The same test on a BoxPairFrame.
inline bool boxes_within(const BoxPairFrame& f, const Vec3& ea, const Vec3& eb, Real margin) {
  return boxes_within(f.r, f.abs_r, f.t, ea, eb, margin);
}

/// A lower bound of the distance between the boxes: the largest gap between their
/// projections over the 15 candidate axes (each edge axis normalised; axes of nearly
/// parallel edges, shorter than 1e-3, skipped) and the axis through the centres; 0 when no
/// axis separates them. Exact when the nearest features are face-vertex or edge-edge.
/// Returns as soon as a gap reaches `enough` (the caller only needs to know that much):
/// face axes first, then the centre axis, then the edge axes.
inline Real boxes_gap(const BoxPairFrame& f, const Vec3& ea, const Vec3& eb,
                      Real enough = std::numeric_limits<Real>::infinity()) {
  const auto& r = f.r;
  const auto& abs_r = f.abs_r;
  const auto& t = f.t;
  Real gap = Real(0);
  for (int i = 0; i < 3; ++i) {
    const Real rb = abs_r[i][0] * eb[0] + abs_r[i][1] * eb[1] + abs_r[i][2] * eb[2];
    gap = std::max(gap, std::abs(t[i]) - ea[i] - rb);
  }
  for (int j = 0; j < 3; ++j) {
    const Real ra = abs_r[0][j] * ea[0] + abs_r[1][j] * ea[1] + abs_r[2][j] * ea[2];
    const Real tj = t[0] * r[0][j] + t[1] * r[1][j] + t[2] * r[2][j];
    gap = std::max(gap, std::abs(tj) - ra - eb[j]);
  }
  if (gap >= enough) return gap;
  const Real tt = t[0] * t[0] + t[1] * t[1] + t[2] * t[2];
  if (tt > Real(0)) {
    const Real len = std::sqrt(tt);
    const Real u[3] = {t[0] / len, t[1] / len, t[2] / len};
    const Real ra = ea[0] * std::abs(u[0]) + ea[1] * std::abs(u[1]) + ea[2] * std::abs(u[2]);
    Real rb = Real(0);
    for (int j = 0; j < 3; ++j) rb += eb[j] * (std::abs(u[0] * r[0][j] + u[1] * r[1][j] + u[2] * r[2][j]));
    // |u . b_j| is bounded as abs_r bounds |r|: a few epsilons of slack keep the gap low.
    gap = std::max(gap, len - ra - rb * (Real(1) + Real(8) * kEpsilon));
    if (gap >= enough) return gap;
  }
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      const EdgeAxisTerms e = edge_axis_terms(r, abs_r, t, ea, eb, i, j);
      const Real g = std::abs(e.projection) - e.radii;
      // |a_i x b_j|^2 = 1 - r_ij^2; the unscaled gap g is the true gap times that length.
      if (g <= Real(0)) continue;
      const Real len2 = Real(1) - r[i][j] * r[i][j];
      if (len2 < Real(1e-6) || g * g <= gap * gap * len2) continue;
      gap = g / std::sqrt(len2);
    }
  }
  return gap;
}

}  // namespace proxima::detail
