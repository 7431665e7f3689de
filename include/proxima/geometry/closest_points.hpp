#pragma once
/// @file closest_points.hpp
/// Distances and closest points between primitives (Ericson, Real-Time Collision
/// Detection, ch. 5), robust for parallel, degenerate (zero-length segment, collinear
/// triangle) and far-from-origin inputs: never NaN for finite input.
///
/// All functions work in whatever frame their arguments are given in and return points in
/// that same frame; distances are in the caller's length unit. Every function is O(1) and
/// allocates nothing. Inputs whose coordinates are so large (or so small) that products of
/// four coordinates would overflow (or underflow) are rescaled by an exact power of two
/// internally, so any finite input gives a finite answer (a squared distance whose true
/// value exceeds the largest Real is reported as infinity). Non-finite input (NaN or
/// infinite coordinates) gives NaN points, parameters and distances (triangles_intersect:
/// false), never a crash or a hang.

#include <proxima/core/math.hpp>
#include <proxima/geometry/aabb.hpp>

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <limits>

namespace proxima::geometry {

/// A point of a segment (or line) and its parameter: point = a + t (b - a).
struct SegmentPoint {
  Vec3 point{Real(0)};  ///< the closest point
  Real t = Real(0);     ///< its parameter along the segment, in [0, 1] for segments
};

/// The pair of closest points of two primitives.
struct ClosestPair {
  Vec3 on_a{Real(0)};               ///< closest point on the first primitive
  Vec3 on_b{Real(0)};               ///< closest point on the second primitive
  Real distance_squared = Real(0);  ///< |on_a - on_b|^2
};

/// Closest pair of two segments/lines with parameters (s on the first, t on the second):
/// on_a = p0 + s (p1 - p0) and on_b = q0 + t (q1 - q0) (for lines: p0 + s d0, p1 + t d1).
struct SegmentPair {
  Vec3 on_a{Real(0)};               ///< closest point on the first
  Vec3 on_b{Real(0)};               ///< closest point on the second
  Real s = Real(0);                 ///< parameter on the first
  Real t = Real(0);                 ///< parameter on the second
  Real distance_squared = Real(0);  ///< |on_a - on_b|^2
};

/// Which feature of a triangle holds a closest point.
enum class TriangleFeature { VertexA, VertexB, VertexC, EdgeAB, EdgeBC, EdgeCA, Face };

/// Closest point of a triangle, its barycentric coordinates (u, v, w) with
/// point = u a + v b + w c, and the feature it lies on.
struct TrianglePoint {
  Vec3 point{Real(0)};                              ///< the closest point
  Vec3 barycentric{Real(1), Real(0), Real(0)};      ///< (u, v, w), each in [0, 1], summing to 1
  TriangleFeature feature = TriangleFeature::Face;  ///< vertex, edge or interior
};

/// Squared distance between two points.
Real distance_squared_point_point(const Vec3& p, const Vec3& q);

/// Closest point to p on the infinite line through a with direction d (d may be zero:
/// then a). t is the parameter along d (point = a + t d).
SegmentPoint closest_point_line(const Vec3& p, const Vec3& a, const Vec3& d);

/// Closest point to p on segment ab (a == b allowed: then a with t = 0). t in [0, 1].
SegmentPoint closest_point_segment(const Vec3& p, const Vec3& a, const Vec3& b);

/// Closest points of the lines p0 + s d0 and p1 + t d1. Parallel (or zero-direction)
/// lines: s = 0 and t chosen for the nearest point (both 0 when both directions are zero).
SegmentPair closest_points_line_line(const Vec3& p0, const Vec3& d0, const Vec3& p1, const Vec3& d1);

/// Closest points of segments p0p1 and q0q1 (s, t in [0, 1]), robust for parallel and
/// zero-length ones (for parallel overlapping segments, the midpoint of the overlap on the
/// first). The witness points always lie on their segments; the distance is within a few
/// ulps of the coordinates of the exact one, also for nearly parallel segments.
SegmentPair closest_points_segment_segment(const Vec3& p0, const Vec3& p1, const Vec3& q0, const Vec3& q1);

/// Closest point to p on triangle abc (Voronoi-region method; collinear triangles fall
/// back to the nearest of its edges, and a triangle whose three vertices coincide is the
/// point a).
TrianglePoint closest_point_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c);

