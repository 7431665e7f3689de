// Closed-form overlap tests: sphere pairs, and boxes by the separating-axis test.
//
// Steps:
//  - Aabb-sphere: squared distance from the centre to the box, accumulated per axis
//    (Arvo, "A simple method for box-sphere intersection testing", Graphics Gems 1990).
//  - sphere-Obb: the same in the box's frame; sphere-capsule: squared distance from the
//    centre to the capsule's segment; sphere-sphere: |c1 - c2|^2 <= (r1 + r2)^2.
//  - Obb-Obb: separating-axis test on the 15 candidate axes (3 + 3 face normals, 9 edge
//    cross products) with the rotation matrix R = A^T B expressed in A's frame; an epsilon
//    is added to |R| so that the near-zero cross products of parallel edges cannot
//    report a false separation (Gottschalk, Lin, Manocha, "OBBTree", SIGGRAPH 1996;
//    Ericson, Real-Time Collision Detection, 4.4.1). Aabb-Obb treats the Aabb as an Obb.
#include <proxima/bounds/overlap.hpp>
#include <proxima/core/tolerance.hpp>

#include <cmath>

namespace proxima {

bool overlaps(const Aabb& a, const BoundingSphere& b) {
  if (!a.is_valid()) return false;
  Real d2 = Real(0);
  for (int i = 0; i < 3; ++i) {
    const Real v = b.center[i];
    if (v < a.min[i]) d2 += (a.min[i] - v) * (a.min[i] - v);
    if (v > a.max[i]) d2 += (v - a.max[i]) * (v - a.max[i]);
  }
  return d2 <= b.radius * b.radius;
}

bool overlaps(const BoundingSphere& a, const BoundingSphere& b) {
  const Vec3 d = a.center - b.center;
  const Real r = a.radius + b.radius;
  return glm::dot(d, d) <= r * r;
}

bool overlaps(const BoundingSphere& a, const Obb& b) {
  const Vec3 d = a.center - b.center;
  Real d2 = Real(0);
  for (int i = 0; i < 3; ++i) {
    const Real excess = std::abs(glm::dot(d, b.axes[i])) - b.half_extents[i];
    if (excess > Real(0)) d2 += excess * excess;
  }
  return d2 <= a.radius * a.radius;
}

bool overlaps(const BoundingSphere& a, const BoundingCapsule& b) {
  const Real r = a.radius + b.radius;
  return b.distance_squared_to_core(a.center) <= r * r;
}

bool overlaps(const Obb& a, const Obb& b) {
  // Rotation of b in a's frame and translation in a's frame.
  Real r[3][3];
  Real abs_r[3][3];
  constexpr Real kParallelEpsilon = Real(32) * kEpsilon;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      r[i][j] = glm::dot(a.axes[i], b.axes[j]);
      abs_r[i][j] = std::abs(r[i][j]) + kParallelEpsilon;
    }
  }
  const Vec3 d = b.center - a.center;
  const Real t[3] = {glm::dot(d, a.axes[0]), glm::dot(d, a.axes[1]), glm::dot(d, a.axes[2])};
  const Vec3& ea = a.half_extents;
  const Vec3& eb = b.half_extents;
  // a's face normals.
  for (int i = 0; i < 3; ++i) {
    const Real ra = ea[i];
    const Real rb = eb[0] * abs_r[i][0] + eb[1] * abs_r[i][1] + eb[2] * abs_r[i][2];
    if (std::abs(t[i]) > ra + rb) return false;
  }
  // b's face normals.
  for (int j = 0; j < 3; ++j) {
    const Real ra = ea[0] * abs_r[0][j] + ea[1] * abs_r[1][j] + ea[2] * abs_r[2][j];
    const Real rb = eb[j];
    if (std::abs(t[0] * r[0][j] + t[1] * r[1][j] + t[2] * r[2][j]) > ra + rb) return false;
  }
  // Edge cross products a_i x b_j.
  for (int i = 0; i < 3; ++i) {
    const int i1 = (i + 1) % 3;
    const int i2 = (i + 2) % 3;
    for (int j = 0; j < 3; ++j) {
      const int j1 = (j + 1) % 3;
      const int j2 = (j + 2) % 3;
      const Real ra = ea[i1] * abs_r[i2][j] + ea[i2] * abs_r[i1][j];
      const Real rb = eb[j1] * abs_r[i][j2] + eb[j2] * abs_r[i][j1];
      const Real dist = std::abs(t[i2] * r[i1][j] - t[i1] * r[i2][j]);
      if (dist > ra + rb) return false;
    }
  }
  return true;
}

bool overlaps(const Aabb& a, const Obb& b) {
  if (!a.is_valid()) return false;
  const Obb box{a.max * Real(0.5) + a.min * Real(0.5), Mat3(Real(1)), a.max * Real(0.5) - a.min * Real(0.5)};
  return overlaps(box, b);
}

}  // namespace proxima
