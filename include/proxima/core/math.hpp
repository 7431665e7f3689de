#pragma once
/// @file math.hpp
/// The scalar type and the GLM vector, quaternion and matrix aliases every layer uses.
///
/// Lengths carry no unit: the library works in whatever unit the caller's data uses
/// (metres in most engines). Angles are in radians.

#include <proxima/core/config.hpp>

#include <glm/ext/quaternion_common.hpp>
#include <glm/ext/quaternion_float.hpp>
#include <glm/ext/quaternion_geometric.hpp>
#include <glm/ext/quaternion_transform.hpp>
#include <glm/ext/quaternion_trigonometric.hpp>
#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace proxima {

#if PROXIMA_DOUBLE
/// Scalar type of every coordinate, length and time in the library (double build).
using Real = double;
#else
/// Scalar type of every coordinate, length and time in the library (float build, the default).
using Real = float;
#endif

/// 2-D vector of Real.
using Vec2 = glm::vec<2, Real, glm::defaultp>;
/// 3-D vector of Real: points and directions.
using Vec3 = glm::vec<3, Real, glm::defaultp>;
/// 4-D vector of Real (plane equations n.x = d stored as (n, d)).
using Vec4 = glm::vec<4, Real, glm::defaultp>;
/// Quaternion of Real; GLM's constructor order is (w, x, y, z).
using Quat = glm::qua<Real, glm::defaultp>;
/// 3x3 matrix of Real, column-major as in GLM: m[c][r].
using Mat3 = glm::mat<3, 3, Real, glm::defaultp>;

/// Identity rotation.
inline constexpr Quat kIdentityQuat{Real(1), Real(0), Real(0), Real(0)};

/// Largest finite Real, used where a bound is unbounded (a half-space's box) so that
/// arithmetic on it never produces inf - inf = NaN.
inline constexpr Real kRealMax = std::numeric_limits<Real>::max();
/// Positive infinity of Real (an unbounded distance, time or interval end).
inline constexpr Real kRealInfinity = std::numeric_limits<Real>::infinity();

/// Pi in Real precision.
inline constexpr Real kPi = Real(3.14159265358979323846);

/// True when every component is finite (no NaN, no infinity).
inline bool is_finite(Real x) { return std::isfinite(x); }
/// True when every component is finite (no NaN, no infinity).
inline bool is_finite(const Vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }
/// True when every component is finite (no NaN, no infinity).
inline bool is_finite(const Quat& q) {
  return std::isfinite(q.w) && std::isfinite(q.x) && std::isfinite(q.y) && std::isfinite(q.z);
}

/// Squared Euclidean length.
inline Real length_squared(const Vec3& v) { return glm::dot(v, v); }

/// Largest absolute component, the scale of a vector for tolerances and safe normalisation.
inline Real max_abs_component(const Vec3& v) { return std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)}); }

/// Splits `v` into a unit vector and its length without overflow or underflow (v is
/// divided by its largest component before the square root). Returns false, leaving
/// `unit` and `length` untouched, when v is zero or not finite. Always inlined: every closed
/// form calls it once, and in a large translation unit GCC's growth limits had left it a
/// call (25 more instructions on a sphere pair's distance of about 350).
[[gnu::always_inline]] inline bool unit_and_length(const Vec3& v, Vec3& unit, Real& length) {
  if (!is_finite(v)) return false;
  const Real m = max_abs_component(v);
  if (!(m > Real(0))) return false;
  const Vec3 w = v / m;
  const Real l = glm::length(w);
  unit = w / l;
  length = m * l;
  return true;
}

/// The part of `v` across the direction `d` (any length): v less its component along d,
/// taken out twice (one pass leaves a rounding residue along d, of the size of v's rounding
/// over |v|). `v` itself when d is zero or not finite. The normal of a point's offset from
/// its closest point inside a segment: exact across the segment, along which the segment's
/// support has a kink, so that a tilt there would move the gap to first order.
inline Vec3 across_direction(const Vec3& v, const Vec3& d) {
  const Real dd = glm::dot(d, d);
  if (!(dd > Real(0)) || !std::isfinite(dd)) return v;
  const Vec3 once = v - (glm::dot(v, d) / dd) * d;
  return once - (glm::dot(once, d) / dd) * d;
}

/// Component-wise minimum / maximum of two vectors.
inline Vec3 min(const Vec3& a, const Vec3& b) { return glm::min(a, b); }
/// Component-wise maximum of two vectors.
inline Vec3 max(const Vec3& a, const Vec3& b) { return glm::max(a, b); }

/// A unit vector orthogonal to `n` (n need not be unit but must be non-zero); branch-free
/// choice after Duff et al., "Building an Orthonormal Basis, Revisited" (JCGT 2017).
inline void orthonormal_basis(const Vec3& n_unit, Vec3& t1, Vec3& t2) {
  const Real sign = std::copysign(Real(1), n_unit.z);
  const Real a = Real(-1) / (sign + n_unit.z);
  const Real b = n_unit.x * n_unit.y * a;
  t1 = Vec3(Real(1) + sign * n_unit.x * n_unit.x * a, sign * b, -sign * n_unit.x);
  t2 = Vec3(b, sign + n_unit.y * n_unit.y * a, -n_unit.y);
}

}  // namespace proxima