/// Closest point to p in the solid box (p itself when inside). For an empty box (min >
/// max on some axis) the answer is finite but meaningless.
Vec3 closest_point_aabb(const Vec3& p, const Aabb& box);

/// Closest point to p in the solid oriented box (centre, unit axes as columns, half
/// extents >= 0); p itself when inside.
Vec3 closest_point_obb(const Vec3& p, const Vec3& center, const Mat3& axes, const Vec3& half_extents);

/// Closest points of segment pq and triangle abc (0 distance with a common point when the
/// segment crosses or touches the triangle). on_a lies on the segment, on_b on the
/// triangle. Zero-length segments and degenerate triangles are allowed.
ClosestPair closest_points_segment_triangle(const Vec3& p, const Vec3& q, const Vec3& a, const Vec3& b, const Vec3& c);

/// True when triangles a0a1a2 and b0b1b2 share a point (touching counts); coplanar
/// triangles handled in 2-D. Degenerate triangles are treated as segments/points.
/// "Touching" is decided with the tolerance kRelativeTolerance * (largest |coordinate|),
/// so triangles closer than that may be reported as intersecting. False for non-finite
/// input.
bool triangles_intersect(const Vec3& a0, const Vec3& a1, const Vec3& a2, const Vec3& b0, const Vec3& b1,
                         const Vec3& b2);

/// Closest points of two triangles (distance 0 with a common point when they intersect).
/// on_a lies on the first triangle, on_b on the second. Degenerate triangles are allowed.
ClosestPair closest_points_triangle_triangle(const Vec3& a0, const Vec3& a1, const Vec3& a2, const Vec3& b0,
                                             const Vec3& b1, const Vec3& b2);

/// Building blocks shared by the distance functions; not part of the stable interface.
namespace detail {

/// Largest |component| of v (0 for the zero vector).
inline Real max_abs(const Vec3& v) { return std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)}); }

/// Largest |coordinate| of the points; infinity when any coordinate is NaN or infinite
/// (the public functions then return NaN answers).
inline Real magnitude(std::initializer_list<Vec3> points) {
  Real m = Real(0);
  bool finite = true;
  for (const Vec3& v : points) {
    finite = finite && is_finite(v);
    m = std::max(m, max_abs(v));
  }
  return finite ? m : std::numeric_limits<Real>::infinity();
}

/// Quiet NaN of Real, the answer to non-finite input.
inline constexpr Real kNaN = std::numeric_limits<Real>::quiet_NaN();

/// Above this magnitude a product of four coordinates could overflow: inputs are scaled down.
inline constexpr Real kRescaleAbove = Real(std::numeric_limits<Real>::max_exponent / 4 >= 64 ? 1e60 : 1e8);
/// Below this magnitude (and above 0) a product of four coordinates could underflow: inputs
/// are scaled up.
inline constexpr Real kRescaleBelow = Real(std::numeric_limits<Real>::max_exponent / 4 >= 64 ? 1e-60 : 1e-8);

/// The power of two e such that magnitude * 2^-e lies in [0.5, 1) when `magnitude` is
/// outside [kRescaleBelow, kRescaleAbove], else 0 (no rescaling needed; also for 0, and
/// for non-finite magnitudes).
inline int rescale_exponent(Real magnitude) {
  if (!std::isfinite(magnitude)) return 0;
  if (magnitude <= kRescaleAbove && (magnitude >= kRescaleBelow || magnitude == Real(0))) return 0;
  int e = 0;
  static_cast<void>(std::frexp(magnitude, &e));
  return e;
}

