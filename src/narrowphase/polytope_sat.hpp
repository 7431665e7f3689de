#pragma once
/// @file polytope_sat.hpp
/// Certified penetration depth of two convex polytopes by the separating-axis test: the
/// signed separation along every face normal of both and every edge-edge cross axis; the
/// largest is the signed distance when they overlap (exact: the Minkowski difference of
/// two polytopes is a polytope whose faces all come from these axes). For two solid
/// polytopes (Box, ConvexHull) edge pairs that do not build a face of the Minkowski
/// difference are pruned by the Gauss-map arc test and the rest cost O(1) each (Gregorius,
/// "The Separating Axis Test between Convex Polyhedra", GDC 2013). Flat or lower-dimensional
/// polytopes (Triangle, Segment, Point) test every axis by full projection.
/// Used by the generic narrow phase when EPA cannot answer for a polytope pair.

#include <proxima/core/math.hpp>
#include <proxima/core/transform.hpp>
#include <proxima/shapes/box.hpp>
#include <proxima/shapes/convex_hull.hpp>
#include <proxima/shapes/point.hpp>
#include <proxima/shapes/segment.hpp>
#include <proxima/shapes/triangle.hpp>

#include <array>
#include <cstdint>
#include <span>
#include <type_traits>

namespace proxima::narrow {

/// True for the shapes the SAT handles (polytopes and their degenerate forms).
template <class S>
inline constexpr bool kIsPolytope =
    std::is_same_v<S, Point> || std::is_same_v<S, Segment> || std::is_same_v<S, Triangle> || std::is_same_v<S, Box> ||
    std::is_same_v<S, ConvexHull>;

/// A polytope's vertices, face planes and edges in its local frame, borrowed from a hull or
/// held inline for the small shapes. Not copyable (it may point into itself).
class PolytopeView {
 public:
  /// Views of each polytope shape.
  explicit PolytopeView(const Point& point);
  /// See Point.
  explicit PolytopeView(const Segment& segment);
  /// See Point.
  explicit PolytopeView(const Triangle& triangle);
  /// See Point.
  explicit PolytopeView(const Box& box);
  /// See Point.
  explicit PolytopeView(const ConvexHull& hull);
  PolytopeView(const PolytopeView&) = delete;
  PolytopeView& operator=(const PolytopeView&) = delete;

  std::span<const Vec3> vertices;    ///< local frame
  std::span<const HullFace> faces;   ///< outward planes (both sides for a triangle)
  std::span<const HullEdge> edges;   ///< each edge once with its two faces (solid only)
  bool solid = false;                ///< true for Box and ConvexHull (Gauss-map pruning valid)
  const ConvexHull* hull = nullptr;  ///< hill-climbing support when set

  /// Index of a vertex farthest along d (local frame); `hint` warm-starts hulls.
  std::uint32_t support_index(const Vec3& d, std::uint32_t& hint) const;

 private:
  std::array<Vec3, 8> own_vertices_{};
  std::array<HullFace, 6> own_faces_{};
  std::array<HullEdge, 12> own_edges_{};
};

/// Answer of polytope_sat, in A's local frame.
struct SatResult {
  bool valid = false;                      ///< false when no axis exists (point/segment pairs)
  Real signed_distance = Real(0);          ///< largest separation over the axes (< 0: depth)
  Vec3 normal{Real(0), Real(0), Real(1)};  ///< unit, A to B, A's frame
  Vec3 point_a{Real(0)};                   ///< on A's surface, A's frame
  Vec3 point_b{Real(0)};                   ///< point_a + signed_distance * normal
  std::uint32_t feature = 0;               ///< axis id: kind (2 bits) << 30 | index
};

/// SAT between polytope A (its local frame) and polytope B placed in A's frame by
/// (rotation, translation). O(F_A S_B + F_B S_A + pruned E_A E_B), S = support cost.
SatResult polytope_sat(const PolytopeView& a, const PolytopeView& b, const Mat3& rotation, const Vec3& translation);

}  // namespace proxima::narrow
