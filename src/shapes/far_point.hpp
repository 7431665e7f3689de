#pragma once
// The answer of closest_point to a non-finite query point, shared by the solid shapes: the
// top point (0, 0, top) of the shape's local frame with normal +z, infinitely far. Internal,
// not installed.

#include <proxima/shapes/surface_point.hpp>

#include <limits>

namespace proxima::detail {

// SurfacePoint at (0, 0, top) (local frame, length units), normal +z, signed distance
// +infinity.
inline SurfacePoint far_top_point(Real top) {
  SurfacePoint far;
  far.point = Vec3(Real(0), Real(0), top);
  far.signed_distance = std::numeric_limits<Real>::infinity();
  return far;
}

}  // namespace proxima::detail
