/// @file core_distance.cpp
/// Signed distance of two rounded 2D cores, in closed form (no iteration).
///
/// The cores' Minkowski difference M = B - A is a convex polygon; its edge normals are the
/// cores' edge normals (the separation of A's edge i from B, min over B's vertices of
/// n_i . (b - a_i), is the origin's separation from M's edge of normal -n_i). For a point p
/// outside a convex polygon with nearest point c, an edge's separation is at most
/// n . (p - c), with equality exactly on the edges through c, and the edge normal nearest in
/// angle to p - c is one of theirs: the edge of largest separation holds the nearest point.
/// Steps (Ericson, Real-Time Collision Detection §5.1.2 and §5.1.9; the separating axes of
/// Catto's polygon collision in Box2D):
///   1. a 1-vertex core (point, circle) against a core with edges, in that core's frame: one
///      pass over its edges finds the largest separation; <= 0 on a polygon core: the point
///      is inside by that much; otherwise the nearest point is on that edge (clamped);
///   2. two 2-vertex cores (segments, whose M may have no area, so that step 3 does not
///      apply): apart unless each one's ends lie strictly on both sides of the other's line;
///      apart: the closest points of two segments; crossing: step 3's penetration;
///   3. otherwise (a core with area), in A's frame: the largest separation over both cores'
///      edge normals; <= 0: the cores overlap by that much (exact), the witness the other
///      core's deepest vertex (slid onto the reference edge's span along a parallel edge);
///      > 0: the closest points lie on that reference edge and on the other core's edges
///      beside its vertex deepest along the edge normal (segment–segment closest points);
///   4. closest points nearer than the pair's tolerance count as touching, measured by the
///      separating axis (their direction would be rounding noise); the radii move the
///      witnesses out along the normal; the answer goes to the world.

#include <proxima/d2/convex_queries.hpp>

#include "d2/core_pair.hpp"

