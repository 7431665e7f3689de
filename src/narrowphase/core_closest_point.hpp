#pragma once
/// @file core_closest_point.hpp
/// Exact distance from a point, segment or triangle core to a convex shape X through X's
/// closest-point query: the stage of the generic ladder (generic_distance.hpp) that answers
/// where GJK's answer is not certified (its duality gap is open, or the cores touch).
///
/// Why: GJK converges slowly where D = A - B is flat in one direction and curved in the
/// other (a segment along a cylinder's rim, a triangle's face over an ellipsoid): the
/// supports along nearby directions jump along the flat side, the simplex turns into a
/// sliver and the iteration stops on rounding with its gap open (seen 5e-8 of the size in
/// double); touching cores go to EPA on inflated cores, whose depth is exact to ~1e-12 only.
/// The signed distance sd(p) from a point p to X (X's closest_point: closed forms, Eberly's
/// root finder for the ellipsoid) is a convex function of p whose gradient is X's outward
/// normal n(p) at the closest point, so with S the core:
///   1. point core: sd(p): the distance, or the depth of p inside X; exact either way;
///   2. segment core p(s) = v0 + s e, e = v1 - v0: min over s in [0, 1] of sd(p(s)): an end
///      when the slope g(s) = e . n(p(s)) does not change sign on [0, 1], else the root of g
///      by regula falsi with the Illinois modification (Dowell, Jarratt, BIT 12, 1972) on the
///      bracket, to the rounding of s; the least sd evaluated is the answer (sd is stationary
///      at the minimum, so an error d in s costs only O(d^2) in the distance);
///   3. triangle core: the least of its three edges (step 2) and of its face: X's support m
///      along +-n (n the triangle's unit normal) when it lies on that side of the plane and
///      projects inside the triangle (the only place where sd's gradient can be +-n inside
///      the triangle, so the only interior minimum);
///   4. box core: the same over its faces (one-sided: X's support against the outward
///      normal) and its twelve edges, keeping the faces whose corners all lie within a
///      window below the box's support plane along a direction towards X (the caller's:
///      GJK's normal) and the edges with a corner there (a corner is searched through its
///      edges), so that a box near X costs a few features, not eighteen.
/// Steps 2 to 4 give the distance where S and X are apart (min sd > 0): a segment through X
/// is deeper than its deepest point, and where they touch X's normal at the contact (a rim,
/// or X without interior) need not be orthogonal to the core, so the caller sends those
/// pairs on to EPA.
/// Normals come from X's closest-point geometry, never from differences of nearby points.
/// Header-only, no allocation; O(1) closest-point queries for a point, O(log(1/eps)) for a
/// segment (typically under 20), three segments and two supports for a triangle, at most
/// twelve segments and six supports for a box.

#include <proxima/core/math.hpp>
#include <proxima/core/tolerance.hpp>
#include <proxima/shapes/box.hpp>
#include <proxima/shapes/capsule.hpp>
#include <proxima/shapes/point.hpp>
#include <proxima/shapes/segment.hpp>
#include <proxima/shapes/sphere.hpp>
#include <proxima/shapes/surface_point.hpp>
#include <proxima/shapes/triangle.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace proxima::narrow {

/// The vertices of a shape's core when it is a point, a segment, a triangle or a box (count 0
/// for every other shape), in the shape's frame.
template <class S>
struct SimpleCore {
  static constexpr int kCount = 0;  ///< not a point, segment, triangle or box core
};
template <>
struct SimpleCore<Point> {
  static constexpr int kCount = 1;  ///< the point itself
  static std::array<Vec3, 1> vertices(const Point& /*s*/) { return {Vec3(Real(0))}; }
};
template <>
struct SimpleCore<Sphere> {
  static constexpr int kCount = 1;  ///< the centre
  static std::array<Vec3, 1> vertices(const Sphere& /*s*/) { return {Vec3(Real(0))}; }
};
template <>
struct SimpleCore<Segment> {
  static constexpr int kCount = 2;  ///< the segment itself
  static std::array<Vec3, 2> vertices(const Segment& s) { return {s.a(), s.b()}; }
};
template <>
struct SimpleCore<Capsule> {
  static constexpr int kCount = 2;  ///< the axis segment
  static std::array<Vec3, 2> vertices(const Capsule& s) { return {s.bottom(), s.top()}; }
};
template <>
struct SimpleCore<Triangle> {
  static constexpr int kCount = 3;  ///< the triangle itself
  static std::array<Vec3, 3> vertices(const Triangle& s) { return {s.a(), s.b(), s.c()}; }
};
template <>
struct SimpleCore<Box> {
  static constexpr int kCount = 8;  ///< the corners; corner i has x, y, z at +h where bit 0, 1, 2 is set
  static std::array<Vec3, 8> vertices(const Box& s) {
    std::array<Vec3, 8> v{};
    const Vec3& h = s.half_extents();
    for (std::size_t i = 0; i < 8; ++i)
      v[i] = Vec3((i & 1u) ? h.x : -h.x, (i & 2u) ? h.y : -h.y, (i & 4u) ? h.z : -h.z);
    return v;
  }
};

