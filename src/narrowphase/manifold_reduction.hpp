#pragma once
/// @file manifold_reduction.hpp
/// Reduction of a set of candidate contact points to at most k (<= 4) that keep the deepest
/// contact and span the largest area, so that a solver sees a stable support polygon.
///
/// Steps (the usual contact-reduction heuristic, e.g. Gregorius, "Robust contact creation for
/// physics simulations", GDC 2015):
///  1. the deepest point;
///  2. the point farthest from it;
///  3. the point maximising the area of the triangle with the first two;
///  4. the point that adds the largest area outside that triangle (largest quadrilateral).
/// Areas are measured in the plane perpendicular to the contact normal. Ties go to the
/// earliest candidate, so the choice is deterministic. A step stops early when no candidate
/// adds length or area (coincident or collinear points). O(n) per step, no allocation.

#include <proxima/core/math.hpp>
#include <proxima/narrowphase/contact.hpp>

#include <algorithm>
#include <array>
#include <span>

namespace proxima::narrow {

/// Chooses at most min(k, 4) of n candidates by the steps above and writes their indices, in
/// order of choice (the deepest first), to `out`; returns how many. `position(i)` gives
/// candidate i's point (world frame), `depth(i)` its depth, `use(i)` whether it is a candidate
/// at all (lets callers stream over a shape's vertices without copying them). `normal` is the
/// contact normal (unit). O(n), four passes.
template <class PositionFn, class DepthFn, class UseFn>
int select_contacts(int n, PositionFn position, DepthFn depth, UseFn use, const Vec3& normal, int k,
                    std::array<int, 4>& out) {
  k = std::min(k, 4);
  if (k <= 0 || n <= 0) return 0;
  // 1. Deepest.
  int i0 = -1;
  Real best = Real(0);
  for (int i = 0; i < n; ++i) {
    if (!use(i)) continue;
    const Real d = depth(i);
    if (i0 < 0 || d > best) {
      i0 = i;
      best = d;
    }
  }
  if (i0 < 0) return 0;
  out[0] = i0;
  if (k == 1) return 1;
  const Vec3 p0 = position(i0);
  // 2. Farthest from the deepest.
  int i1 = -1;
  best = Real(0);
  for (int i = 0; i < n; ++i) {
    if (i == i0 || !use(i)) continue;
    const Real d2 = length_squared(position(i) - p0);
    if (d2 > best) {
      i1 = i;
      best = d2;
    }
  }
  if (i1 < 0) return 1;
  out[1] = i1;
  if (k == 2) return 2;
  const Vec3 p1 = position(i1);
  // 3. Largest triangle.
  int i2 = -1;
  best = Real(0);
  Real orientation = Real(0);
  for (int i = 0; i < n; ++i) {
    if (i == i0 || i == i1 || !use(i)) continue;
    const Real area = glm::dot(glm::cross(p1 - p0, position(i) - p0), normal);
    if (std::abs(area) > best) {
      i2 = i;
      best = std::abs(area);
      orientation = area;
    }
  }
  if (i2 < 0) return 2;
  out[2] = i2;
  if (k == 3) return 3;
  const Vec3 p2 = position(i2);
  // 4. Largest area added outside the triangle (p0, p1, p2), oriented like `orientation`.
  const Real s = orientation > Real(0) ? Real(1) : Real(-1);
  int i3 = -1;
  best = Real(0);
  for (int i = 0; i < n; ++i) {
    if (i == i0 || i == i1 || i == i2 || !use(i)) continue;
    const Vec3 p = position(i);
    const Real e01 = -s * glm::dot(glm::cross(p1 - p0, p - p0), normal);
    const Real e12 = -s * glm::dot(glm::cross(p2 - p1, p - p1), normal);
    const Real e20 = -s * glm::dot(glm::cross(p0 - p2, p - p2), normal);
    const Real added = std::max({e01, e12, e20});
    if (added > best) {
      i3 = i;
      best = added;
    }
  }
  if (i3 < 0) return 3;
  out[3] = i3;
  return 4;
}

/// Reduces `points` (all sharing `normal`, unit, world frame) to at most min(k, 4) by
/// select_contacts, positions taken as the midpoints of point_a and point_b. Writes them to
/// `out` (deepest first) and returns the count. Allocation-free; O(points.size()).
int reduce_contacts(std::span<const ContactPoint> points, const Vec3& normal, int k,
                    std::array<ContactPoint, kMaxContactPoints>& out);

}  // namespace proxima::narrow
