#pragma once
/// @file fit_shape_capsule.hpp
/// Bounding capsule of a placed shape (any shape type with the members of Sphere).
///
/// Steps:
///  1. Shapes that are capsules already (point, segment, sphere, capsule): the exact capsule.
///  2. Otherwise the axis u is the longest axis of the shape's oriented box
///     (fit_shape_obb), through the box centre c.
///  3. The axial extent [lo, hi] along u comes from two support queries, h(u) and h(-u).
///  4. The distance from the axis is bounded by support queries in N directions d_k
///     orthogonal to u: the farthest point from the axis lies within pi/N of some d_k, so
///     rho = max_k (h(d_k) - d_k . c) / cos(pi/N) bounds it.
///  5. The capsule with segment c + [lo, hi] u and radius rho contains the cylinder that
///     contains the shape; the radius is padded by a few ulps against rounding.
/// Support functions of convex sets: Ericson, Real-Time Collision Detection, 3.8 and 4.3.

#include <proxima/bounds/bounding_capsule.hpp>
#include <proxima/bounds/fit_shape.hpp>

#include <algorithm>
#include <cmath>

namespace proxima {

/// World bounding capsule of the shape: exact for Point, Segment, Sphere and Capsule; for
/// the other bounded shapes a capsule along the longest axis of the shape's oriented box
/// that contains the shape (not the minimal one: its radius may exceed the shape's largest
/// distance from the axis by the factor 1/cos(pi/64) = 1.0012). A HalfSpace gets radius
/// kRealMax (it is unbounded). Cost: 66 support queries for the generic case.
template <class S>
BoundingCapsule fit_shape_capsule(const S& shape, const Transform& pose) {
  constexpr int kDirections = 64;
  const Real pose_scale = std::max({std::abs(pose.position.x), std::abs(pose.position.y), std::abs(pose.position.z)});
  if constexpr (S::kType == ShapeType::HalfSpace) {
    return BoundingCapsule{pose.position, pose.position, kRealMax};
  } else if constexpr (S::kType == ShapeType::Point) {
    return BoundingCapsule{pose.position, pose.position, Real(0)};
  } else if constexpr (S::kType == ShapeType::Segment) {
    return BoundingCapsule{pose.apply(shape.a()), pose.apply(shape.b()), detail::pad_up(Real(0), pose_scale)};
  } else if constexpr (S::kType == ShapeType::Sphere) {
    return BoundingCapsule{pose.position, pose.position, detail::pad_up(shape.radius(), pose_scale)};
  } else if constexpr (S::kType == ShapeType::Capsule) {
    return BoundingCapsule{pose.apply(shape.bottom()), pose.apply(shape.top()),
                           detail::pad_up(shape.radius(), pose_scale)};
  } else {
    const Obb box = fit_shape_obb(shape, pose);
    int longest = 0;
    for (int i = 1; i < 3; ++i) {
      if (box.half_extents[i] > box.half_extents[longest]) longest = i;
    }
    const Vec3 u = box.axes[longest];
    const Vec3 v = box.axes[(longest + 1) % 3];
    const Vec3 w = box.axes[(longest + 2) % 3];
    const Vec3 c = box.center;
    const Real hi = glm::dot(support(shape, pose, u) - c, u);
    const Real lo = glm::dot(support(shape, pose, -u) - c, u);
    Real rho = Real(0);
    for (int k = 0; k < kDirections; ++k) {
      const Real angle = Real(2) * kPi * static_cast<Real>(k) / static_cast<Real>(kDirections);
      const Vec3 d = std::cos(angle) * v + std::sin(angle) * w;
      rho = std::max(rho, glm::dot(support(shape, pose, d) - c, d));
    }
    rho /= std::cos(kPi / static_cast<Real>(kDirections));
    const Real scale = std::max({std::abs(c.x), std::abs(c.y), std::abs(c.z), std::abs(lo), std::abs(hi)});
    return BoundingCapsule{c + lo * u, c + hi * u, detail::pad_up(rho, scale)};
  }
}

}  // namespace proxima
