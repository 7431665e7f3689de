#pragma once
/// @file tolerance.hpp
/// Tolerances, all derived from the precision of proxima::Real so that the float and the
/// double builds make the same decisions at their own resolution.

#include <proxima/core/math.hpp>

#include <algorithm>
#include <limits>

namespace proxima {

/// Machine epsilon of Real (1.19e-7 for float, 2.22e-16 for double).
inline constexpr Real kEpsilon = std::numeric_limits<Real>::epsilon();

/// Relative tolerance for geometric decisions (coplanarity, parallelism, "on the surface"):
/// about 1e-5 in float and 1e-12 in double. Multiply by the problem's length scale.
inline constexpr Real kRelativeTolerance = Real(100) * kEpsilon;

/// sqrt(epsilon): the accuracy left after one cancellation in a squared quantity
/// (3.5e-4 in float, 1.5e-8 in double). Used for iterative solvers' convergence.
inline const Real kSqrtEpsilon = std::sqrt(kEpsilon);

/// Absolute linear tolerance at length scale `scale` (>= 1 is assumed for tiny shapes so
/// that the tolerance never underflows): kRelativeTolerance * max(1, |scale|).
inline Real linear_tolerance(Real scale) { return kRelativeTolerance * std::max(Real(1), std::abs(scale)); }

/// Largest Real accepted as a coordinate or size (1e7 for float, 1e50 for double): the
/// stated range in which every answer is right (docs/conventions.md, "Limits"). The most
/// fragile products hold four lengths in the narrow phase (GJK's and EPA's squared signed
/// areas: with 1e18 accepted, float answers broke from about 1e9) and five in mass
/// properties (the inertia per unit density, 1e36 for the largest accepted float hull), so
/// both stay finite, with room for densities up to about 100 in float and 1e50 in double.
inline constexpr Real kMaxCoordinate = sizeof(Real) == 4 ? Real(1e7) : Real(1e50);

/// Largest position component the narrow phase accepts in a pose (4 kMaxCoordinate): room
/// for composed placements, a compound's child placed inside a placed compound reaching
/// (1 + sqrt 3) kMaxCoordinate. Poses beyond it answer status InvalidInput.
inline constexpr Real kMaxPlacedCoordinate = Real(4) * kMaxCoordinate;

}  // namespace proxima
