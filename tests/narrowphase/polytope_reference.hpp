#pragma once
// References for the polyhedral pair tests, computed without the code under test: the
// separating-axis overlap over every face normal and edge-pair cross product in long double
// (exact depth of two polytopes), a dense-direction upper bound of the depth, exhaustive
// feature-pair distances, and contact-manifold invariants.
#include <gtest/gtest.h>

#include <proxima/core/math.hpp>
#include <proxima/core/transform.hpp>
#include <proxima/geometry/closest_points.hpp>
#include <proxima/narrowphase/contact.hpp>
#include <proxima/shapes/box.hpp>
#include <proxima/shapes/triangle.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include "support/random.hpp"

namespace proxima::test {

using LD = long double;

struct PolyVec {
  LD x = 0, y = 0, z = 0;
};
inline PolyVec operator-(const PolyVec& a, const PolyVec& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline LD dot(const PolyVec& a, const PolyVec& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline PolyVec cross(const PolyVec& a, const PolyVec& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline LD norm(const PolyVec& a) { return std::sqrt(dot(a, a)); }

// A transform applied in long double (quaternion rotation written out).
inline PolyVec apply_ld(const Transform& t, const Vec3& p) {
  const LD w = t.rotation.w, x = t.rotation.x, y = t.rotation.y, z = t.rotation.z;
  const LD n = std::sqrt(w * w + x * x + y * y + z * z);
  const LD qw = w / n, qx = x / n, qy = y / n, qz = z / n;
  const LD px = p.x, py = p.y, pz = p.z;
  // v' = v + 2 q x (q x v + w v)
  const LD cx = qy * pz - qz * py + qw * px;
  const LD cy = qz * px - qx * pz + qw * py;
  const LD cz = qx * py - qy * px + qw * pz;
  return {px + 2 * (qy * cz - qz * cy) + LD(t.position.x), py + 2 * (qz * cx - qx * cz) + LD(t.position.y),
          pz + 2 * (qx * cy - qy * cx) + LD(t.position.z)};
}

// A polytope given by its world vertices, face normals and edge directions (long double).
struct LPolytope {
  std::vector<PolyVec> vertices;
  std::vector<PolyVec> face_normals;
  std::vector<PolyVec> edge_dirs;
};

inline LPolytope box_polytope(const Box& box, const Transform& pose) {
  LPolytope p;
  const Vec3 h = box.half_extents();
  for (int c = 0; c < 8; ++c) {
    p.vertices.push_back(apply_ld(pose, Vec3((c & 1) ? h.x : -h.x, (c & 2) ? h.y : -h.y, (c & 4) ? h.z : -h.z)));
  }
  const PolyVec o = apply_ld(pose, Vec3(0));
  for (int i = 0; i < 3; ++i) {
    Vec3 e(0);
    e[i] = 1;
    const PolyVec d = apply_ld(pose, e) - o;
    p.face_normals.push_back(d);
    p.edge_dirs.push_back(d);
  }
  return p;
}

inline LPolytope triangle_polytope(const Triangle& tri, const Transform& pose) {
  LPolytope p;
  for (int i = 0; i < 3; ++i) p.vertices.push_back(apply_ld(pose, tri.vertex(i)));
  const PolyVec n = cross(p.vertices[1] - p.vertices[0], p.vertices[2] - p.vertices[0]);
  p.face_normals.push_back(n);
  for (int i = 0; i < 3; ++i) {
    const PolyVec e = p.vertices[(i + 1) % 3] - p.vertices[i];
    p.edge_dirs.push_back(e);
    p.face_normals.push_back(cross(n, e));  // in-plane normals (matter only for coplanar pairs)
  }
  return p;
}

// Overlap of the two projections on axis l (negative: separated by that much).
inline LD overlap_on(const LPolytope& a, const LPolytope& b, PolyVec l) {
  const LD len = norm(l);
  l = {l.x / len, l.y / len, l.z / len};
  LD amin = std::numeric_limits<LD>::infinity(), amax = -amin, bmin = amin, bmax = -amin;
  for (const PolyVec& v : a.vertices) {
    amin = std::min(amin, dot(v, l));
    amax = std::max(amax, dot(v, l));
  }
  for (const PolyVec& v : b.vertices) {
    bmin = std::min(bmin, dot(v, l));
    bmax = std::max(bmax, dot(v, l));
  }
  return std::min(amax - bmin, bmax - amin);
}

// Minimum overlap over every face normal and edge-pair cross product: the penetration
// depth when > 0, a lower bound of minus the gap when < 0.
inline LD sat_overlap(const LPolytope& a, const LPolytope& b) {
  LD best = std::numeric_limits<LD>::infinity();
  LD scale = 0;
  for (const PolyVec& v : a.vertices) scale = std::max(scale, norm(v));
  for (const PolyVec& v : b.vertices) scale = std::max(scale, norm(v));
  for (const PolyVec& n : a.face_normals) best = std::min(best, overlap_on(a, b, n));
  for (const PolyVec& n : b.face_normals) best = std::min(best, overlap_on(a, b, n));
  for (const PolyVec& ea : a.edge_dirs) {
    for (const PolyVec& eb : b.edge_dirs) {
      const PolyVec c = cross(ea, eb);
      if (norm(c) > 1e-9L * norm(ea) * norm(eb)) best = std::min(best, overlap_on(a, b, c));
    }
  }
  return best;
}

// Smallest overlap over `count` random unit directions: an upper bound of the depth.
inline LD dense_overlap(const LPolytope& a, const LPolytope& b, Random& rng, int count) {
  LD best = std::numeric_limits<LD>::infinity();
  for (int i = 0; i < count; ++i) {
    const Vec3 d = rng.unit_vector();
    best = std::min(best, overlap_on(a, b, {d.x, d.y, d.z}));
  }
  return best;
}

// Box corners and edges in the world frame (Real).
inline std::array<Vec3, 8> box_corners(const Box& box, const Transform& pose) {
  std::array<Vec3, 8> c{};
  const Vec3 h = box.half_extents();
  for (int i = 0; i < 8; ++i) c[i] = pose.apply(Vec3((i & 1) ? h.x : -h.x, (i & 2) ? h.y : -h.y, (i & 4) ? h.z : -h.z));
  return c;
}
inline std::array<std::array<int, 2>, 12> box_edges() {
  std::array<std::array<int, 2>, 12> e{};
  int n = 0;
  for (int c = 0; c < 8; ++c) {
    for (int bit = 1; bit < 8; bit <<= 1) {
      if (!(c & bit)) e[n++] = {c, c | bit};
    }
  }
  return e;
}

// Exhaustive distance of two separated boxes: every corner against the other box, every
// edge pair.
inline Real brute_box_box_distance(const Box& a, const Transform& pa, const Box& b, const Transform& pb) {
  Real best = std::numeric_limits<Real>::infinity();
  const auto ca = box_corners(a, pa);
  const auto cb = box_corners(b, pb);
  const Mat3 ma = pa.rotation_matrix();
  const Mat3 mb = pb.rotation_matrix();
  for (const Vec3& v : ca) {
    best = std::min(best, glm::length(v - geometry::closest_point_obb(v, pb.position, mb, b.half_extents())));
  }
  for (const Vec3& v : cb) {
    best = std::min(best, glm::length(v - geometry::closest_point_obb(v, pa.position, ma, a.half_extents())));
  }
  for (const auto& ea : box_edges()) {
    for (const auto& eb : box_edges()) {
      const auto sp = geometry::closest_points_segment_segment(ca[ea[0]], ca[ea[1]], cb[eb[0]], cb[eb[1]]);
      best = std::min(best, std::sqrt(sp.distance_squared));
    }
  }
  return best;
}

// Area of the convex hull of the manifold's points projected on the plane orthogonal to n.
inline Real manifold_area(const ContactManifold& m) {
  if (m.count < 3) return Real(0);
  Vec3 t1, t2;
  orthonormal_basis(m.normal, t1, t2);
  std::vector<Vec2> p;
  for (int i = 0; i < m.count; ++i)
    p.emplace_back(glm::dot(m.points[i].point_a, t1), glm::dot(m.points[i].point_a, t2));
  Vec2 c(0);
  for (const Vec2& q : p) c += q / static_cast<Real>(p.size());
  std::sort(p.begin(), p.end(), [&](const Vec2& u, const Vec2& v) {
    return std::atan2(u.y - c.y, u.x - c.x) < std::atan2(v.y - c.y, v.x - c.x);
  });
  Real area = 0;
  for (size_t i = 0; i < p.size(); ++i) {
    const Vec2& u = p[i];
    const Vec2& v = p[(i + 1) % p.size()];
    area += u.x * v.y - v.x * u.y;
  }
  return std::abs(area) / 2;
}

}  // namespace proxima::test
