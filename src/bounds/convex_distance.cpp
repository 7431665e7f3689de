// Distance between the convex hulls of two point sets (GJK).
//
// Steps:
//  1. Work in double relative to a local origin (a's first point); support points are
//     found by a linear scan (the sets are small: box corners, k-DOP or hull vertices).
//  2. GJK: v = a point of the Minkowski difference A - B; repeat: w = s_A(-v) - s_B(v);
//     stop when |v|^2 - v.w <= eps |v|^2 (the support gap bounds the error), when w is
//     already in the simplex, or when |v| stops decreasing; otherwise add w and replace
//     the simplex by the smallest sub-simplex holding its point closest to the origin.
//  3. Closest point of a simplex to the origin by Voronoi regions: segment (clamped
//     parameter), triangle (Ericson 5.1.5; a degenerate triangle falls back to its
//     edges), tetrahedron (every face whose plane separates the origin from the opposite
//     vertex is tried; none means the origin is inside: distance 0; a flat tetrahedron
//     tries all faces).
//  4. The witness points are the same barycentric combinations of the A and B points.
// Sources: E. Gilbert, D. Johnson, S. Keerthi, "A fast procedure for computing the
// distance between complex objects in three-dimensional space", IEEE J. Robotics and
// Automation 4(2), 1988; G. van den Bergen, "A Fast and Robust GJK Implementation for
// Collision Detection of Convex Objects", JGT 4(2), 1999; Ericson, Real-Time Collision
// Detection, 5.1.5, 5.1.6 and 9.5.
#include <proxima/bounds/convex_distance.hpp>
#include <proxima/core/tolerance.hpp>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include <algorithm>
#include <array>
#include <cmath>

namespace proxima {
namespace {

using D3 = glm::dvec3;

struct Vertex {
  D3 w;  // a - b
  D3 a;
  D3 b;
};

struct Simplex {
  std::array<Vertex, 4> v{};
  std::array<double, 4> lambda{};
  int n = 0;
};

// Closest point to the origin of segment (v0, v1): keeps the sub-simplex and weights.
void solve_segment(Simplex& s, int i0, int i1, Simplex& out) {
  const D3 a = s.v[i0].w, b = s.v[i1].w;
  const D3 ab = b - a;
  const double len2 = glm::dot(ab, ab);
  double t = len2 > 0.0 ? -glm::dot(a, ab) / len2 : 0.0;
  if (t <= 0.0) {
    out.n = 1;
    out.v[0] = s.v[i0];
    out.lambda[0] = 1.0;
  } else if (t >= 1.0) {
    out.n = 1;
    out.v[0] = s.v[i1];
    out.lambda[0] = 1.0;
  } else {
    out.n = 2;
    out.v[0] = s.v[i0];
    out.v[1] = s.v[i1];
    out.lambda[0] = 1.0 - t;
    out.lambda[1] = t;
  }
}

D3 point_of(const Simplex& s) {
  D3 p(0.0);
  for (int i = 0; i < s.n; ++i) p += s.lambda[i] * s.v[i].w;
  return p;
}

// Closest point to the origin of triangle (i0, i1, i2) by Voronoi regions (Ericson 5.1.5).
void solve_triangle(Simplex& s, int i0, int i1, int i2, Simplex& out) {
  const D3 a = s.v[i0].w, b = s.v[i1].w, c = s.v[i2].w;
  const D3 ab = b - a, ac = c - a, ap = -a;
  const double d1 = glm::dot(ab, ap), d2 = glm::dot(ac, ap);
  if (d1 <= 0.0 && d2 <= 0.0) {
    out.n = 1;
    out.v[0] = s.v[i0];
    out.lambda[0] = 1.0;
    return;
  }
  const D3 bp = -b;
  const double d3 = glm::dot(ab, bp), d4 = glm::dot(ac, bp);
  if (d3 >= 0.0 && d4 <= d3) {
    out.n = 1;
    out.v[0] = s.v[i1];
    out.lambda[0] = 1.0;
    return;
  }
  const D3 cp = -c;
  const double d5 = glm::dot(ab, cp), d6 = glm::dot(ac, cp);
  if (d6 >= 0.0 && d5 <= d6) {
    out.n = 1;
    out.v[0] = s.v[i2];
    out.lambda[0] = 1.0;
    return;
  }
  const double vc = d1 * d4 - d3 * d2;
  const double vb = d5 * d2 - d1 * d6;
  const double va = d3 * d6 - d5 * d4;
  const double sum = va + vb + vc;
  const D3 n = glm::cross(ab, ac);
  const double n2 = glm::dot(n, n);
  const double scale2 = std::max({glm::dot(ab, ab), glm::dot(ac, ac), glm::dot(c - b, c - b)});
  if (!(n2 > 1e-24 * scale2 * scale2) || !(sum > 0.0)) {
    // Degenerate (collinear) triangle: the best of its edges.
    Simplex best, cand;
    double best_d = -1.0;
    const int e[3][2] = {{i0, i1}, {i1, i2}, {i2, i0}};
    for (const auto& ed : e) {
      solve_segment(s, ed[0], ed[1], cand);
      const D3 p = point_of(cand);
      const double d = glm::dot(p, p);
      if (best_d < 0.0 || d < best_d) {
        best_d = d;
        best = cand;
      }
    }
    out = best;
    return;
  }
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) {
    solve_segment(s, i0, i1, out);
    return;
  }
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) {
    solve_segment(s, i0, i2, out);
    return;
  }
  if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0) {
    solve_segment(s, i1, i2, out);
    return;
  }
  out.n = 3;
  out.v[0] = s.v[i0];
  out.v[1] = s.v[i1];
  out.v[2] = s.v[i2];
  out.lambda[1] = vb / sum;
  out.lambda[2] = vc / sum;
  out.lambda[0] = 1.0 - out.lambda[1] - out.lambda[2];
}

