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
//    Ericson, Real-Time Collision Detection, 4.4.1); the test itself is in
//    box_separation.hpp, shared with the mesh-mesh descent. Aabb-Obb treats the Aabb as an Obb.
#include <proxima/bounds/overlap.hpp>
#include <proxima/core/tolerance.hpp>

#include <cmath>

#include "geometry/box_separation.hpp"

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
  const Vec3 axes_a[3] = {a.axes[0], a.axes[1], a.axes[2]};
  const Vec3 axes_b[3] = {b.axes[0], b.axes[1], b.axes[2]};
  constexpr Real kParallelEpsilon = Real(32) * kEpsilon;
  return detail::boxes_within(detail::box_pair_frame(axes_a, a.center, axes_b, b.center, kParallelEpsilon),
                              a.half_extents, b.half_extents, Real(0));
}

bool overlaps(const Aabb& a, const Obb& b) {
  if (!a.is_valid()) return false;
  const Obb box{a.max * Real(0.5) + a.min * Real(0.5), Mat3(Real(1)), a.max * Real(0.5) - a.min * Real(0.5)};
  return overlaps(box, b);
}

}  // namespace proxima
