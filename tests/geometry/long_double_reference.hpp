#pragma once
// Long double references for the closest-point tests of the geometry layer: a long double
// vector type, the exact point-segment distance, a point-triangle distance from the Gram
// normal equations and the three edges, a golden-section search for the nested searches
// over the primitives' parameters, and the tolerances at a coordinate scale. None of it
// shares code with the library.
#include <proxima/core/math.hpp>
#include <proxima/core/tolerance.hpp>

#include <algorithm>
#include <cmath>
#include <initializer_list>

namespace proxima::test {

using LD = long double;
using LVec = glm::vec<3, LD, glm::defaultp>;

// A Real vector in long double.
inline LVec ld(const Vec3& v) { return LVec(v.x, v.y, v.z); }
inline LD dist2(const LVec& a, const LVec& b) { return glm::dot(a - b, a - b); }

// Tolerance on a distance at coordinate magnitude `scale`.
inline Real tol_at(Real scale) { return Real(64) * kEpsilon * scale; }

// Largest absolute coordinate of the points.
inline Real max_abs(std::initializer_list<Vec3> vs) {
  Real m = Real(0);
  for (const Vec3& v : vs) m = std::max({m, std::abs(v.x), std::abs(v.y), std::abs(v.z)});
  return m;
}

// Golden-section minimum of a convex f over [lo, hi] (the end points included).
template <class F>
LD golden_min(F f, LD lo, LD hi, int iterations) {
  const LD r = (std::sqrt(LD(5)) - LD(1)) / LD(2);
  LD x1 = hi - r * (hi - lo);
  LD x2 = lo + r * (hi - lo);
  LD f1 = f(x1);
  LD f2 = f(x2);
  for (int i = 0; i < iterations; ++i) {
    if (f1 <= f2) {
      hi = x2;
      x2 = x1;
      f2 = f1;
      x1 = hi - r * (hi - lo);
      f1 = f(x1);
    } else {
      lo = x1;
      x1 = x2;
      f1 = f2;
      x2 = lo + r * (hi - lo);
      f2 = f(x2);
    }
  }
  return std::min({f1, f2, f(lo), f(hi)});
}

// Exact clamped projection in long double (the inner step of the nested searches).
inline LD ref_dist2_point_segment(const LVec& p, const LVec& a, const LVec& b) {
  const LVec ab = b - a;
  const LD den = glm::dot(ab, ab);
  LD t = den > 0 ? glm::dot(p - a, ab) / den : LD(0);
  t = std::clamp(t, LD(0), LD(1));
  return dist2(p, a + t * ab);
}

// Gram normal equations for the projection, and the three edges. Every candidate is a
// point of the triangle, so the minimum is never below the true distance, and equals it
// when the projection (well-conditioned triangles) or an edge is the answer.
inline LD ref_dist2_point_triangle(const LVec& p, const LVec& a, const LVec& b, const LVec& c) {
  const LVec ab = b - a;
  const LVec ac = c - a;
  const LVec ap = p - a;
  const LD g11 = glm::dot(ab, ab), g12 = glm::dot(ab, ac), g22 = glm::dot(ac, ac);
  const LD r1 = glm::dot(ab, ap), r2 = glm::dot(ac, ap);
  const LD det = g11 * g22 - g12 * g12;
  LD best =
      std::min({ref_dist2_point_segment(p, a, b), ref_dist2_point_segment(p, b, c), ref_dist2_point_segment(p, c, a)});
  if (det > LD(0)) {
    const LD v = (g22 * r1 - g12 * r2) / det;
    const LD w = (g11 * r2 - g12 * r1) / det;
    if (v >= 0 && w >= 0 && v + w <= 1) best = std::min(best, dist2(p, a + v * ab + w * ac));
  }
  return best;
}

}  // namespace proxima::test
