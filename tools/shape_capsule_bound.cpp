// Bounding capsule of a placed convex shape.
// Steps: 1. exact answers for the shapes that are capsules already (point, segment, sphere,
// capsule); 2. otherwise the axis u is the longest axis of the shape's oriented box (library
// fit_shape_obb), through the box centre c; 3. the axial extent [lo, hi] of the shape along u
// comes from two support queries (h(u), h(-u)); 4. the radial extent is bounded from the
// support function h in N directions d_k orthogonal to u: the farthest point from the axis
// lies within pi/N of some d_k, so rho = max_k (h(d_k) - d_k . c) / cos(pi/N) bounds it;
// 5. the capsule with segment c + [lo, hi] u and radius rho contains the cylinder that
// contains the shape; the radius is padded by a few ulps against rounding.
// Support functions of convex sets: Ericson, Real-Time Collision Detection, 3.8 and 4.3.
#include "shape_capsule_bound.hpp"

#include <proxima/bounds/fit_shape.hpp>
#include <proxima/core/tolerance.hpp>
#include <proxima/shapes/placed.hpp>

#include <algorithm>
#include <cmath>
#include <variant>

namespace proxima::tool {

namespace {

constexpr int kDirections = 64;

Real padded(Real radius, Real scale) { return radius + Real(16) * kEpsilon * std::max(radius, scale); }

template <class S>
BoundingCapsule generic_capsule(const S& shape, const Transform& pose) {
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
  return BoundingCapsule{c + lo * u, c + hi * u, padded(rho, scale)};
}

}  // namespace

BoundingCapsule bound_shape_capsule(const Shape& shape, const Transform& pose, const std::string& field) {
  return std::visit(
      [&](const auto& s) -> BoundingCapsule {
        using S = std::decay_t<decltype(s)>;
        const Real scale = std::max({std::abs(pose.position.x), std::abs(pose.position.y), std::abs(pose.position.z)});
        if constexpr (S::kType == ShapeType::HalfSpace) {
          throw FieldError(field, "unbounded", "a halfspace is unbounded: only the aabb and sphere bounds exist");
        } else if constexpr (S::kType == ShapeType::Point) {
          return BoundingCapsule{pose.position, pose.position, Real(0)};
        } else if constexpr (S::kType == ShapeType::Segment) {
          return BoundingCapsule{pose.apply(s.a()), pose.apply(s.b()), padded(Real(0), scale)};
        } else if constexpr (S::kType == ShapeType::Sphere) {
          return BoundingCapsule{pose.position, pose.position, padded(s.radius(), scale)};
        } else if constexpr (S::kType == ShapeType::Capsule) {
          return BoundingCapsule{pose.apply(s.bottom()), pose.apply(s.top()), padded(s.radius(), scale)};
        } else {
          return generic_capsule(s, pose);
        }
      },
      shape);
}

}  // namespace proxima::tool
