#pragma once
/// @file fit_kdop.hpp
/// Fitting a k-DOP to a point set.

#include <proxima/bounds/kdop.hpp>
#include <proxima/core/math.hpp>
#include <proxima/core/result.hpp>

#include <span>

namespace proxima {

/// The tightest Kdop<K> of `points` (min and max of d_i . p per slab; exact containment).
/// Errors: TooFew for an empty set ("points"), NotFinite / OutOfRange ("points[i].x" ...).
/// O(n K).
template <int K>
Result<Kdop<K>> fit_kdop(std::span<const Vec3> points);

extern template Result<Kdop<6>> fit_kdop<6>(std::span<const Vec3>);
extern template Result<Kdop<14>> fit_kdop<14>(std::span<const Vec3>);
extern template Result<Kdop<18>> fit_kdop<18>(std::span<const Vec3>);
extern template Result<Kdop<26>> fit_kdop<26>(std::span<const Vec3>);

}  // namespace proxima
