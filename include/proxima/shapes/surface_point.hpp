#pragma once
/// @file surface_point.hpp
/// SurfacePoint: the answer of a closest-point query on a shape.

#include <proxima/core/math.hpp>

namespace proxima {

/// The point of a shape's surface nearest to a query point q, in the shape's frame.
///
/// `signed_distance` is |q - point|, negated when q is strictly inside a solid. `normal`
/// is the unit outward surface normal at `point` (for q outside: (q - point) / distance;
/// for q inside: the outward normal of the nearest surface feature). For shapes without
/// interior (point, segment, triangle) the distance is never negative and the normal
/// points from the shape towards q (any unit vector orthogonal to the feature when q lies
/// on the shape).
struct SurfacePoint {
  Vec3 point{Real(0)};                     ///< nearest surface point
  Vec3 normal{Real(0), Real(0), Real(1)};  ///< unit outward normal at `point`
  Real signed_distance = Real(0);          ///< > 0 outside, < 0 inside, 0 on the surface
};

}  // namespace proxima