// Returns false when the origin is inside the tetrahedron.
bool solve_tetrahedron(Simplex& s, Simplex& out) {
  const int faces[4][4] = {{0, 1, 2, 3}, {0, 2, 3, 1}, {0, 3, 1, 2}, {1, 3, 2, 0}};
  bool any = false;
  double best_d = -1.0;
  Simplex cand;
  for (const auto& f : faces) {
    const D3 a = s.v[f[0]].w, b = s.v[f[1]].w, c = s.v[f[2]].w, d = s.v[f[3]].w;
    const D3 n = glm::cross(b - a, c - a);
    const double side_o = glm::dot(-a, n);
    const double side_d = glm::dot(d - a, n);
    const double n_len = std::sqrt(glm::dot(n, n));
    const double span = std::max({glm::length(b - a), glm::length(c - a), glm::length(d - a)});
    const bool flat = !(std::abs(side_d) > 1e-12 * n_len * span);
    // Origin outside this face's plane (on the side away from the opposite vertex).
    if (!flat && side_o * side_d > 0.0) continue;
    any = true;
    solve_triangle(s, f[0], f[1], f[2], cand);
    const D3 p = point_of(cand);
    const double dist = glm::dot(p, p);
    if (best_d < 0.0 || dist < best_d) {
      best_d = dist;
      out = cand;
    }
  }
  return any;
}

}  // namespace

