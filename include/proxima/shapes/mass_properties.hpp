#pragma once
/// @file mass_properties.hpp
/// MassProperties: volume, mass, centre of mass and inertia tensor of a solid of uniform
/// density, in the shape's local frame — what engines derive rigid-body data from.

#include <proxima/core/math.hpp>

#include <cmath>

namespace proxima {

/// Mass properties of a uniform-density solid, in the shape's local frame.
struct MassProperties {
  Real volume = Real(0);   ///< volume (length^3); 0 for points, segments, triangles
  Real mass = Real(0);     ///< density * volume
  Vec3 centroid{Real(0)};  ///< centre of mass, local frame
  Mat3 inertia{Real(0)};   ///< inertia tensor about the centroid, local axes (mass * length^2)
};

/// True when every component is finite. Mass properties stay finite while the density times
/// the shape's size^5 (the inertia) fits Real: for every convex shape and mesh within
/// kMaxCoordinate up to a density of about 100 in float and 1e50 in double. Past it the
/// overflowing components are infinite, never NaN (docs/conventions.md, "Limits").
inline bool is_finite(const MassProperties& m) {
  bool finite = std::isfinite(m.volume) && std::isfinite(m.mass) && std::isfinite(m.centroid.x) &&
                std::isfinite(m.centroid.y) && std::isfinite(m.centroid.z);
  for (int c = 0; c < 3; ++c) {
    for (int r = 0; r < 3; ++r) finite = finite && std::isfinite(m.inertia[c][r]);
  }
  return finite;
}

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
