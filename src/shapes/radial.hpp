#pragma once
// Radial helpers shared by the shapes of revolution about local z (cylinder, cone): lengths
// and directions in the (x, y) plane computed from scaled components, so that denormal or
// huge coordinates neither underflow nor overflow. Internal, not installed.

#include <proxima/core/math.hpp>
#include <proxima/core/validate.hpp>

#include <algorithm>
#include <cmath>
#include <optional>

namespace proxima::detail {

// sqrt(a^2 + b^2) without overflow or underflow of the squares.
inline Real robust_hypot(Real a, Real b) {
  const Real m = std::max(std::abs(a), std::abs(b));
  if (!(m > Real(0))) return Real(0);
  const Real sa = a / m;
  const Real sb = b / m;
  return m * std::sqrt(sa * sa + sb * sb);
}

// The distance rho of (x, y) from the axis and the unit radial direction (ux, uy) towards
// it ((1, 0) on the axis).
inline Real radial_direction(Real x, Real y, Real& ux, Real& uy) {
  const Real m = std::max(std::abs(x), std::abs(y));
  if (!(m > Real(0))) {
    ux = Real(1);
    uy = Real(0);
    return Real(0);
  }
  const Real sx = x / m;
  const Real sy = y / m;
  const Real len = std::sqrt(sx * sx + sy * sy);
  ux = sx / len;
  uy = sy / len;
  return m * len;
}

// The error of a solid of revolution's validated construction (cylinder, cone): radius and
// half_length (length units) must be finite and > 0 (error fields "radius", "half_length").
inline std::optional<Error> check_radius_half_length(Real radius, Real half_length) {
  if (auto e = validate::positive(radius, "radius")) return e;
  return validate::positive(half_length, "half_length");
}

}  // namespace proxima::detail
