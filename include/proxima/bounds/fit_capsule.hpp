#pragma once
/// @file fit_capsule.hpp
/// Fitting a bounding capsule to a point set.

#include <proxima/bounds/bounding_capsule.hpp>
#include <proxima/core/math.hpp>
#include <proxima/core/result.hpp>

#include <span>

namespace proxima {

/// Capsule along a principal axis of the points (their covariance), refined by a local
/// search over the axis direction, and tightened:
/// 1. the radius starts as the largest distance of a point from the axis line;
/// 2. the segment ends are pulled in as far as every point stays within that radius of
///    the segment (each point p at axial coordinate s and distance rho from the axis
///    allows the end to stop sqrt(r^2 - rho^2) short of s);
/// 3. larger radii (which allow shorter segments) are tried by a 1-D search and the
///    smallest volume is kept, each principal axis being tried in turn;
/// 4. the radius is finally reduced to the largest distance of a point from the segment.
/// Contains every point in the exact sense of BoundingCapsule::contains. Errors: TooFew for
/// an empty set ("points"), NotFinite / OutOfRange ("points[i].x" ...). From 257 to 8,192
/// points are replaced by their hull's vertices; more than 2,048 points are searched for
/// the axis through the subset extreme along 512 directions, the final fit and radius
/// using all of them. O(n log n).
Result<BoundingCapsule> fit_capsule(std::span<const Vec3> points);

}  // namespace proxima
