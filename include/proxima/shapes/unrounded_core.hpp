#pragma once
/// @file unrounded_core.hpp
/// UnroundedCore<Shape>: the CRTP base of the convex shapes that are their own core (no
/// rounding radius), which states their identical ConvexShape members once. A shape header
/// includes this file for the whole shared vocabulary: the ConvexShape concept and its types
/// (convex_shape.hpp) and Result for the shape's validated `create`.

#include <proxima/core/math.hpp>
#include <proxima/core/result.hpp>
#include <proxima/shapes/convex_shape.hpp>

namespace proxima {

/// Base of a convex shape `Shape` whose core is the shape itself: the "core + radius" members
/// of ConvexShape (convex_shape.hpp) for a zero radius. `Shape` derives publicly from
/// UnroundedCore<Shape> and provides a public `Vec3 support(const Vec3& direction) const`.
/// The base is empty: it adds nothing to the size of the shape.
template <class Shape>
class UnroundedCore {
 public:
  /// Farthest point of the core (the shape itself) in `direction` (local frame, any
  /// length): Shape::support(direction).
  Vec3 core_support(const Vec3& direction) const { return static_cast<const Shape&>(*this).support(direction); }
  /// Radius added around the core (length units): 0.
  Real core_radius() const { return Real(0); }

 protected:
  UnroundedCore() = default;
};

}  // namespace proxima
