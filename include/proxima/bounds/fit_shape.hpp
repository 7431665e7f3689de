#pragma once
/// @file fit_shape.hpp
/// Bounding volumes of a placed shape: any shape type S with the members of Sphere
/// (support, core_support, core_radius, local_aabb, world_aabb), placed at a Transform.
/// Results are in the world frame and contain the whole shape; each is padded outward by
/// a few ulps of its coordinates' magnitude so that transformed surface points, rounded
/// differently, still pass the volume's contains().

#include <proxima/bounds/bounding_sphere.hpp>
#include <proxima/bounds/fit_sphere.hpp>
#include <proxima/bounds/kdop.hpp>
#include <proxima/bounds/obb.hpp>
#include <proxima/core/tolerance.hpp>
#include <proxima/core/transform.hpp>
#include <proxima/geometry/aabb.hpp>
#include <proxima/shapes/placed.hpp>
#include <proxima/shapes/shape_type.hpp>

#include <algorithm>
#include <array>
#include <cmath>

namespace proxima {

namespace detail {
/// x moved outward by a few ulps of max(|x|, scale), never past +-kRealMax.
inline Real pad_up(Real x, Real scale) {
  const Real pad = Real(8) * kEpsilon * std::max(std::abs(x), scale);
  return x < kRealMax - pad ? x + pad : kRealMax;
}
/// x moved down by a few ulps of max(|x|, scale), never past -kRealMax.
inline Real pad_down(Real x, Real scale) { return -pad_up(-x, scale); }
/// Sum of the magnitudes of the terms of d . p: the scale of the rounding error of a
/// projection onto d, which exceeds |d . p| when the terms cancel (far points).
inline Real projection_terms(const Vec3& d, const Vec3& p) {
  return std::abs(d.x * p.x) + std::abs(d.y * p.y) + std::abs(d.z * p.z);
}
}  // namespace detail

/// World box of the shape: world_aabb (exact for every shape), padded by a few ulps.
template <class S>
Aabb fit_shape_aabb(const S& shape, const Transform& pose) {
  Aabb box = shape.world_aabb(pose);
  for (int i = 0; i < 3; ++i) {
    const Real scale = std::abs(pose.position[i]);
    box.min[i] = detail::pad_down(box.min[i], scale);
    box.max[i] = detail::pad_up(box.max[i], scale);
  }
  return box;
}

/// World oriented box of the shape: its local box under the pose (centre mapped, axes =
/// the pose's rotation columns, same half extents), padded by a few ulps.
template <class S>
Obb fit_shape_obb(const S& shape, const Transform& pose) {
  Obb box = Obb::from_aabb(shape.local_aabb(), pose);
  const Real scale = std::max({std::abs(box.center.x), std::abs(box.center.y), std::abs(box.center.z)});
  for (int i = 0; i < 3; ++i) box.half_extents[i] = detail::pad_up(box.half_extents[i], scale);
  return box;
}

/// Exact world k-DOP of the shape from its support mapping: slab i spans
/// [d_i . support(-d_i), d_i . support(d_i)] (world support of the placed shape), padded
/// by a few ulps of the largest of the pose's coordinates and the magnitudes of the
/// projections' terms (a far support point whose coordinates cancel in d_i . p carries
/// their rounding, not that of the sum). O(K) support queries.
template <int K, class S>
Kdop<K> fit_shape_kdop(const S& shape, const Transform& pose) {
  Kdop<K> k;
  const Real position_scale =
      std::max({std::abs(pose.position.x), std::abs(pose.position.y), std::abs(pose.position.z)});
  for (int i = 0; i < K / 2; ++i) {
    const Vec3 d = Kdop<K>::direction(i);
    const Vec3 p_hi = support(shape, pose, d);
    const Vec3 p_lo = support(shape, pose, -d);
    const Real hi = Kdop<K>::project(i, p_hi);
    const Real lo = Kdop<K>::project(i, p_lo);
    const Real scale = std::max({position_scale, detail::projection_terms(d, p_hi), detail::projection_terms(d, p_lo)});
    k.min[i] = detail::pad_down(std::min(lo, hi), scale);
    k.max[i] = detail::pad_up(std::max(lo, hi), scale);
  }
  return k;
}

/// World bounding sphere of the shape, from the shape's own geometry: exact minimal spheres
/// for Point, Segment, Triangle, Sphere, Capsule, Box, Cylinder, Cone, Ellipsoid and
/// ConvexHull (Welzl on its vertices); a HalfSpace gets radius kRealMax (it is unbounded);
/// other shape types the smaller of the ball around their local box and the ball around
/// their core's box grown by core_radius. Padded by a few ulps.
template <class S>
BoundingSphere fit_shape_sphere(const S& shape, const Transform& pose) {
  Vec3 local_center(Real(0));
  Real radius = Real(0);
  if constexpr (S::kType == ShapeType::Point) {
    radius = Real(0);
  } else if constexpr (S::kType == ShapeType::Segment) {
    local_center = shape.a() * Real(0.5) + shape.b() * Real(0.5);
    radius = Real(0.5) * glm::length(shape.b() - shape.a());
  } else if constexpr (S::kType == ShapeType::Triangle) {
    const std::array<Vec3, 3> corners{shape.a(), shape.b(), shape.c()};
    const BoundingSphere s = fit_sphere_minimal(corners).value();
    local_center = s.center;
    radius = s.radius;
  } else if constexpr (S::kType == ShapeType::Sphere) {
    radius = shape.radius();
  } else if constexpr (S::kType == ShapeType::Capsule) {
    radius = shape.half_length() + shape.radius();
  } else if constexpr (S::kType == ShapeType::Box) {
    radius = glm::length(shape.half_extents());
  } else if constexpr (S::kType == ShapeType::Cylinder) {
    radius = std::hypot(shape.radius(), shape.half_length());
  } else if constexpr (S::kType == ShapeType::Cone) {
    // Apex (0,0,h), base circle of radius r at z = -h: the ball through the apex and the
    // rim has its centre at z = -r^2 / (4h) when that lies above the base, otherwise the
    // ball of the base circle contains the apex.
    const Real h = shape.half_length();
    const Real r = shape.radius();
    if (r <= Real(2) * h) {
      const Real z = -r * r / (Real(4) * h);
      local_center = Vec3(Real(0), Real(0), z);
      radius = h - z;
    } else {
      local_center = Vec3(Real(0), Real(0), -h);
      radius = r;
    }
  } else if constexpr (S::kType == ShapeType::Ellipsoid) {
    const Vec3 r = shape.radii();
    radius = std::max({r.x, r.y, r.z});
  } else if constexpr (S::kType == ShapeType::ConvexHull) {
    const BoundingSphere s = fit_sphere_minimal(shape.vertices()).value();
    local_center = s.center;
    radius = s.radius;
  } else if constexpr (S::kType == ShapeType::HalfSpace) {
    return BoundingSphere{pose.position, kRealMax};
  } else {
    const Aabb box = shape.local_aabb();
    const Vec3 c = box.max * Real(0.5) + box.min * Real(0.5);
    const Vec3 h = box.max * Real(0.5) - box.min * Real(0.5);
    local_center = c;
    radius = glm::length(h);
    Aabb core;
    for (int i = 0; i < 3; ++i) {
      Vec3 d(Real(0));
      d[i] = Real(1);
      core.grow(shape.core_support(d));
      core.grow(shape.core_support(-d));
    }
    const Real core_ball = glm::length(core.half_extents()) + shape.core_radius();
    if (core_ball < radius) {
      local_center = core.center();
      radius = core_ball;
    }
  }
  const Vec3 center = pose.apply(local_center);
  const Real scale = std::max({std::abs(center.x), std::abs(center.y), std::abs(center.z)});
  return BoundingSphere{center, detail::pad_up(radius, scale)};
}

}  // namespace proxima
