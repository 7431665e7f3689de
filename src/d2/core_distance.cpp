/// @file core_distance.cpp
/// Signed distance of two rounded 2D cores.
///
/// Steps (Gilbert, Johnson and Keerthi 1988; the simplex solver of Ericson, Real-Time
/// Collision Detection §5.1.5 and §9.5):
///   1. move B into A's frame (core_pair.hpp);
///   2. GJK on the Minkowski difference B - A of the cores: keep a simplex of up to three
///      support points, replace it by the sub-simplex nearest the origin, search towards the
///      origin; stop when the new support point gains nothing (the cores are apart by the
///      simplex's distance) or the simplex encloses the origin (the cores overlap);
///   3. apart: witnesses from the barycentric weights, then the radii move them out along
///      the normal; overlapping: the penetration of convex polygons is the smallest overlap
///      over both polygons' edge normals (the Minkowski difference's edge normals), exact,
///      with the deepest vertex as the witness.

#include <proxima/d2/convex_queries.hpp>

#include <array>

#include "d2/core_pair.hpp"

namespace proxima::d2 {
namespace {

using detail::CorePair;

struct SimplexVertex {
  Vec2 a{Real(0)};  ///< support point of A
  Vec2 b{Real(0)};  ///< support point of B
  Vec2 w{Real(0)};  ///< b - a
  int ia = 0;       ///< vertex of A
  int ib = 0;       ///< vertex of B
  Real weight = Real(1);
};

struct Simplex {
  std::array<SimplexVertex, 3> v;
  int count = 0;
  /// The point of the simplex nearest the origin (weights set on the kept vertices).
  Vec2 closest() const {
    Vec2 p(Real(0));
    for (int i = 0; i < count; ++i) p += v[i].weight * v[i].w;
    return p;
  }
};

/// Keeps vertex i only.
void keep_one(Simplex& s, int i) {
  s.v[0] = s.v[i];
  s.v[0].weight = Real(1);
  s.count = 1;
}

/// Keeps vertices i, j with weights (1 - t, t).
void keep_two(Simplex& s, int i, int j, Real t) {
  const SimplexVertex vi = s.v[i];
  const SimplexVertex vj = s.v[j];
  s.v[0] = vi;
  s.v[1] = vj;
  s.v[0].weight = Real(1) - t;
  s.v[1].weight = t;
  s.count = 2;
}

void solve_segment(Simplex& s) {
  const Vec2 e = s.v[1].w - s.v[0].w;
  const Real ee = glm::dot(e, e);
  const Real t = ee > Real(0) ? -glm::dot(s.v[0].w, e) / ee : Real(0);
  if (t <= Real(0)) return keep_one(s, 0);
  if (t >= Real(1)) return keep_one(s, 1);
  keep_two(s, 0, 1, t);
}

/// Returns true when the origin is inside the triangle (the cores overlap).
bool solve_triangle(Simplex& s) {
  const Vec2 a = s.v[0].w, b = s.v[1].w, c = s.v[2].w;
  const Vec2 ab = b - a, ac = c - a;
  const Real d1 = -glm::dot(ab, a), d2 = -glm::dot(ac, a);
  if (d1 <= Real(0) && d2 <= Real(0)) return keep_one(s, 0), false;
  const Real d3 = -glm::dot(ab, b), d4 = -glm::dot(ac, b);
  if (d3 >= Real(0) && d4 <= d3) return keep_one(s, 1), false;
  const Real vc = d1 * d4 - d3 * d2;
  if (vc <= Real(0) && d1 >= Real(0) && d3 <= Real(0))
    return keep_two(s, 0, 1, d1 > d3 ? d1 / (d1 - d3) : Real(0)), false;
  const Real d5 = -glm::dot(ab, c), d6 = -glm::dot(ac, c);
  if (d6 >= Real(0) && d5 <= d6) return keep_one(s, 2), false;
  const Real vb = d5 * d2 - d1 * d6;
  if (vb <= Real(0) && d2 >= Real(0) && d6 <= Real(0))
    return keep_two(s, 0, 2, d2 > d6 ? d2 / (d2 - d6) : Real(0)), false;
  const Real va = d3 * d6 - d5 * d4;
  if (va <= Real(0) && (d4 - d3) >= Real(0) && (d5 - d6) >= Real(0)) {
    const Real sum = (d4 - d3) + (d5 - d6);
    return keep_two(s, 1, 2, sum > Real(0) ? (d4 - d3) / sum : Real(0)), false;
  }
  return true;
}

SimplexVertex support_vertex(const CorePair& pair, const Vec2& direction) {
  SimplexVertex v;
  v.ia = pair.a->support_index(-direction);
  v.ib = pair.b.support_index(direction);
  v.a = pair.a->vertices[v.ia];
  v.b = pair.b.vertices[v.ib];
  v.w = v.b - v.a;
  return v;
}

struct GjkOutcome {
  bool overlap = false;
  Vec2 a{Real(0)};  ///< witness on A's core (A frame)
  Vec2 b{Real(0)};  ///< witness on B's core (A frame)
  int iterations = 0;
};

GjkOutcome run_gjk(const CorePair& pair) {
  constexpr int kMaxIterations = 64;
  Simplex s;
  s.v[0] = support_vertex(pair, pair.b.vertices[0] - pair.a->vertices[0]);
  s.count = 1;
  const Real tiny = detail::pair_tolerance(pair.scale) * Real(1e-3);
  GjkOutcome out;
  Simplex best = s;
  Real best_distance2 = std::numeric_limits<Real>::infinity();
  for (out.iterations = 1; out.iterations <= kMaxIterations; ++out.iterations) {
    if (s.count == 2) solve_segment(s);
    if (s.count == 3 && solve_triangle(s)) {
      out.overlap = true;
      return out;
    }
    const Vec2 p = s.closest();
    if (length_squared(p) <= tiny * tiny) {
      out.overlap = true;
      return out;
    }
    // In exact arithmetic |p| shrinks at every step; when rounding stops that (a boundary
    // through the origin), the previous simplex is the answer.
    if (out.iterations > 1 && length_squared(p) >= best_distance2) {
      s = best;
      break;
    }
    best = s;
    best_distance2 = length_squared(p);
    const SimplexVertex next = support_vertex(pair, -p);
    bool repeated = false;
    for (int i = 0; i < s.count; ++i) repeated = repeated || (s.v[i].ia == next.ia && s.v[i].ib == next.ib);
    // Progress test: the support line through `next` bounds the distance from below by
    // dot(next.w, p) / |p|; stop when that bound is within rounding of |p| (an absolute
    // 16 epsilon of the pair's scale, so that touching pairs stop too).
    const Real gain = glm::dot(p, p) - glm::dot(next.w, p);
    const Real resolution = Real(16) * kEpsilon * pair.scale * std::sqrt(glm::dot(p, p));
    if (repeated || gain <= resolution + kRelativeTolerance * glm::dot(p, p) || out.iterations == kMaxIterations) break;
    s.v[s.count++] = next;
  }
  for (int i = 0; i < s.count; ++i) {
    out.a += s.v[i].weight * s.v[i].a;
    out.b += s.v[i].weight * s.v[i].b;
  }
  return out;
}

/// Exact penetration of overlapping cores by the separating-axis test (A frame): the axis of
/// largest separation among both cores' edge normals, with the deepest vertex as witness.
DistanceResult sat_penetration(const CorePair& pair) {
  const ConvexCore& a = *pair.a;
  const ConvexCore& b = pair.b;
  DistanceResult r;
  r.method = PairMethod::Sat;
  if (a.count < 2 && b.count < 2) {  // two coincident points
    r.signed_distance = glm::length(b.vertices[0] - a.vertices[0]);
    r.normal = {Real(1), Real(0)};
    r.point_a = a.vertices[0];
    r.point_b = b.vertices[0];
    return r;
  }
  const detail::AxisSeparation on_a = a.count >= 2 ? detail::max_edge_separation(a, b) : detail::AxisSeparation{};
  const detail::AxisSeparation on_b = b.count >= 2 ? detail::max_edge_separation(b, a) : detail::AxisSeparation{};
  if (on_a.separation >= on_b.separation) {
    const Vec2 n = a.normals[on_a.edge];
    const Vec2 deepest = b.vertices[b.support_index(-n)];
    r.signed_distance = on_a.separation;
    r.normal = n;
    r.point_b = deepest;
    r.point_a = deepest - on_a.separation * n;
  } else {
    const Vec2 m = b.normals[on_b.edge];
    const Vec2 deepest = a.vertices[a.support_index(-m)];
    r.signed_distance = on_b.separation;
    r.normal = -m;
    r.point_a = deepest;
    r.point_b = deepest + on_b.separation * r.normal;
  }
  return r;
}

}  // namespace

DistanceResult core_distance(const ConvexCore& a, const Pose& pose_a, const ConvexCore& b, const Pose& pose_b) {
  DistanceResult r;
  if (!is_finite(pose_a.position) || !is_finite(pose_b.position) ||
      !std::isfinite(pose_a.rotation.c + pose_a.rotation.s) || !std::isfinite(pose_b.rotation.c + pose_b.rotation.s)) {
    r.signed_distance = std::numeric_limits<Real>::infinity();
    r.status = PairStatus::InvalidInput;
    return r;
  }
  CorePair pair = detail::make_core_pair(a, pose_a, b, pose_b, false);
  const auto penetration = [&] {
    detail::move_normals(pair, b);
    return sat_penetration(pair);
  };
  const GjkOutcome gjk = run_gjk(pair);
  if (gjk.overlap) {
    r = penetration();
  } else {
    Vec2 n;
    Real d;
    if (!unit_and_length(gjk.b - gjk.a, n, d)) {
      r = penetration();
    } else {
      r.signed_distance = d;
      r.normal = n;
      r.point_a = gjk.a;
      r.point_b = gjk.b;
      r.method = PairMethod::Gjk;
    }
  }
  r.iterations = gjk.iterations;
  // Radii: each witness moves out of its core along the normal.
  r.point_a += a.radius * r.normal;
  r.point_b -= b.radius * r.normal;
  r.signed_distance -= a.radius + b.radius;
  r.status = status_from_distance(r.signed_distance, detail::pair_tolerance(pair.scale));
  r.point_a = pose_a.apply(r.point_a);
  r.point_b = pose_a.apply(r.point_b);
  r.normal = pose_a.apply_vector(r.normal);
  return r;
}

bool core_intersect(const ConvexCore& a, const Pose& pose_a, const ConvexCore& b, const Pose& pose_b) {
  const DistanceResult r = core_distance(a, pose_a, b, pose_b);
  return r.status != PairStatus::InvalidInput && r.status != PairStatus::Separated;
}

}  // namespace proxima::d2
