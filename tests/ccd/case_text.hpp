#pragma once
// Test support: numbers, vectors and placements written with every digit that gives the same
// Real back (9 in float, 17 in double), so a failing case printed by a sweep reproduces.
#include <proxima/core/math.hpp>
#include <proxima/core/transform.hpp>

#include <cstdio>
#include <limits>
#include <string>

namespace proxima::test {

/// `x` with max_digits10 significant digits.
inline std::string num(Real x) {
  char buffer[40];
  std::snprintf(buffer, sizeof(buffer), "%.*g", std::numeric_limits<Real>::max_digits10, double(x));
  return buffer;
}

/// "(x, y, z)" with num's digits.
inline std::string text(const Vec3& v) { return "(" + num(v.x) + ", " + num(v.y) + ", " + num(v.z) + ")"; }

}  // namespace proxima::test
