// Sphere: the local origin grown by a radius.
//
// Steps:
//  - support: radius * unit direction (core + radius with a point core, van den Bergen,
//    Collision Detection in Interactive 3D Environments, 4.3.3); the direction is scaled by
//    its largest component before normalising so that denormal and huge directions neither
//    underflow nor overflow;
//  - bounds: centre +- radius on every axis (exact under any rotation);
//  - contains / closest point: the radial projection; the centre itself takes +z;
//  - ray cast: geometry::ray_sphere;
//  - mass: V = 4/3 pi r^3, I = 2/5 m r^2 on every axis.
// Non-finite query input gets the shape-wide defined answer: a finite support point,
// contains false, closest point at distance +infinity, no ray hit.
#include <proxima/core/validate.hpp>
#include <proxima/geometry/raycast.hpp>
#include <proxima/shapes/sphere.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

#include "shapes/far_point.hpp"

namespace proxima {
Result<Sphere> Sphere::create(Real radius) {
  if (auto e = validate::positive(radius, "radius")) return *e;
  return Sphere(radius);
}

Vec3 Sphere::support(const Vec3& direction) const {
  Vec3 unit;
  Real length = Real(0);
  if (!unit_and_length(direction, unit, length)) return Vec3(Real(0), Real(0), radius_);
  return unit * radius_;
}

Aabb Sphere::local_aabb() const { return {Vec3(-radius_), Vec3(radius_)}; }

Aabb Sphere::world_aabb(const Transform& pose) const {
  return {pose.position - Vec3(radius_), pose.position + Vec3(radius_)};
}

std::optional<RayHit> Sphere::raycast(const Ray& ray, Real max_t) const {
  if (!(max_t >= Real(0)) || !is_finite(ray.origin) || !is_finite(ray.direction)) return std::nullopt;
  return geometry::ray_sphere(ray, max_t, Vec3(Real(0)), radius_);
}

bool Sphere::contains(const Vec3& point) const {
  if (!is_finite(point)) return false;
  // Compare in the scale of the radius so that huge coordinates cannot overflow the square.
  const Vec3 q = point / radius_;
  return glm::dot(q, q) <= Real(1);
}

SurfacePoint Sphere::closest_point(const Vec3& point) const {
  if (!is_finite(point)) return detail::far_top_point(radius_);
  SurfacePoint r;
  Vec3 unit(Real(0), Real(0), Real(1));
  Real dist = Real(0);
  unit_and_length(point, unit, dist);  // the centre keeps +z
  r.normal = unit;
  r.point = unit * radius_;
  r.signed_distance = dist - radius_;
  return r;
}

MassProperties Sphere::mass_properties(Real density) const {
  MassProperties m;
  m.volume = Real(4) / Real(3) * kPi * radius_ * radius_ * radius_;
  m.mass = density * m.volume;
  const Real i = Real(0.4) * m.mass * radius_ * radius_;
  m.inertia = Mat3(i);
  return m;
}

}  // namespace proxima
