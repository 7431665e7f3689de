#pragma once
/// @file fit_sphere.hpp
/// Fitting a bounding sphere to a point set: three fast approximations and the exact
/// minimal sphere (Welzl's algorithm).
///
/// Every fitter returns a sphere that contains every input point in the exact sense of
/// BoundingSphere::contains. Errors (all fitters): TooFew for an empty set ("points"),
/// NotFinite / OutOfRange for a bad coordinate ("points[i].x" ...).

#include <proxima/bounds/bounding_sphere.hpp>
#include <proxima/core/math.hpp>
#include <proxima/core/result.hpp>

#include <span>

namespace proxima {

/// Sphere fitting methods, from the cheapest to the tightest.
enum class SphereFit {
  Centroid,    ///< centre = mean of the points, radius = farthest point. O(n)
  AabbCenter,  ///< centre = centre of the points' box, radius = farthest point. O(n)
  Ritter,      ///< Ritter's two-pass growing sphere (Graphics Gems, 1990). O(n)
  Minimal      ///< the exact smallest enclosing sphere (Welzl / Gaertner). Expected O(n)
};

/// Sphere centred on the mean of the points, radius to the farthest point. O(n).
Result<BoundingSphere> fit_sphere_centroid(std::span<const Vec3> points);

/// Sphere centred on the centre of the points' axis-aligned box, radius to the farthest
/// point. O(n).
Result<BoundingSphere> fit_sphere_aabb_center(std::span<const Vec3> points);

/// Ritter's sphere: start from the farthest pair found by two farthest-point passes, then
/// grow the sphere just enough to take in every point left outside (J. Ritter, "An
/// Efficient Bounding Sphere", Graphics Gems, 1990). At most ~5% larger than minimal on
/// typical data, never smaller. O(n).
Result<BoundingSphere> fit_sphere_ritter(std::span<const Vec3> points);

/// The smallest sphere containing every point (E. Welzl, "Smallest enclosing disks (balls
/// and ellipsoids)", 1991, in B. Gaertner's move-to-front form with pivoting, "Fast and
/// Robust Smallest Enclosing Balls", ESA 1999). Deterministic: it works on a copy shuffled
/// from a fixed seed. The support-set solver handles degenerate (collinear, coplanar,
/// repeated) support sets. Expected O(n); the radius is exact up to a few ulps (then
/// enlarged by the few ulps needed for every point to pass BoundingSphere::contains).
Result<BoundingSphere> fit_sphere_minimal(std::span<const Vec3> points);

/// Fits with the chosen method.
Result<BoundingSphere> fit_sphere(std::span<const Vec3> points, SphereFit method = SphereFit::Minimal);

}  // namespace proxima
