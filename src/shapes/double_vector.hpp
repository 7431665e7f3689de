#pragma once
/// @file double_vector.hpp
/// Internal: three doubles as a vector, for the shape builders' geometric predicates that
/// must not round to Real (a float build's hull and mesh validation decide flatness and
/// degeneracy in double).

#include <proxima/core/math.hpp>

#include <array>
#include <cmath>

namespace proxima::detail {

/// A vector of three doubles.
using D3 = std::array<double, 3>;

/// v widened to double.
inline D3 to_d3(const Vec3& v) { return {double(v.x), double(v.y), double(v.z)}; }
/// a − b.
inline D3 sub(const D3& a, const D3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
/// a · b.
inline double dot(const D3& a, const D3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
/// a × b.
inline D3 cross(const D3& a, const D3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
/// |a|.
inline double norm(const D3& a) { return std::sqrt(dot(a, a)); }

}  // namespace proxima::detail
