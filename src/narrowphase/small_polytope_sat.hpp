#pragma once
/// @file small_polytope_sat.hpp
/// Separating-axis test between two small polytopes given by their world vertices (a
/// triangle, a box), over candidate axes (face normals, edge-pair cross products, in-plane
/// edge normals of flat shapes). The largest separation is the signed distance when it is
/// <= 0 (exact penetration depth, every face of the Minkowski difference having one of
/// these normals), a lower bound of the gap otherwise. O(axes x vertices), no allocation.

#include <proxima/core/math.hpp>
#include <proxima/core/tolerance.hpp>
#include <proxima/core/transform.hpp>
#include <proxima/shapes/triangle.hpp>

#include <array>
#include <cmath>
#include <limits>

namespace proxima::narrow {

/// Vertices, face normals and edge directions of a polytope with at most 8 vertices.
struct SmallPolytope {
  std::array<Vec3, 8> vertices{};  ///< world frame (or any common frame)
  int vertex_count = 0;            ///< valid vertices
  std::array<Vec3, 6> faces{};     ///< face normals (need not be unit; sign irrelevant)
  int face_count = 0;              ///< valid face normals
  std::array<Vec3, 3> edges{};     ///< edge directions (one per parallel class)
  int edge_count = 0;              ///< valid edge directions
};

/// Result of small_polytope_sat: the largest separation and its unit axis, A to B.
struct SmallSat {
  Real separation = -std::numeric_limits<Real>::infinity();  ///< > 0 gap bound, <= 0 minus the depth
  Vec3 normal{Real(0), Real(0), Real(1)};                    ///< unit, from A to B
};

/// Separation of the two vertex sets along `axis` (unit), with the side: `normal` is axis or
/// -axis, pointing from A to B.
/// The interval [lo, hi] of a polytope's vertices projected on `axis`.
inline void project_vertices(const SmallPolytope& p, const Vec3& axis, Real& lo, Real& hi) {
  lo = std::numeric_limits<Real>::infinity();
  hi = -lo;
  for (int i = 0; i < p.vertex_count; ++i) {
    const Real d = glm::dot(p.vertices[i], axis);
    lo = std::min(lo, d);
    hi = std::max(hi, d);
  }
}

inline Real axis_separation(const SmallPolytope& a, const SmallPolytope& b, const Vec3& axis, Vec3& normal) {
  Real amin, amax, bmin, bmax;
  project_vertices(a, axis, amin, amax);
  project_vertices(b, axis, bmin, bmax);
  const Real plus = bmin - amax;   // B on the + side
  const Real minus = amin - bmax;  // B on the - side
  normal = plus >= minus ? axis : -axis;
  return std::max(plus, minus);
}

/// SAT over the face normals of both, their edge-pair cross products (pairs within
/// `parallel_sine` of parallel skipped) and `extra` axes.
inline SmallSat small_polytope_sat(const SmallPolytope& a, const SmallPolytope& b, const Vec3* extra, int extra_count,
                                   Real parallel_sine) {
  SmallSat s;
  const auto test = [&](const Vec3& raw, bool is_edge) {
    Vec3 axis;
    Real len = Real(0);
    if (!unit_and_length(raw, axis, len)) return;
    Vec3 n;
    const Real sep = axis_separation(a, b, axis, n);
    // Edge axes must beat the others by more than rounding (nearly parallel edges).
    if (sep > s.separation + (is_edge ? kRelativeTolerance * std::abs(s.separation) : Real(0))) {
      s.separation = sep;
      s.normal = n;
    }
  };
  for (int i = 0; i < a.face_count; ++i) test(a.faces[i], false);
  for (int i = 0; i < b.face_count; ++i) test(b.faces[i], false);
  for (int i = 0; i < extra_count; ++i) test(extra[i], false);
  for (int i = 0; i < a.edge_count; ++i) {
    for (int j = 0; j < b.edge_count; ++j) {
      const Vec3 c = glm::cross(a.edges[i], b.edges[j]);
      const Real la = glm::length(a.edges[i]);
      const Real lb = glm::length(b.edges[j]);
      if (glm::length(c) > parallel_sine * la * lb) test(c, true);
    }
  }
  return s;
}

/// The translations t of B along `d` (B moved by t * d) for which the two polytopes overlap
/// or touch, over the candidate axes of small_polytope_sat: the interval [lo, hi], empty
/// when lo > hi. For polytopes whose candidate axes hold every face normal of their
/// Minkowski difference (a triangle or a box against a box), the interval is exact: each
/// axis m bounds t by the gap of the projections over m . d (Minkowski difference as an
/// intersection of half-spaces; the ray cast of van den Bergen, "Collision Detection in
/// Interactive 3D Environments", 5.5, done over the planes). O(axes * vertices).
struct TranslationInterval {
  Real lo = -std::numeric_limits<Real>::infinity();  ///< smallest t (length units of d)
  Real hi = std::numeric_limits<Real>::infinity();   ///< largest t
};

/// The interval of t (see TranslationInterval) for polytopes a and b and the direction d.
inline TranslationInterval small_polytope_translation_interval(const SmallPolytope& a, const SmallPolytope& b,
                                                               const Vec3& d, Real parallel_sine) {
  TranslationInterval r;
  const auto bound = [&](const Vec3& m) {
    Real amin, amax, bmin, bmax;
    project_vertices(a, m, amin, amax);
    project_vertices(b, m, bmin, bmax);
    // Overlap along m: amin - bmax <= t c <= amax - bmin.
    const Real c = glm::dot(m, d);
    if (c > Real(0)) {
      r.lo = std::max(r.lo, (amin - bmax) / c);
      r.hi = std::min(r.hi, (amax - bmin) / c);
    } else if (c < Real(0)) {
      r.lo = std::max(r.lo, (amax - bmin) / c);
      r.hi = std::min(r.hi, (amin - bmax) / c);
    } else if (amin - bmax > Real(0) || bmin - amax > Real(0)) {
      r.lo = std::numeric_limits<Real>::infinity();  // separated along m whatever t
      r.hi = -r.lo;
    }
  };
  for (int i = 0; i < a.face_count; ++i) bound(a.faces[i]);
  for (int i = 0; i < b.face_count; ++i) bound(b.faces[i]);
  for (int i = 0; i < a.edge_count; ++i) {
    for (int j = 0; j < b.edge_count; ++j) {
      const Vec3 c = glm::cross(a.edges[i], b.edges[j]);
      if (glm::length(c) > parallel_sine * glm::length(a.edges[i]) * glm::length(b.edges[j])) bound(c);
    }
  }
  return r;
}

/// Smallest sine between two edges whose cross product is a candidate axis of the triangle
/// pairs (nearly parallel edges give no axis).
inline const Real kParallelSine = Real(4) * kSqrtEpsilon;

/// The SAT polytope of triangle `t` placed by `pose` (world frame): its 3 vertices, its
/// normal and its 3 in-plane edge normals (which separate coplanar flat shapes), its edges.
inline void triangle_polytope(const Triangle& t, const Transform& pose, SmallPolytope& p) {
  p.vertex_count = 3;
  for (int i = 0; i < 3; ++i) p.vertices[i] = pose.apply(t.vertex(i));
  const Vec3 n = pose.apply_vector(t.normal());
  p.face_count = 4;
  p.faces[0] = n;
  p.edge_count = 3;
  for (int i = 0; i < 3; ++i) {
    p.edges[i] = p.vertices[(i + 1) % 3] - p.vertices[i];
    p.faces[1 + i] = glm::cross(n, p.edges[i]);
  }
}

}  // namespace proxima::narrow
