// Radii of geometries about their origins and world support points, for the motion bounds.

#include "ccd/shape_radii.hpp"

#include <proxima/ccd/movement_bounds.hpp>
#include <proxima/shapes/placed.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <type_traits>

namespace proxima::detail {

namespace {

template <class S>
Real hull_radius(const S& shape) {
  Real r2 = Real(0);
  for (const Vec3& v : shape.vertices()) r2 = std::max(r2, glm::dot(v, v));
  return std::sqrt(r2);
}

}  // namespace

ShapeRadii shape_radii(ShapeRef shape) {
  constexpr Real kInfinity = std::numeric_limits<Real>::infinity();
  return visit_shape(shape, [](const auto& s) -> ShapeRadii {
    using S = std::decay_t<decltype(s)>;
    ShapeRadii r;
    if constexpr (std::is_same_v<S, HalfSpace>) {
      r.core = r.full = kInfinity;
      r.halfspace = true;
    } else if constexpr (std::is_same_v<S, TriangleMesh> || std::is_same_v<S, Compound>) {
      r.core = r.full = radius_about_origin(s.local_aabb());
    } else {
      r.convex = true;
      if constexpr (std::is_same_v<S, Sphere> || std::is_same_v<S, Point>) {
        r.core = Real(0);
        r.full = s.core_radius();
      } else if constexpr (std::is_same_v<S, Capsule>) {
        r.core = s.half_length();
        r.full = s.half_length() + s.radius();
      } else if constexpr (std::is_same_v<S, ConvexHull>) {
        r.core = r.full = hull_radius(s);
      } else {
        r.full = radius_about_origin(s.local_aabb());
        r.core = r.full;
      }
    }
    return r;
  });
}

Vec3 world_support(ShapeRef shape, const Transform& pose, const Vec3& direction) {
  return visit_shape(shape, [&](const auto& s) -> Vec3 {
    using S = std::decay_t<decltype(s)>;
    if constexpr (ConvexShape<S> && !std::is_same_v<S, HalfSpace>) {
      return support(s, pose, direction);
    } else {
      return pose.position;
    }
  });
}

}  // namespace proxima::detail
