#pragma once
/// @file closest_points.hpp
/// Distances and closest points between primitives (Ericson, Real-Time Collision
/// Detection, ch. 5), robust for parallel, degenerate (zero-length segment, collinear
/// triangle) and far-from-origin inputs: never NaN for finite input.

#include <proxima/core/math.hpp>
#include <proxima/geometry/aabb.hpp>

namespace proxima::geometry {

/// A point of a segment (or line) and its parameter: point = a + t (b - a).
struct SegmentPoint {
  Vec3 point{Real(0)};  ///< the closest point
  Real t = Real(0);     ///< its parameter along the segment, in [0, 1] for segments
};

/// The pair of closest points of two primitives.
struct ClosestPair {
  Vec3 on_a{Real(0)};             ///< closest point on the first primitive
  Vec3 on_b{Real(0)};             ///< closest point on the second primitive
  Real distance_squared = Real(0);  ///< |on_a - on_b|^2
};

/// Closest pair of two segments/lines with parameters (s on the first, t on the second).
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
  Vec3 point{Real(0)};                        ///< the closest point
  Vec3 barycentric{Real(1), Real(0), Real(0)};  ///< (u, v, w), summing to 1
  TriangleFeature feature = TriangleFeature::Face;  ///< vertex, edge or interior
};

/// Squared distance between two points.
Real distance_squared_point_point(const Vec3& p, const Vec3& q);

/// Closest point to p on the infinite line through a with direction d (d may be zero:
/// then a). t is the parameter along d.
SegmentPoint closest_point_line(const Vec3& p, const Vec3& a, const Vec3& d);

/// Closest point to p on segment ab (a == b allowed).
SegmentPoint closest_point_segment(const Vec3& p, const Vec3& a, const Vec3& b);

/// Closest points of the lines p0 + s d0 and p1 + t d1. Parallel (or zero-direction)
/// lines: s = 0 and t chosen for the nearest point.
SegmentPair closest_points_line_line(const Vec3& p0, const Vec3& d0, const Vec3& p1, const Vec3& d1);

/// Closest points of segments p0p1 and q0q1, robust for parallel and zero-length ones
/// (for parallel overlapping segments, the midpoint of the overlap on the first).
SegmentPair closest_points_segment_segment(const Vec3& p0, const Vec3& p1, const Vec3& q0, const Vec3& q1);

/// Closest point to p on triangle abc (Voronoi-region method; collinear triangles fall
/// back to the nearest of its edges).
TrianglePoint closest_point_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c);

/// Closest point to p in the solid box (p itself when inside).
Vec3 closest_point_aabb(const Vec3& p, const Aabb& box);

/// Closest point to p in the solid oriented box (centre, unit axes as columns, half
/// extents); p itself when inside.
Vec3 closest_point_obb(const Vec3& p, const Vec3& center, const Mat3& axes, const Vec3& half_extents);

/// Closest points of segment pq and triangle abc (0 distance with a common point when the
/// segment crosses the triangle).
ClosestPair closest_points_segment_triangle(const Vec3& p, const Vec3& q, const Vec3& a, const Vec3& b,
                                            const Vec3& c);

/// True when triangles a0a1a2 and b0b1b2 share a point (touching counts); coplanar
/// triangles handled in 2-D. Degenerate triangles are treated as segments/points.
bool triangles_intersect(const Vec3& a0, const Vec3& a1, const Vec3& a2, const Vec3& b0, const Vec3& b1,
                         const Vec3& b2);

/// Closest points of two triangles (distance 0 with a common point when they intersect).
ClosestPair closest_points_triangle_triangle(const Vec3& a0, const Vec3& a1, const Vec3& a2, const Vec3& b0,
                                             const Vec3& b1, const Vec3& b2);

}  // namespace proxima::geometry