/// v * 2^e, exact unless a component underflows.
inline Vec3 scaled(const Vec3& v, int e) { return {std::ldexp(v.x, e), std::ldexp(v.y, e), std::ldexp(v.z, e)}; }

/// A triangle whose doubled area |(b - a) x (c - a)| is at most kThinTriangle times its
/// squared longest edge (height below kThinTriangle times that edge) has no reliable
/// plane: it is handled through its edges only.
inline constexpr Real kThinTriangle = Real(64) * std::numeric_limits<Real>::epsilon();

/// True when triangle abc is thin in the sense of kThinTriangle (collinear, coincident
/// vertices or a sliver), given n = (b - a) x (c - a).
inline bool is_thin_triangle(const Vec3& n, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Real l2 = std::max({length_squared(b - a), length_squared(c - b), length_squared(a - c)});
  return !(length_squared(n) > kThinTriangle * kThinTriangle * l2 * l2);
}

/// closest_point_segment without the rescaling (inputs in the safe range).
inline SegmentPoint closest_point_segment_unscaled(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 ab = b - a;
  const Real num = glm::dot(p - a, ab);
  if (num <= Real(0)) return {a, Real(0)};
  const Real den = glm::dot(ab, ab);
  if (num >= den) return {b, Real(1)};
  const Real t = num / den;
  return {a + t * ab, t};
}

/// closest_points_segment_segment without the rescaling (inputs in the safe range).
SegmentPair closest_points_segment_segment_unscaled(const Vec3& p0, const Vec3& p1, const Vec3& q0, const Vec3& q1);

/// closest_point_triangle without the rescaling (inputs in the safe range).
TrianglePoint closest_point_triangle_unscaled(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c);

/// closest_points_segment_triangle without the rescaling (inputs in the safe range).
ClosestPair closest_points_segment_triangle_unscaled(const Vec3& p, const Vec3& q, const Vec3& a, const Vec3& b,
                                                     const Vec3& c);

/// When segment pq crosses the plane of triangle abc (its end points on opposite sides, or
/// one of them on the plane) and the line pq passes inside the three edges, writes the
/// point where the segment crosses the plane to `point` and returns true. Thin triangles
/// and segments lying in the plane never cross (their contacts are found by edge and
/// vertex tests). For a segment nearly in the plane the crossing point is ill-conditioned:
/// callers confirm it (common_point_segment_triangle). No rescaling is done here.
bool segment_crosses_triangle(const Vec3& p, const Vec3& q, const Vec3& a, const Vec3& b, const Vec3& c, Vec3& point);

/// segment_crosses_triangle for a triangle known not to be thin, with its precomputed
/// normal n = (b - a) x (c - a).
bool segment_crosses_triangle(const Vec3& p, const Vec3& q, const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& n,
                              Vec3& point);

/// Outcome of looking for a common point of a segment and a triangle.
enum class Crossing {
  None,       ///< no crossing found (the closest pair is an end point or edge pair)
  Common,     ///< `pair` holds a common point (on_a == on_b, distance 0)
  Candidate,  ///< an unconfirmed crossing: `pair` is a valid pair of points, one candidate among others
};

/// Crossing test of segment pq with triangle abc (normal n, not thin) confirmed by the
/// crossing point's distance to the triangle: within `accept`, the point is returned as a
/// common point (distance 0); otherwise the point and its nearest triangle point are a
/// candidate pair. No rescaling is done here.
Crossing common_point_segment_triangle(const Vec3& p, const Vec3& q, const Vec3& a, const Vec3& b, const Vec3& c,
                                       const Vec3& n, Real accept, ClosestPair& pair);

/// Largest distance from the triangle at which a crossing point is accepted as common to
/// segment and triangle, at coordinate magnitude `scale`: a few rounding errors.
inline Real crossing_acceptance(Real scale) { return Real(16) * std::numeric_limits<Real>::epsilon() * scale; }

}  // namespace detail

}  // namespace proxima::geometry
