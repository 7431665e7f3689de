#pragma once
/// @file shape_type.hpp
/// ShapeType: the dense enum that indexes the narrow phase's N x N dispatch table.

#include <cstdint>

namespace proxima {

/// Every shape kind, numbered densely from 0 (order is part of the dispatch table layout).
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
  Count  ///< number of shape types, not a shape
};

/// Number of shape types.
inline constexpr int kShapeTypeCount = static_cast<int>(ShapeType::Count);

/// Lower-case name as used by the query protocol ("sphere", "convex", "halfspace", ...).
const char* to_string(ShapeType type);

}  // namespace proxima