/// A point of the core and X's closest point to it, in the common frame.
struct CoreClosest {
  Real signed_distance = std::numeric_limits<Real>::infinity();  ///< sd(core_point), length
  Vec3 core_point{Real(0)};                                      ///< on the core
  Vec3 surface_point{Real(0)};                                   ///< X's closest point to core_point
  Vec3 normal{Real(0), Real(0), Real(1)};                        ///< X's unit outward normal there
};

/// X's closest-point query and support in a common frame, X placed by rotation (X's frame to
/// the common frame) and translation (X's origin in the common frame).
template <class X>
struct PlacedShape {
  const X& shape;    ///< X in its own frame
  Mat3 rotation;     ///< X's frame -> common frame
  Mat3 rotation_t;   ///< common frame -> X's frame
  Vec3 translation;  ///< X's origin in the common frame

  /// X's closest point to p (common frame).
  CoreClosest closest(const Vec3& p) const {
    const SurfacePoint q = shape.closest_point(rotation_t * (p - translation));
    return {q.signed_distance, p, rotation * q.point + translation, rotation * q.normal};
  }
  /// X's farthest point in direction d (common frame).
  Vec3 support(const Vec3& d) const { return rotation * shape.support(rotation_t * d) + translation; }
};

namespace core_closest_detail {

/// X's normal at the least sd found inside segment v0 + s e, at s (apart from X): there sd
/// is smooth and stationary, so the normal is orthogonal to e. The sampled normal, the
/// direction of p - q, is orthogonal only to the rounding of s, which turns it by about
/// |e| ds / sd (a segment 60 long 0.17 from a box's edge: 5e-12 of overlap along it). It is
/// moved along the direction in which p - q turns with s, w (from one more sample 1/1024 along
/// the segment, its part across the normal), onto the plane orthogonal to e: the correction
/// keeps what X's geometry fixes (across a box's edge, its part along the edge stays zero),
/// where projecting e out would tilt it. The sampled normal when w is within a thousand
/// roundings of the points or nearly across e (no such move).
template <class X>
Vec3 stationary_normal(const PlacedShape<X>& x, const Vec3& v0, const Vec3& e, Real s, const CoreClosest& at) {
  const Vec3& n = at.normal;
  const Real step = s <= Real(0.5) ? Real(1) / Real(1024) : Real(-1) / Real(1024);
  const CoreClosest c = x.closest(v0 + (s + step) * e);
  const Vec3 w = (c.core_point - c.surface_point) - (at.core_point - at.surface_point);
  const Vec3 w_across = w - glm::dot(w, n) * n;
  const Real slope = glm::dot(w_across, e);
  const Real rounding = Real(1024) * kEpsilon * (glm::length(at.core_point) + glm::length(c.core_point));
  const Real across = glm::length(w_across);
  if (!(across > rounding && std::abs(slope) > Real(1e-3) * across * glm::length(e))) return n;
  const Vec3 moved = n - (glm::dot(n, e) / slope) * w_across;
  const Real len = glm::length(moved);
  return len > Real(0.5) && std::isfinite(len) ? moved / len : n;
}

/// Step 2: the point of segment v0 v1 with the least sd.
template <class X>
CoreClosest segment_minimum(const PlacedShape<X>& x, const Vec3& v0, const Vec3& v1) {
  const Vec3 e = v1 - v0;
  const CoreClosest start = x.closest(v0);
  Real g_lo = glm::dot(e, start.normal);
  if (!(g_lo < Real(0))) return start;  // sd does not fall along the segment (or no length)
  const CoreClosest end = x.closest(v1);
  Real g_hi = glm::dot(e, end.normal);
  if (!(g_hi > Real(0))) return end;  // sd falls all the way
  CoreClosest best = end.signed_distance < start.signed_distance ? end : start;
  bool interior = false;  // best is a point inside the segment, at best_s
  Real best_s = Real(0);
  Real lo = Real(0);
  Real hi = Real(1);
  int side = 0;  // which end moved last: -1 lo, +1 hi (Illinois: halve the stale end's slope)
  for (int step = 0; step < 96; ++step) {
    Real s = (lo * g_hi - hi * g_lo) / (g_hi - g_lo);
    if (!(s > lo && s < hi)) s = Real(0.5) * (lo + hi);
    if (!(s > lo && s < hi)) break;  // the bracket is at the rounding of s
    const CoreClosest c = x.closest(v0 + s * e);
    if (c.signed_distance < best.signed_distance) {
      best = c;
      best_s = s;
      interior = true;
    }
    const Real g = glm::dot(e, c.normal);
    if (g < Real(0)) {
      lo = s;
      g_lo = g;
      if (side == -1) g_hi *= Real(0.5);
      side = -1;
    } else if (g > Real(0)) {
      hi = s;
      g_hi = g;
      if (side == 1) g_lo *= Real(0.5);
      side = 1;
    } else {
      break;  // a stationary point: the minimum
    }
  }
  if (interior && best.signed_distance > Real(0)) best.normal = stationary_normal(x, v0, e, best_s, best);
  return best;
}

/// Steps 3 and 4, a face: the convex polygon p (in order) with unit normal n. For m = n (and
/// m = -n too when `two_sided`; a box face passes its outward normal negated), X's support q
/// along m, when the face's plane lies beyond q along m (X is on one side of it) and q
/// projects inside the polygon: there sd's gradient is m (a plane through X by rounding
/// only, within 64 eps of the coordinates, counts as touching). Infinite signed distance
/// when no m gives such a point.
template <class X, std::size_t K>
CoreClosest face_minimum(const PlacedShape<X>& x, const std::array<Vec3, K>& p, const Vec3& n, bool two_sided) {
  CoreClosest best;
  const Real orient = glm::dot(glm::cross(p[1] - p[0], p[2] - p[0]), n) >= Real(0) ? Real(1) : Real(-1);
  for (const Real sign : {Real(1), Real(-1)}) {
    if (sign < Real(0) && !two_sided) break;
    const Vec3 m = sign * n;  // from X towards the face's plane
    const Vec3 q = x.support(m);
    const Real gap = glm::dot(m, p[0] - q);
    // The plane cuts X, or X lies on the other side; a touching face may round either way.
    const Real slack = Real(64) * kEpsilon * (glm::length(q) + glm::length(p[0]));
    if (!(gap >= -slack)) continue;
    const Vec3 proj = q + gap * m;
    bool inside = true;
    for (std::size_t i = 0; i < K; ++i)
      inside = inside && orient * glm::dot(glm::cross(p[(i + 1) % K] - p[i], proj - p[i]), n) >= Real(0);
    if (inside && gap < best.signed_distance) best = {gap, proj, q, m};
  }
  return best;
}

/// Step 4: the box core with corners v (SimpleCore<Box> order, common frame): its faces with
/// every corner, and its edges with a corner, within `window` of the box's support plane
/// along `toward`.
template <class X>
CoreClosest box_minimum(const PlacedShape<X>& x, const std::array<Vec3, 8>& v, const Vec3& toward, Real window) {
  std::array<bool, 8> near{};
  Real top = -std::numeric_limits<Real>::infinity();
  for (const Vec3& p : v) top = std::max(top, glm::dot(toward, p));
  for (std::size_t i = 0; i < 8; ++i) near[i] = !(glm::dot(toward, v[i]) < top - window);  // NaN keeps it
  CoreClosest best;
  for (std::size_t k = 0; k < 3; ++k) {
    const std::size_t bk = std::size_t(1) << k;
    const std::size_t bi = std::size_t(1) << ((k + 1) % 3);
    const std::size_t bj = std::size_t(1) << ((k + 2) % 3);
    const Vec3 axis = v[bk] - v[0];
    const Real len = glm::length(axis);
    if (!(len > Real(0))) continue;
    for (const std::size_t side : {std::size_t(0), bk}) {
      const Vec3 out = (side != 0 ? Real(1) : Real(-1)) / len * axis;
      const std::array<Vec3, 4> face{v[side], v[side | bi], v[side | bi | bj], v[side | bj]};
      if (!(near[side] && near[side | bi] && near[side | bi | bj] && near[side | bj])) continue;
      const CoreClosest c = face_minimum(x, face, -out, false);
      if (c.signed_distance < best.signed_distance) best = c;
    }
    for (std::size_t a = 0; a < 8; ++a) {
      if ((a & bk) != 0 || !(near[a] || near[a | bk])) continue;  // a near corner's edges hold it
      const CoreClosest c = segment_minimum(x, v[a], v[a | bk]);
      if (c.signed_distance < best.signed_distance) best = c;
    }
  }
  return best;
}

}  // namespace core_closest_detail

