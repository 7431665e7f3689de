#pragma once
/// @file shape_visit.hpp
/// Internal: calling a generic lambda with the concrete convex type behind a ShapeRef (for
/// code that needs members only convex shapes have, such as support), and the distance
/// between two boxes used as a lower bound when pruning hierarchies.

#include <proxima/geometry/aabb.hpp>
#include <proxima/shapes/shape_ref.hpp>

#include <algorithm>
#include <cmath>

namespace proxima::detail {

/// Calls `f(concrete_shape)` with the convex shape `s` views (one switch, no allocation);
/// `s` must be convex (is_convex(s.type())).
template <class F>
decltype(auto) visit_convex(ShapeRef s, F&& f) {
  switch (s.type()) {
    case ShapeType::Point: return f(s.as<Point>());
    case ShapeType::Segment: return f(s.as<Segment>());
    case ShapeType::Triangle: return f(s.as<Triangle>());
    case ShapeType::Sphere: return f(s.as<Sphere>());
    case ShapeType::Capsule: return f(s.as<Capsule>());
    case ShapeType::Box: return f(s.as<Box>());
    case ShapeType::Cylinder: return f(s.as<Cylinder>());
    case ShapeType::Cone: return f(s.as<Cone>());
    case ShapeType::Ellipsoid: return f(s.as<Ellipsoid>());
    case ShapeType::ConvexHull: return f(s.as<ConvexHull>());
    default: PROXIMA_ASSERT(s.type() == ShapeType::HalfSpace); return f(s.as<HalfSpace>());
  }
}

/// Euclidean distance between two boxes (0 when they overlap or touch): a lower bound on
/// the distance between anything the boxes contain.
inline Real aabb_gap(const Aabb& a, const Aabb& b) {
  Real d2 = Real(0);
  for (int i = 0; i < 3; ++i) {
    const Real g = std::max({a.min[i] - b.max[i], b.min[i] - a.max[i], Real(0)});
    d2 += g * g;
  }
  return std::sqrt(d2);
}

}  // namespace proxima::detail
