#pragma once
// Independent references for the signed distance of two placed convex shapes, used to decide
// who is right when the narrow phase and a peer library disagree. None calls the narrow
// phase; they use only the shapes' support mappings (the shape layer) or their vertices.
//
//  - reference_signed_distance: sd = max over unit u of  min_{x in B} u.x - max_{y in A} u.y
//    (the support function of the Minkowski difference B - A). Apart, this is a concave
//    maximisation over the unit ball, so a pattern search converges to the global optimum;
//    overlapping, the maximum over the sphere is global only after dense sampling, so it
//    starts from a Fibonacci sphere of directions and refines the best ones.
//  - polytope_depth_sat: exact penetration depth of two polytopes (boxes, hulls): the least
//    overlap over the face normals of both and the cross products of their edge directions
//    (the Minkowski difference's facet normals are among these).
//  - polytope_distance_brute: exact gap of two separated polytopes, the least distance over
//    every vertex-triangle and edge-edge pair (Ericson, Real-Time Collision Detection, 5.1).
#include <proxima/shapes/placed.hpp>
#include <proxima/shapes/shape.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <vector>

#include "shapes/shape_visit.hpp"

namespace proxima::test {

/// A 3-vector in double for the references.
struct D3v {
  double x = 0, y = 0, z = 0;
};
inline D3v d3v(const Vec3& v) { return {double(v.x), double(v.y), double(v.z)}; }
inline D3v operator+(D3v a, D3v b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline D3v operator-(D3v a, D3v b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline D3v operator*(double s, D3v a) { return {s * a.x, s * a.y, s * a.z}; }
inline double dot(D3v a, D3v b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline D3v cross(D3v a, D3v b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
inline double norm(D3v a) { return std::sqrt(dot(a, a)); }
inline D3v unit(D3v a) { return (1.0 / norm(a)) * a; }

/// World support point of a placed shape in direction u, in double.
inline D3v reference_support(const Shape& shape, const Transform& pose, D3v u) {
  const Vec3 d(static_cast<Real>(u.x), static_cast<Real>(u.y), static_cast<Real>(u.z));
  return d3v(detail::visit_convex(shape, [&](const auto& s) { return support(s, pose, d); }));
}

/// min_{x in B} u.x - max_{y in A} u.y for a unit u.
inline double support_gap(const Shape& a, const Transform& pa, const Shape& b, const Transform& pb, D3v u) {
  return dot(reference_support(b, pb, -1.0 * u), u) - dot(reference_support(a, pa, u), u);
}

/// The reference signed distance and its direction (A to B).
struct ReferenceDistance {
  double signed_distance = 0;
  D3v normal{};
};

/// Signed distance from the support functions (see the file comment). `samples` directions
/// seed the search; the best `starts` of them are refined. `extra_seeds` (any length, zero
/// vectors ignored) are further candidate directions, e.g. the normals the contestants
/// answered: each is only evaluated by the support functions here, so a wrong one cannot
/// raise the answer above the true maximum, while a right one on a narrow ridge of the
/// support function (where the pattern search may stall short of it) is found.
inline ReferenceDistance reference_signed_distance(const Shape& a, const Transform& pa, const Shape& b,
                                                   const Transform& pb, int samples = 1500, int starts = 8,
                                                   const std::vector<D3v>& extra_seeds = {}) {
  std::vector<std::pair<double, D3v>> seeds;
  for (const D3v& e : extra_seeds) {
    if (!(norm(e) > 0) || !std::isfinite(norm(e))) continue;
    const D3v u = unit(e);
    seeds.emplace_back(support_gap(a, pa, b, pb, u), u);
  }
  const double golden = 3.883222077450933;  // pi (3 - sqrt 5)
  for (int i = 0; i < samples; ++i) {
    const double z = 1.0 - (2.0 * i + 1.0) / samples;
    const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
    const D3v u{r * std::cos(golden * i), r * std::sin(golden * i), z};
    seeds.emplace_back(support_gap(a, pa, b, pb, u), u);
  }
  // The centre-to-centre direction is a good extra seed.
  const D3v c = d3v(pb.position) - d3v(pa.position);
  if (norm(c) > 0) {
    const D3v u = unit(c);
    seeds.emplace_back(support_gap(a, pa, b, pb, u), u);
  }
  std::partial_sort(seeds.begin(), seeds.begin() + std::min<std::ptrdiff_t>(starts, std::ssize(seeds)), seeds.end(),
                    [](const auto& l, const auto& r) { return l.first > r.first; });
  ReferenceDistance best{seeds.front().first, seeds.front().second};
  std::uint64_t lcg = 12345;
  auto next = [&lcg]() {
    lcg = lcg * 6364136223846793005ull + 1442695040888963407ull;
    return double(lcg >> 11) / double(1ull << 53) * 2.0 - 1.0;
  };
  for (int s = 0; s < std::min<int>(starts, int(seeds.size())); ++s) {
    D3v u = seeds[std::size_t(s)].second;
    double value = seeds[std::size_t(s)].first;
    double step = 0.05;
    while (step > 1e-9) {
      bool improved = false;
      for (int k = 0; k < 12; ++k) {
        const D3v w = unit(u + step * D3v{next(), next(), next()});
        const double v = support_gap(a, pa, b, pb, w);
        if (v > value) {
          value = v;
          u = w;
          improved = true;
        }
      }
      if (!improved) {
        // Before shrinking, a ring of 32 tangent directions: on a ridge of the support
        // function (an edge of the Minkowski difference) the ascent cone is narrow and 12
        // random tries can all miss it.
        const D3v helper = std::abs(u.x) < 0.6 ? D3v{1, 0, 0} : D3v{0, 1, 0};
        const D3v t1 = unit(cross(u, helper));
        const D3v t2 = cross(u, t1);
        const double phase = next() * 3.141592653589793;
        for (int k = 0; k < 32; ++k) {
          const double angle = phase + 6.283185307179586 * k / 32.0;
          const D3v w = unit(u + step * (std::cos(angle) * t1 + std::sin(angle) * t2));
          const double v = support_gap(a, pa, b, pb, w);
          if (v > value) {
            value = v;
            u = w;
            improved = true;
          }
        }
      }
      if (!improved) step *= 0.5;
    }
    if (value > best.signed_distance) best = {value, u};
  }
  return best;
}

/// A placed polytope in the world frame: vertices, face normals, edge directions.
struct WorldPolytope {
  std::vector<D3v> vertices;
  std::vector<D3v> face_normals;
  std::vector<D3v> edges;
  std::vector<std::array<D3v, 3>> triangles;
  std::vector<std::array<D3v, 2>> segments;
};

/// The world polytope of a Box or ConvexHull (nothing for other shapes).
inline std::optional<WorldPolytope> world_polytope(const Shape& shape, const Transform& pose) {
  WorldPolytope p;
  auto w = [&](const Vec3& v) { return d3v(pose.apply(v)); };
  auto wv = [&](const Vec3& v) { return d3v(pose.apply_vector(v)); };
  if (const Box* box = std::get_if<Box>(&shape)) {
    const Vec3 h = box->half_extents();
    for (int i = 0; i < 8; ++i) {
      p.vertices.push_back(w(Vec3((i & 1) ? h.x : -h.x, (i & 2) ? h.y : -h.y, (i & 4) ? h.z : -h.z)));
    }
    for (int axis = 0; axis < 3; ++axis) {
      Vec3 e(Real(0));
      e[axis] = Real(1);
      p.face_normals.push_back(wv(e));
      p.edges.push_back(wv(e));
    }
    // Faces as triangles and edges as segments (for the brute-force distance).
    const int quads[6][4] = {{0, 1, 3, 2}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 3, 7, 6}, {0, 2, 6, 4}, {1, 3, 7, 5}};
    for (const auto& q : quads) {
      p.triangles.push_back(
          {p.vertices[std::size_t(q[0])], p.vertices[std::size_t(q[1])], p.vertices[std::size_t(q[2])]});
      p.triangles.push_back(
          {p.vertices[std::size_t(q[0])], p.vertices[std::size_t(q[2])], p.vertices[std::size_t(q[3])]});
      for (int k = 0; k < 4; ++k) {
        p.segments.push_back({p.vertices[std::size_t(q[k])], p.vertices[std::size_t(q[(k + 1) % 4])]});
      }
    }
    return p;
  }
  if (const ConvexHull* hull = std::get_if<ConvexHull>(&shape)) {
    for (const Vec3& v : hull->vertices()) p.vertices.push_back(w(v));
    for (std::uint32_t f = 0; f < hull->faces().size(); ++f) {
      p.face_normals.push_back(wv(hull->faces()[f].normal));
      const auto loop = hull->face_vertices(f);
      for (std::size_t k = 1; k + 1 < loop.size(); ++k) {
        p.triangles.push_back({p.vertices[loop[0]], p.vertices[loop[k]], p.vertices[loop[k + 1]]});
      }
    }
    for (const HullEdge& e : hull->edges()) {
      p.edges.push_back(p.vertices[e.v1] - p.vertices[e.v0]);
      p.segments.push_back({p.vertices[e.v0], p.vertices[e.v1]});
    }
    return p;
  }
  return std::nullopt;
}

/// Exact penetration depth of two overlapping polytopes (negative overlap = gap on some axis
/// means they are apart; then the largest gap is returned as a negative depth).
inline double polytope_depth_sat(const WorldPolytope& a, const WorldPolytope& b) {
  double depth = 1e300;
  auto test_axis = [&](D3v axis) {
    const double n = norm(axis);
    if (n < 1e-9) return;
    axis = (1.0 / n) * axis;
    double amin = 1e300, amax = -1e300, bmin = 1e300, bmax = -1e300;
    for (const D3v& v : a.vertices) {
      amin = std::min(amin, dot(v, axis));
      amax = std::max(amax, dot(v, axis));
    }
    for (const D3v& v : b.vertices) {
      bmin = std::min(bmin, dot(v, axis));
      bmax = std::max(bmax, dot(v, axis));
    }
    depth = std::min(depth, std::min(amax - bmin, bmax - amin));
  };
  for (const D3v& n : a.face_normals) test_axis(n);
  for (const D3v& n : b.face_normals) test_axis(n);
  for (const D3v& ea : a.edges) {
    for (const D3v& eb : b.edges) {
      // Skip nearly parallel edges: their cross product's direction is noise.
      const D3v c = cross(ea, eb);
      if (norm(c) > 1e-6 * norm(ea) * norm(eb)) test_axis(c);
    }
  }
  return depth;
}

/// Squared distance from p to triangle abc (Ericson 5.1.5).
inline double point_triangle_distance2(D3v p, D3v a, D3v b, D3v c) {
  const D3v ab = b - a, ac = c - a, ap = p - a;
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  auto d2of = [&](D3v q) { return dot(p - q, p - q); };
  if (d1 <= 0 && d2 <= 0) return d2of(a);
  const D3v bp = p - b;
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return d2of(b);
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return d2of(a + (d1 / (d1 - d3)) * ab);
  const D3v cp = p - c;
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return d2of(c);
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return d2of(a + (d2 / (d2 - d6)) * ac);
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) return d2of(b + ((d4 - d3) / ((d4 - d3) + (d5 - d6))) * (c - b));
  const double denom = 1.0 / (va + vb + vc);
  return d2of(a + (vb * denom) * ab + (vc * denom) * ac);
}

/// Squared distance between segments p1q1 and p2q2 (Ericson 5.1.9).
inline double segment_segment_distance2(D3v p1, D3v q1, D3v p2, D3v q2) {
  const D3v d1 = q1 - p1, d2 = q2 - p2, r = p1 - p2;
  const double a = dot(d1, d1), e = dot(d2, d2), f = dot(d2, r);
  double s = 0, t = 0;
  const double c = dot(d1, r), b = dot(d1, d2), denom = a * e - b * b;
  s = denom > 1e-300 ? std::clamp((b * f - c * e) / denom, 0.0, 1.0) : 0.0;
  t = (b * s + f) / e;
  if (t < 0) {
    t = 0;
    s = std::clamp(-c / a, 0.0, 1.0);
  } else if (t > 1) {
    t = 1;
    s = std::clamp((b - c) / a, 0.0, 1.0);
  }
  const D3v x = (p1 + s * d1) - (p2 + t * d2);
  return dot(x, x);
}

/// Exact gap of two separated polytopes: least vertex-triangle and edge-edge distance.
inline double polytope_distance_brute(const WorldPolytope& a, const WorldPolytope& b) {
  double best = 1e300;
  for (const D3v& v : a.vertices) {
    for (const auto& t : b.triangles) best = std::min(best, point_triangle_distance2(v, t[0], t[1], t[2]));
  }
  for (const D3v& v : b.vertices) {
    for (const auto& t : a.triangles) best = std::min(best, point_triangle_distance2(v, t[0], t[1], t[2]));
  }
  for (const auto& sa : a.segments) {
    for (const auto& sb : b.segments) best = std::min(best, segment_segment_distance2(sa[0], sa[1], sb[0], sb[1]));
  }
  return std::sqrt(best);
}

/// The deciding reference: exact for two polytopes, support-function search otherwise.
inline double decide_signed_distance(const Shape& a, const Transform& pa, const Shape& b, const Transform& pb,
                                     const std::vector<D3v>& extra_seeds = {}) {
  const auto wa = world_polytope(a, pa);
  const auto wb = world_polytope(b, pb);
  if (wa && wb) {
    const double depth = polytope_depth_sat(*wa, *wb);
    if (depth > 0) return -depth;
    return polytope_distance_brute(*wa, *wb);
  }
  return reference_signed_distance(a, pa, b, pb, 1500, 8, extra_seeds).signed_distance;
}

}  // namespace proxima::test