/// The point of the core with vertices `v` (common frame) nearest to X, with X's closest point
/// to it (steps 1-4; a box searches only its features within `window` of its support plane
/// along `toward`). Exact where the core is a point, or lies apart from X or touches it; a
/// segment, triangle or box through X gets a negative distance that is not its depth.
template <class X, std::size_t N>
CoreClosest core_closest_point(const PlacedShape<X>& x, const std::array<Vec3, N>& v,
                               const Vec3& toward = Vec3(Real(0)),
                               Real window = std::numeric_limits<Real>::infinity()) {
  namespace cd = core_closest_detail;
  if constexpr (N == 1) {
    return x.closest(v[0]);
  } else if constexpr (N == 2) {
    return cd::segment_minimum(x, v[0], v[1]);
  } else if constexpr (N == 8) {
    return cd::box_minimum(x, v, toward, window);
  } else {
    const Vec3 n = glm::cross(v[1] - v[0], v[2] - v[0]);
    const Real len = glm::length(n);
    CoreClosest best;
    if (len > Real(0) && std::isfinite(len)) best = cd::face_minimum(x, v, n / len, true);
    for (int i = 0; i < 3; ++i) {
      const CoreClosest c =
          cd::segment_minimum(x, v[static_cast<std::size_t>(i)], v[static_cast<std::size_t>((i + 1) % 3)]);
      if (c.signed_distance < best.signed_distance) best = c;
    }
    return best;
  }
}

}  // namespace proxima::narrow
