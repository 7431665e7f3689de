// Box: the solid [-h, h] in its local frame.
//
// Steps:
//  - support: the corner whose signs match the direction's;
//  - world box: Arvo's method, |R| h around the transformed centre (Graphics Gems, 1990);
//  - ray cast: slab method (geometry::ray_aabb);
//  - closest point (Ericson, Real-Time Collision Detection, 5.1.3): outside, the point
//    clamped to the box; inside, the nearest face (smallest h_i - |p_i|), the point
//    projected on it and that face's normal, with a negative distance;
//  - mass: the closed-form inertia of a cuboid, m/3 (h_j^2 + h_k^2) on axis i.
#include <proxima/core/validate.hpp>
#include <proxima/geometry/closest_points.hpp>
#include <proxima/geometry/raycast.hpp>
#include <proxima/shapes/box.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

#include "shapes/far_point.hpp"

namespace proxima {
Result<Box> Box::create(const Vec3& half_extents) {
  if (auto e = validate::positive(half_extents.x, "half_extents.x")) return *e;
  if (auto e = validate::positive(half_extents.y, "half_extents.y")) return *e;
  if (auto e = validate::positive(half_extents.z, "half_extents.z")) return *e;
  return Box(half_extents);
}

Vec3 Box::support(const Vec3& direction) const {
  const Vec3& h = half_extents_;
  return {direction.x >= Real(0) ? h.x : -h.x, direction.y >= Real(0) ? h.y : -h.y,
          direction.z >= Real(0) ? h.z : -h.z};
}

Aabb Box::local_aabb() const { return {-half_extents_, half_extents_}; }

Aabb Box::world_aabb(const Transform& pose) const { return local_aabb().transformed(pose); }

std::optional<RayHit> Box::raycast(const Ray& ray, Real max_t) const {
  if (!(max_t >= Real(0)) || !is_finite(ray.origin) || !is_finite(ray.direction)) return std::nullopt;
  return geometry::ray_aabb(ray, max_t, local_aabb());
}

bool Box::contains(const Vec3& point) const {
  if (!is_finite(point)) return false;
  const Vec3& h = half_extents_;
  return std::abs(point.x) <= h.x && std::abs(point.y) <= h.y && std::abs(point.z) <= h.z;
}

SurfacePoint Box::closest_point(const Vec3& point) const {
  if (!is_finite(point)) return detail::far_top_point(half_extents_.z);
  SurfacePoint r;
  if (!contains(point)) {
    r.point = geometry::closest_point_aabb(point, local_aabb());
    Vec3 unit;
    Real dist = Real(0);
    unit_and_length(point - r.point, unit, dist);  // non-zero: the point is outside
    r.normal = unit;
    r.signed_distance = dist;
    return r;
  }
  int axis = 0;
  Real gap = half_extents_.x - std::abs(point.x);
  for (int i = 1; i < 3; ++i) {
    const Real g = half_extents_[i] - std::abs(point[i]);
    if (g < gap) {
      gap = g;
      axis = i;
    }
  }
  const Real side = point[axis] >= Real(0) ? Real(1) : Real(-1);
  r.point = point;
  r.point[axis] = side * half_extents_[axis];
  r.normal = Vec3(Real(0));
  r.normal[axis] = side;
  r.signed_distance = gap > Real(0) ? -gap : Real(0);
  return r;
}

MassProperties Box::mass_properties(Real density) const {
  const Vec3 h2 = half_extents_ * half_extents_;
  MassProperties m;
  m.volume = Real(8) * half_extents_.x * half_extents_.y * half_extents_.z;
  m.mass = density * m.volume;
  m.inertia = Mat3(Real(0));
  m.inertia[0][0] = m.mass / Real(3) * (h2.y + h2.z);
  m.inertia[1][1] = m.mass / Real(3) * (h2.x + h2.z);
  m.inertia[2][2] = m.mass / Real(3) * (h2.x + h2.y);
  return m;
}

}  // namespace proxima
