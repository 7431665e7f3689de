#pragma once
/// @file mass_properties.hpp
/// MassProperties: volume, mass, centre of mass and inertia tensor of a solid of uniform
/// density, in the shape's local frame — what engines derive rigid-body data from.

#include <proxima/core/math.hpp>

namespace proxima {

/// Mass properties of a uniform-density solid, in the shape's local frame.
struct MassProperties {
  Real volume = Real(0);   ///< volume (length^3); 0 for points, segments, triangles
  Real mass = Real(0);     ///< density * volume
  Vec3 centroid{Real(0)};  ///< centre of mass, local frame
  Mat3 inertia{Real(0)};   ///< inertia tensor about the centroid, local axes (mass * length^2)
};

/// Inertia tensor about a point displaced by `offset` from the centroid (parallel-axis
/// theorem): I + m (|d|^2 E - d d^T).
inline Mat3 shift_inertia(const Mat3& inertia_at_centroid, Real mass, const Vec3& offset) {
  Mat3 r = inertia_at_centroid;
  const Real d2 = glm::dot(offset, offset);
  for (int c = 0; c < 3; ++c) {
    for (int row = 0; row < 3; ++row) {
      r[c][row] += mass * ((c == row ? d2 : Real(0)) - offset[c] * offset[row]);
    }
  }
  return r;
}

}  // namespace proxima
