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

/// "(x, y, z)" with num's digits (one formatted write: GCC 12 at -O3 warns falsely, with
/// -Wrestrict, about a chain of string concatenations).
inline std::string text(const Vec3& v) {
  char buffer[128];
  const int digits = std::numeric_limits<Real>::max_digits10;
  std::snprintf(buffer, sizeof(buffer), "(%.*g, %.*g, %.*g)", digits, double(v.x), digits, double(v.y), digits,
                double(v.z));
  return buffer;
}

}  // namespace proxima::test
