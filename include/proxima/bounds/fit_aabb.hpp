#pragma once
/// @file fit_aabb.hpp
/// Fitting an axis-aligned box to a point set.

#include <proxima/core/math.hpp>
#include <proxima/core/result.hpp>
#include <proxima/geometry/aabb.hpp>

#include <span>

namespace proxima {

/// The tightest axis-aligned box of `points` (any frame; the box is in the same frame).
/// Errors: TooFew for an empty set ("points"), NotFinite / OutOfRange for a bad coordinate
/// ("points[i].x" ...). O(n).
Result<Aabb> fit_aabb(std::span<const Vec3> points);

}  // namespace proxima
