#pragma once
// References for the GJK / EPA / SAT / dispatch tests, computed without the code under test:
//  - support_signed_distance: max over unit u of  min_B u.x - max_A u.x  (support functions
//    only), by a Fibonacci sphere of directions refined by pattern search. Apart it is the
//    distance; overlapping it is minus the penetration depth.
//  - polytope_depth_exhaustive: the least overlap over every face normal of both polytopes
//    and every edge-pair cross product (no pruning), in double.
//  - polytope_distance_exhaustive: least vertex-triangle and edge-edge distance.
#include <proxima/shapes/placed.hpp>
#include <proxima/shapes/shape.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

#include "support/random.hpp"

namespace proxima::test::gjkref {

struct V {
  double x = 0, y = 0, z = 0;
};
inline V v(const Vec3& p) { return {double(p.x), double(p.y), double(p.z)}; }
inline V operator+(V a, V b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline V operator-(V a, V b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline V operator*(double s, V a) { return {s * a.x, s * a.y, s * a.z}; }
inline double dot(V a, V b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline V cross(V a, V b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
inline double norm(V a) { return std::sqrt(dot(a, a)); }
inline V unit(V a) { return (1.0 / norm(a)) * a; }

template <class A, class B>
double support_gap(const A& a, const Transform& pa, const B& b, const Transform& pb, V u) {
  const Vec3 d(Real(u.x), Real(u.y), Real(u.z));
  return dot(v(support(b, pb, -d)), u) - dot(v(support(a, pa, d)), u);
}

/// Signed distance from the support functions (see the file comment).
template <class A, class B>
double support_signed_distance(const A& a, const Transform& pa, const B& b, const Transform& pb, int samples = 1500,
                               int starts = 6) {
  std::vector<std::pair<double, V>> seeds;
  const double golden = 3.883222077450933;
  for (int i = 0; i < samples; ++i) {
    const double z = 1.0 - (2.0 * i + 1.0) / samples;
    const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
    const V u{r * std::cos(golden * i), r * std::sin(golden * i), z};
    seeds.emplace_back(support_gap(a, pa, b, pb, u), u);
  }
  const V c = v(pb.position) - v(pa.position);
  if (norm(c) > 0) seeds.emplace_back(support_gap(a, pa, b, pb, unit(c)), unit(c));
  const auto k = std::min<std::ptrdiff_t>(starts, std::ssize(seeds));
  std::partial_sort(seeds.begin(), seeds.begin() + k, seeds.end(),
                    [](const auto& l, const auto& r) { return l.first > r.first; });
  double best = seeds.front().first;
  std::uint64_t lcg = 99;
  auto next = [&lcg]() {
    lcg = lcg * 6364136223846793005ull + 1442695040888963407ull;
    return double(lcg >> 11) / double(1ull << 53) * 2.0 - 1.0;
  };
  for (std::ptrdiff_t s = 0; s < k; ++s) {
    V u = seeds[std::size_t(s)].second;
    double value = seeds[std::size_t(s)].first;
    for (double step = 0.05; step > 1e-7;) {
      bool improved = false;
      for (int j = 0; j < 10; ++j) {
        const V w = unit(u + step * V{next(), next(), next()});
        const double g = support_gap(a, pa, b, pb, w);
        if (g > value) value = g, u = w, improved = true;
      }
      if (!improved) step *= 0.5;
    }
    best = std::max(best, value);
  }
  return best;
}

/// A polytope in the world frame.
struct Poly {
  std::vector<V> verts;
  std::vector<V> normals;              // face normals
  std::vector<std::pair<V, V>> edges;  // segments
  std::vector<std::array<V, 3>> tris;  // fan triangulation of the faces
};

inline Poly world_poly(const ConvexHull& h, const Transform& t) {
  Poly p;
  for (const Vec3& x : h.vertices()) p.verts.push_back(v(t.apply(x)));
  for (std::uint32_t f = 0; f < h.faces().size(); ++f) {
    p.normals.push_back(v(t.apply_vector(h.faces()[f].normal)));
    const auto loop = h.face_vertices(f);
    for (std::size_t i = 1; i + 1 < loop.size(); ++i)
      p.tris.push_back({p.verts[loop[0]], p.verts[loop[i]], p.verts[loop[i + 1]]});
  }
  for (const HullEdge& e : h.edges()) p.edges.emplace_back(p.verts[e.v0], p.verts[e.v1]);
  return p;
}

inline Poly world_poly(const Box& b, const Transform& t) {
  const Vec3 h = b.half_extents();
  std::vector<Vec3> pts;
  for (int i = 0; i < 8; ++i) pts.emplace_back((i & 1) ? h.x : -h.x, (i & 2) ? h.y : -h.y, (i & 4) ? h.z : -h.z);
  return world_poly(ConvexHull::create(pts).value(), t);
}

inline double overlap_on(const Poly& a, const Poly& b, V l) {
  double amax = -1e300, bmin = 1e300;
  for (const V& x : a.verts) amax = std::max(amax, dot(x, l));
  for (const V& x : b.verts) bmin = std::min(bmin, dot(x, l));
  return bmin - amax;  // separation along l
}

/// Signed separation from all SAT axes (exact penetration when negative).
inline double polytope_sat_exhaustive(const Poly& a, const Poly& b) {
  double best = -1e300;
  auto test = [&](V l) {
    const double n = norm(l);
    if (!(n > 1e-12)) return;
    l = (1.0 / n) * l;
    best = std::max({best, overlap_on(a, b, l), overlap_on(a, b, -1.0 * l)});
  };
  for (const V& n : a.normals) test(n);
  for (const V& n : b.normals) test(n);
  for (const auto& ea : a.edges)
    for (const auto& eb : b.edges) test(cross(ea.second - ea.first, eb.second - eb.first));
  return best;
}

inline double seg_seg2(V p1, V q1, V p2, V q2) {
  const V d1 = q1 - p1, d2 = q2 - p2, r = p1 - p2;
  const double a = dot(d1, d1), e = dot(d2, d2), f = dot(d2, r);
  double s = 0, t = 0;
  if (a <= 1e-300 && e <= 1e-300) return dot(r, r);
  if (a <= 1e-300) {
    t = std::clamp(f / e, 0.0, 1.0);
    const V d = p1 - (p2 + t * d2);
    return dot(d, d);
  }
  if (e <= 1e-300) {
    s = std::clamp(-dot(d1, r) / a, 0.0, 1.0);
    const V d = (p1 + s * d1) - p2;
    return dot(d, d);
  }
  const double c = dot(d1, r), b = dot(d1, d2), den = a * e - b * b;
  s = den > 1e-300 ? std::clamp((b * f - c * e) / den, 0.0, 1.0) : 0.0;
  t = (b * s + f) / e;
  if (t < 0)
    t = 0, s = std::clamp(-c / a, 0.0, 1.0);
  else if (t > 1)
    t = 1, s = std::clamp((b - c) / a, 0.0, 1.0);
  const V d = (p1 + s * d1) - (p2 + t * d2);
  return dot(d, d);
}

inline double point_tri2(V p, V a, V b, V c) {
  const V n = cross(b - a, c - a);
  const double nn = dot(n, n);
  const double u = dot(cross(b - p, c - p), n), w = dot(cross(c - p, a - p), n), x = dot(cross(a - p, b - p), n);
  if (u >= 0 && w >= 0 && x >= 0 && nn > 0) {
    const double dd = dot(p - a, n);
    return dd * dd / nn;
  }
  return std::min({seg_seg2(p, p, a, b), seg_seg2(p, p, b, c), seg_seg2(p, p, c, a)});
}

/// Distance between the surfaces of two polytopes (= their distance when apart).
inline double polytope_distance_exhaustive(const Poly& a, const Poly& b) {
  double best = 1e300;
  for (const V& x : a.verts)
    for (const auto& t : b.tris) best = std::min(best, point_tri2(x, t[0], t[1], t[2]));
  for (const V& x : b.verts)
    for (const auto& t : a.tris) best = std::min(best, point_tri2(x, t[0], t[1], t[2]));
  for (const auto& ea : a.edges)
    for (const auto& eb : b.edges) best = std::min(best, seg_seg2(ea.first, ea.second, eb.first, eb.second));
  return std::sqrt(best);
}

/// A random hull of `n` points: in a ball, stretched by `stretch` (flat / needle hulls).
inline ConvexHull random_hull(Random& rng, int n, Real radius, const Vec3& stretch = Vec3(1)) {
  std::vector<Vec3> pts;
  for (int i = 0; i < n; ++i) pts.push_back(rng.in_ball(radius) * stretch);
  for (int i = 0; i < 4; ++i) pts.push_back(rng.unit_vector() * radius * stretch);
  return ConvexHull::create(pts).value();
}

/// A random hull with points on the sphere (every point a vertex).
inline ConvexHull sphere_hull(Random& rng, int n, Real radius) {
  std::vector<Vec3> pts;
  for (int i = 0; i < n; ++i) pts.push_back(rng.unit_vector() * radius);
  return ConvexHull::create(pts).value();
}

}  // namespace proxima::test::gjkref