namespace proxima::d2 {
namespace {

using detail::CorePair;
using detail::LocalDistance;

/// The answer "overlapping by `separation` along `normal`" with B's witness `on_b` (the
/// deepest point) and A's on A's surface.
LocalDistance overlap(Real separation, const Vec2& normal, const Vec2& on_b) {
  return {separation, normal, on_b - separation * normal, on_b, PairMethod::Sat};
}

/// Fills `r` with "apart" at closest points `on_a`, `on_b` and returns true, unless they are
/// within the tolerance `tol`: their direction would then be rounding noise, and the caller
/// measures the cores as touching by its separating axis instead.
bool apart(const Vec2& on_a, const Vec2& on_b, Real tol, LocalDistance& r) {
  Vec2 n;
  Real d;
  if (!unit_and_length(on_b - on_a, n, d) || d <= tol) return false;
  r = {d, n, on_a, on_b, PairMethod::Gjk};
  return true;
}

/// The nearest point to `q` of the core's edge `edge`.
Vec2 closest_on_edge(const ConvexCore& core, int edge, const Vec2& q) {
  const Vec2 p = core.vertices[edge], e = core.vertices[(edge + 1) % core.count] - p;
  return p + std::clamp(glm::dot(q - p, e) / glm::dot(e, e), Real(0), Real(1)) * e;
}

/// Step 1: point `q` against `core` (2+ vertices), both in the core's frame; A is the core.
/// `scale` is the pair's scale before the core's vertices (the radii and |q|). A separation
/// beyond `stop` is answered as it is (a lower bound of the distance).
LocalDistance core_to_point(const ConvexCore& core, const Vec2& q, Real scale, Real stop) {
  int edge = 0;
  Real separation = -std::numeric_limits<Real>::infinity();
  for (int i = 0; i < core.count; ++i) {
    const Real s = glm::dot(core.normals[i], q - core.vertices[i]);
    if (s > separation) separation = s, edge = i;
    scale = std::max(scale, max_abs_component(core.vertices[i]));
  }
  const Vec2 n = core.normals[edge];
  LocalDistance r{separation, n, q, q, PairMethod::Gjk};
  const bool inside = core.count >= 3 && separation <= Real(0);
  if (separation <= stop && (inside || !apart(closest_on_edge(core, edge, q), q, detail::pair_tolerance(scale), r))) {
    r = overlap(separation, n, q);
  }
  r.scale = scale;
  return r;
}

/// Two 1-vertex cores, A's frame (centres within the tolerance get A's x axis); `scale` as
/// above.
LocalDistance point_to_point(const Vec2& p, const Vec2& q, Real scale) {
  scale = std::max(scale, max_abs_component(p));
  LocalDistance r;
  if (!apart(p, q, detail::pair_tolerance(scale), r)) {
    r = {glm::length(q - p), Vec2(Real(1), Real(0)), p, q, PairMethod::Sat};
  }
  r.scale = scale;
  return r;
}

/// The point of `other` deepest below edge `edge` of `ref` (normal n): its vertex deepest
/// along -n, slid along the tangent onto the edge's span when it lies beyond it (then
/// `other` has an edge parallel to the reference edge, and the slid point is on it).
Vec2 deepest_point(const ConvexCore& ref, int edge, const ConvexCore& other) {
  const Vec2 w = other.vertices[other.support_index(-ref.normals[edge])];
  const Vec2 v = ref.vertices[edge], e = ref.vertices[(edge + 1) % ref.count] - v;
  const Real ee = glm::dot(e, e), t = glm::dot(w - v, e);
  return w + ((std::clamp(t, Real(0), ee) - t) / ee) * e;
}

/// Exact penetration of overlapping cores (A frame): the axis of largest separation among
/// both cores' edge normals, with the deepest point as witness.
LocalDistance sat_penetration(const CorePair& pair, const detail::AxisSeparation& on_a,
                              const detail::AxisSeparation& on_b) {
  const ConvexCore& a = *pair.a;
  const ConvexCore& b = pair.b;
  if (on_a.separation >= on_b.separation) {
    return overlap(on_a.separation, a.normals[on_a.edge], deepest_point(a, on_a.edge, b));
  }
  const Vec2 n = -b.normals[on_b.edge];
  return overlap(on_b.separation, n, deepest_point(b, on_b.edge, a) + on_b.separation * n);
}

/// Closest points of segment (p, q) of A and segment (u, v) of B (A frame).
struct SegmentPoints {
  Vec2 a{Real(0)}, b{Real(0)};
  Real distance2 = std::numeric_limits<Real>::infinity();
};

SegmentPoints closest_segment_points(const Vec2& p, const Vec2& q, const Vec2& u, const Vec2& v) {
  Real s, t;
  detail::closest_segment_parameters(p, q, u, v, s, t);
  SegmentPoints r{p + s * (q - p), u + t * (v - u)};
  r.distance2 = length_squared(r.b - r.a);
  return r;
}

/// The nearer of the closest points of A's edge (p, q) to B's two edges beside vertex j.
SegmentPoints edge_to_vertex_edges(const Vec2& p, const Vec2& q, const ConvexCore& b, int j) {
  const int before = (j + b.count - 1) % b.count, after = (j + 1) % b.count;
  const SegmentPoints first = closest_segment_points(p, q, b.vertices[before], b.vertices[j]);
  if (b.count == 2) return first;
  const SegmentPoints second = closest_segment_points(p, q, b.vertices[j], b.vertices[after]);
  return second.distance2 < first.distance2 ? second : first;
}

/// Step 3: both cores with edges, one with area (A frame).
LocalDistance sat_distance(const CorePair& pair) {
  const ConvexCore& a = *pair.a;
  const ConvexCore& b = pair.b;
  const detail::AxisSeparation on_a = detail::max_edge_separation(a, b);
  const detail::AxisSeparation on_b = detail::max_edge_separation(b, a);
  const Real tol = detail::pair_tolerance(pair.scale);
  LocalDistance r;
  if (std::max(on_a.separation, on_b.separation) <= Real(0)) return sat_penetration(pair, on_a, on_b);
  if (on_a.separation >= on_b.separation) {
    const int i = on_a.edge, j = b.support_index(-a.normals[i]);
    const SegmentPoints c = edge_to_vertex_edges(a.vertices[i], a.vertices[(i + 1) % a.count], b, j);
    if (apart(c.a, c.b, tol, r)) return r;
  } else {
    const int i = on_b.edge, j = a.support_index(-b.normals[i]);
    const SegmentPoints c = edge_to_vertex_edges(b.vertices[i], b.vertices[(i + 1) % b.count], a, j);
    if (apart(c.b, c.a, tol, r)) return r;
  }
  return sat_penetration(pair, on_a, on_b);
}

/// True when r's ends lie strictly (beyond the tolerance `tol`) on both sides of the line
/// through p and q.
bool straddles(const Vec2& p, const Vec2& q, const Vec2& r0, const Vec2& r1, Real tol) {
  const Vec2 d = q - p;
  const Real o0 = cross(d, r0 - p), o1 = cross(d, r1 - p);
  const Real noise = tol * tol * length_squared(d);
  return o0 * o1 < Real(0) && o0 * o0 > noise && o1 * o1 > noise;
}

/// Step 2: two 2-vertex cores (A frame).
LocalDistance segment_distance(const CorePair& pair) {
  const ConvexCore& a = *pair.a;
  const ConvexCore& b = pair.b;
  const Real tol = detail::pair_tolerance(pair.scale);
  const SegmentPoints c = closest_segment_points(a.vertices[0], a.vertices[1], b.vertices[0], b.vertices[1]);
  LocalDistance r;
  if (!(straddles(a.vertices[0], a.vertices[1], b.vertices[0], b.vertices[1], tol) &&
        straddles(b.vertices[0], b.vertices[1], a.vertices[0], a.vertices[1], tol)) &&
      apart(c.a, c.b, tol, r)) {
    return r;
  }
  return sat_penetration(pair, detail::max_edge_separation(a, b), detail::max_edge_separation(b, a));
}

}  // namespace

namespace detail {

LocalDistance local_core_distance(const ConvexCore& a, const Pose& pose_a, const ConvexCore& b, const Pose& pose_b,
                                  Real stop) {
  const Real radii = std::max(a.radius + b.radius, Real(1e-30));
  if (b.count == 1) {  // in A's frame
    const Vec2 q = relative(pose_a, pose_b).apply(b.vertices[0]);
    const Real scale = std::max(radii, max_abs_component(q));
    return a.count == 1 ? point_to_point(a.vertices[0], q, scale) : core_to_point(a, q, scale, stop);
  }
  if (a.count == 1) {  // in B's frame, then mirrored
    const Vec2 p = relative(pose_b, pose_a).apply(a.vertices[0]);
    const LocalDistance m = core_to_point(b, p, std::max(radii, max_abs_component(p)), stop);
    return {m.distance, -m.normal, m.point_b, m.point_a, m.method, true, m.scale};
  }
  const CorePair pair = make_core_pair(a, pose_a, b, pose_b);
  LocalDistance r = a.count == 2 && b.count == 2 ? segment_distance(pair) : sat_distance(pair);
  r.scale = pair.scale;
  return r;
}

}  // namespace detail

DistanceResult core_distance(const ConvexCore& a, const Pose& pose_a, const ConvexCore& b, const Pose& pose_b) {
  DistanceResult r;
  if (!detail::valid_poses(pose_a, pose_b)) {
    r.signed_distance = std::numeric_limits<Real>::infinity();
    r.status = PairStatus::InvalidInput;
    return r;
  }
  const LocalDistance local = detail::local_core_distance(a, pose_a, b, pose_b);
  const Pose& frame = local.in_b_frame ? pose_b : pose_a;
  // Radii: each witness moves out of its core along the normal.
  r.signed_distance = local.distance - (a.radius + b.radius);
  r.status = status_from_distance(r.signed_distance, detail::pair_tolerance(local.scale));
  r.method = local.method;
  r.normal = frame.apply_vector(local.normal);
  r.point_a = frame.apply(local.point_a + a.radius * local.normal);
  r.point_b = frame.apply(local.point_b - b.radius * local.normal);
  return r;
}

bool core_intersect(const ConvexCore& a, const Pose& pose_a, const ConvexCore& b, const Pose& pose_b) {
  const DistanceResult r = core_distance(a, pose_a, b, pose_b);
  return r.status != PairStatus::InvalidInput && r.status != PairStatus::Separated;
}

}  // namespace proxima::d2
