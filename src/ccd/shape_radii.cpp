// Radii of geometries about their origins and world support points, for the motion bounds.

#include "ccd/shape_radii.hpp"

#include <proxima/ccd/movement_bounds.hpp>
#include <proxima/shapes/placed.hpp>

#include <algorithm>
#include <array>
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

// Largest distance of `points` from the line through the origin along the unit `axis`.
template <class Points>
Real farthest_from_axis(const Points& points, const Vec3& axis) {
  Real r2 = Real(0);
  for (const Vec3& p : points) {
    const Vec3 off = p - glm::dot(p, axis) * axis;
    r2 = std::max(r2, glm::dot(off, off));
  }
  return std::sqrt(r2);
}

std::array<Vec3, 8> corners(const Aabb& box) {
  std::array<Vec3, 8> c;
  for (int i = 0; i < 8; ++i) {
    c[i] = Vec3(i & 1 ? box.max.x : box.min.x, i & 2 ? box.max.y : box.min.y, i & 4 ? box.max.z : box.min.z);
  }
  return c;
}

}  // namespace

ShapeRadii shape_radii_about_axis(ShapeRef shape, const Vec3& axis) {
  ShapeRadii r = shape_radii(shape);
  if (r.halfspace) return r;
  visit_shape(shape, [&](const auto& s) {
    using S = std::decay_t<decltype(s)>;
    if constexpr (std::is_same_v<S, Sphere> || std::is_same_v<S, Point>) {
      // Rotation does not move them; `full` keeps the rounding radius.
    } else if constexpr (std::is_same_v<S, Capsule>) {
      const std::array<Vec3, 2> ends{s.top(), -s.top()};
      r.core = std::min(r.core, farthest_from_axis(ends, axis));
      r.full = std::min(r.full, r.core + s.radius());
    } else if constexpr (std::is_same_v<S, ConvexHull>) {
      r.core = r.full = std::min(r.full, farthest_from_axis(s.vertices(), axis));
    } else {
      const Real by_box = farthest_from_axis(corners(s.local_aabb()), axis);
      r.core = std::min(r.core, by_box);
      r.full = std::min(r.full, by_box);
    }
  });
  return r;
}

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
