#pragma once
/// @file fit_hull.hpp
/// Fitting the convex hull (the tightest convex bounding volume) to a point set.

#include <proxima/core/math.hpp>
#include <proxima/core/result.hpp>
#include <proxima/shapes/convex_hull.hpp>

#include <span>

namespace proxima {

/// The convex hull of `points`, in their frame (ConvexHull::create: qhull). Errors as
/// ConvexHull::create: TooFew (< 4 points), NotFinite, Degenerate (flat sets), Internal.
inline Result<ConvexHull> fit_hull(std::span<const Vec3> points) { return ConvexHull::create(points); }

}  // namespace proxima
