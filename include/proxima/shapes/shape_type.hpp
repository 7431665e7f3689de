#pragma once
/// @file shape_type.hpp
/// ShapeType: the dense enum of every shape kind. It indexes the owning Shape variant, the
/// ShapeRef view and the narrow phase's dispatch table; the convex kinds come first.

#include <cstdint>

namespace proxima {

/// Every shape kind, numbered densely from 0 (order is part of the dispatch table layout):
/// the eleven convex kinds (half-space included: an unbounded convex set), then the
/// composite ones, which the narrow phase answers through their hierarchies.
enum class ShapeType : std::uint8_t {
  Point,
  Segment,
  Triangle,
  Sphere,
  Capsule,
  Box,
  Cylinder,
  Cone,
  Ellipsoid,
  ConvexHull,
  HalfSpace,
  TriangleMesh,  ///< a surface of triangles with its BVH
  Compound,      ///< child shapes at local poses with a BVH over them
  Count          ///< number of shape types, not a shape
};

/// Number of shape types.
inline constexpr int kShapeTypeCount = static_cast<int>(ShapeType::Count);
/// Number of convex shape types: ShapeType values below this are convex (support mapping,
/// core + radius, closed-form or GJK/EPA pair routines).
inline constexpr int kConvexShapeTypeCount = static_cast<int>(ShapeType::HalfSpace) + 1;

/// True for the convex kinds (Point ... HalfSpace).
constexpr bool is_convex(ShapeType type) noexcept { return static_cast<int>(type) < kConvexShapeTypeCount; }

/// Lower-case name as used by the query protocol ("sphere", "convex", "halfspace", "mesh", "compound").
const char* to_string(ShapeType type);

}  // namespace proxima
