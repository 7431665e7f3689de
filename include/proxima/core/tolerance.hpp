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

/// Largest Real accepted as a coordinate or size at construction (1e18 for float, 1e150
/// for double): beyond it squared lengths overflow.
inline constexpr Real kMaxCoordinate = sizeof(Real) == 4 ? Real(1e18) : Real(1e150);

}  // namespace proxima
