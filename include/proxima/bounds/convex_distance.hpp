#pragma once
/// @file convex_distance.hpp
/// Distance between the convex hulls of two point sets by GJK, the general method behind
/// the overlap tests of bounding volumes that have no closed form.

#include <proxima/core/math.hpp>

#include <span>

namespace proxima {

/// Outcome of convex_distance.
struct ConvexDistance {
  Real distance = Real(0);  ///< distance between conv(a) and conv(b) (0 when they intersect)
  Vec3 on_a{Real(0)};       ///< a closest point of conv(a) (a convex combination of a's points)
  Vec3 on_b{Real(0)};       ///< a closest point of conv(b)
  int iterations = 0;       ///< GJK iterations used
};

/// Euclidean distance between conv(a) and conv(b) (non-empty point sets, any frame) by the
/// GJK distance algorithm (Gilbert, Johnson, Keerthi, IEEE J. Robotics and Automation
/// 1988; van den Bergen, "A Fast and Robust GJK Implementation for Collision Detection of
/// Convex Objects", JGT 1999), in double precision around a local origin with a
/// Voronoi-region simplex solver (Ericson, Real-Time Collision Detection, 5.1.5-5.1.6,
/// 9.5). Terminates when the lower bound from the support gap is within a relative 1e-12
/// of the distance, when no progress is made, or after 128 iterations; the answer is never
/// NaN and never smaller than the true distance minus that gap. O(iterations (|a| + |b|)).
ConvexDistance convex_distance(std::span<const Vec3> a, std::span<const Vec3> b);

/// True when the set of points within `radius_a` of conv(a) meets the set within
/// `radius_b` of conv(b): GJK distance <= radius_a + radius_b + tolerance, the tolerance
/// being 16 ulps (of Real) of the largest coordinate magnitude (and radius).
bool convex_cores_overlap(std::span<const Vec3> a, Real radius_a, std::span<const Vec3> b, Real radius_b);

}  // namespace proxima
