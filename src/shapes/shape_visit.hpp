#pragma once
/// @file shape_visit.hpp
/// Internal: calling a generic lambda with the concrete convex type behind a ShapeRef (for
/// code that needs members only convex shapes have, such as support), and the distance
/// between two boxes used as a lower bound when pruning hierarchies.

#include <proxima/geometry/aabb.hpp>
#include <proxima/shapes/shape_ref.hpp>

#include <algorithm>
#include <cmath>
#include <type_traits>
#include <utility>

namespace proxima::detail {

/// Calls `f(concrete_shape)` with the convex shape `s` views (one switch, no allocation);
/// `s` must be convex (is_convex(s.type())). Unlike visit_shape, `f` is instantiated for the
/// convex types only, so it may use members only they have (support, core_radius).
template <class F>
decltype(auto) visit_convex(ShapeRef s, F&& f) {
  using R = decltype(f(std::declval<const Point&>()));
  return visit_shape(s, [&](const auto& shape) -> R {
    if constexpr (is_convex(kShapeTypeOf<std::decay_t<decltype(shape)>>)) {
      return f(shape);
    } else {
      PROXIMA_ASSERT(false && "visit_convex on a mesh or compound");
      return f(s.as<HalfSpace>());  // not reached for a convex view
    }
  });
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