ConvexDistance convex_distance(std::span<const Vec3> a, std::span<const Vec3> b) {
  ConvexDistance result;
  if (a.empty() || b.empty()) return result;
  const D3 origin(a[0]);
  auto support = [&](std::span<const Vec3> set, const D3& d) {
    D3 best = D3(set[0]) - origin;
    double best_s = glm::dot(best, d);
    for (std::size_t i = 1; i < set.size(); ++i) {
      const D3 p = D3(set[i]) - origin;
      const double s = glm::dot(p, d);
      if (s > best_s) {
        best_s = s;
        best = p;
      }
    }
    return best;
  };
  Simplex simplex;
  Vertex first;
  first.a = D3(a[0]) - origin;
  first.b = D3(b[0]) - origin;
  first.w = first.a - first.b;
  simplex.v[0] = first;
  simplex.lambda[0] = 1.0;
  simplex.n = 1;
  D3 v = first.w;
  double vv = glm::dot(v, v);
  double scale2 = vv;
  constexpr double kRelative = 1e-12;
  int it = 0;
  bool inside = false;
  for (; it < 128; ++it) {
    if (vv == 0.0) {
      inside = true;
      break;
    }
    Vertex w;
    w.a = support(a, -v);
    w.b = support(b, v);
    w.w = w.a - w.b;
    scale2 = std::max(scale2, glm::dot(w.w, w.w));
    // Convergence: the support gap bounds |v|^2 - dist^2 from above.
    if (vv - glm::dot(v, w.w) <= kRelative * vv) break;
    bool duplicate = false;
    for (int i = 0; i < simplex.n; ++i) {
      if (simplex.v[i].w == w.w) duplicate = true;
    }
    if (duplicate) break;
    Simplex grown = simplex;
    grown.v[grown.n++] = w;
    Simplex next;
    if (grown.n == 2) {
      solve_segment(grown, 0, 1, next);
    } else if (grown.n == 3) {
      solve_triangle(grown, 0, 1, 2, next);
    } else {
      if (!solve_tetrahedron(grown, next)) {
        simplex = grown;
        inside = true;
        break;
      }
    }
    const D3 nv = point_of(next);
    const double nvv = glm::dot(nv, nv);
    if (!(nvv < vv)) break;  // no progress: keep the previous (better) simplex
    simplex = next;
    v = nv;
    vv = nvv;
    if (vv <= 1e-30 * scale2) {
      inside = true;
      break;
    }
  }
  result.iterations = it;
  if (inside) {
    // Any common point: the current simplex's witness combination.
    D3 pa(0.0), pb(0.0);
    if (simplex.n == 4) {
      // Barycentric coordinates of the origin in the tetrahedron (signed volumes).
      const D3 w0 = simplex.v[0].w, w1 = simplex.v[1].w, w2 = simplex.v[2].w, w3 = simplex.v[3].w;
      const double total = glm::dot(w1 - w0, glm::cross(w2 - w0, w3 - w0));
      double l[4] = {glm::dot(w1, glm::cross(w2, w3)), -glm::dot(w0, glm::cross(w2, w3)),
                     glm::dot(w0, glm::cross(w1, w3)), -glm::dot(w0, glm::cross(w1, w2))};
      double sum = 0.0;
      for (double& x : l) {
        x = total != 0.0 ? std::max(x / total, 0.0) : 0.25;
        sum += x;
      }
      for (int i = 0; i < 4; ++i) {
        const double li = sum > 0.0 ? l[i] / sum : 0.25;
        pa += li * simplex.v[i].a;
        pb += li * simplex.v[i].b;
      }
    } else {
      for (int i = 0; i < simplex.n; ++i) {
        pa += simplex.lambda[i] * simplex.v[i].a;
        pb += simplex.lambda[i] * simplex.v[i].b;
      }
    }
    result.distance = Real(0);
    result.on_a = Vec3(pa + origin);
    result.on_b = Vec3(pb + origin);
    return result;
  }
  D3 pa(0.0), pb(0.0);
  for (int i = 0; i < simplex.n; ++i) {
    pa += simplex.lambda[i] * simplex.v[i].a;
    pb += simplex.lambda[i] * simplex.v[i].b;
  }
  result.distance = Real(std::sqrt(vv));
  result.on_a = Vec3(pa + origin);
  result.on_b = Vec3(pb + origin);
  return result;
}

bool convex_cores_overlap(std::span<const Vec3> a, Real radius_a, std::span<const Vec3> b, Real radius_b) {
  double magnitude = double(radius_a) + double(radius_b);
  for (const Vec3& p : a)
    magnitude = std::max({magnitude, double(std::abs(p.x)), double(std::abs(p.y)), double(std::abs(p.z))});
  for (const Vec3& p : b)
    magnitude = std::max({magnitude, double(std::abs(p.x)), double(std::abs(p.y)), double(std::abs(p.z))});
  const ConvexDistance d = convex_distance(a, b);
  const double tolerance = 16.0 * double(kEpsilon) * magnitude;
  return double(d.distance) <= double(radius_a) + double(radius_b) + tolerance;
}

}  // namespace proxima
