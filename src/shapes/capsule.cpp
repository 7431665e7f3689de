// Capsule: the segment (0,0,-h)-(0,0,h) of the local z axis grown by a radius.
//
// Steps:
//  - support: the segment end on the side of the direction plus radius * unit direction
//    (core + radius, van den Bergen, Collision Detection in Interactive 3D Environments,
//    4.3.3);
//  - bounds: the box of the two transformed segment ends grown by the radius (the capsule
//    is their Minkowski sum with a ball, so the box is exact);
//  - contains / closest point: the nearest axis point, z clamped to [-h, h], pushed out by
//    the radius;
//  - ray cast: geometry::ray_capsule;
//  - mass: a cylinder of height 2h plus a sphere split in two hemispheres, each
//    hemisphere's inertia moved from its own centroid (3r/8 from its flat face) to the
//    capsule centre by the parallel-axis theorem.
#include <proxima/core/validate.hpp>
#include <proxima/geometry/raycast.hpp>
#include <proxima/shapes/capsule.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace proxima {
Result<Capsule> Capsule::create(Real radius, Real half_length) {
  if (auto e = validate::positive(radius, "radius")) return *e;
  if (auto e = validate::non_negative(half_length, "half_length")) return *e;
  return Capsule(radius, half_length);
}

Vec3 Capsule::support(const Vec3& direction) const {
  Vec3 unit;
  Real len = Real(0);
  if (!is_finite(direction) || !unit_and_length(direction, unit, len)) {
    return Vec3(Real(0), Real(0), half_length_ + radius_);
  }
  return core_support(direction) + radius_ * unit;
}

Aabb Capsule::local_aabb() const {
  const Vec3 h(radius_, radius_, half_length_ + radius_);
  return {-h, h};
}

Aabb Capsule::world_aabb(const Transform& pose) const {
  const Vec3 axis = pose.apply_vector(top());
  const Vec3 e = glm::abs(axis) + Vec3(radius_);
  return {pose.position - e, pose.position + e};
}

std::optional<RayHit> Capsule::raycast(const Ray& ray, Real max_t) const {
  if (!(max_t >= Real(0)) || !is_finite(ray.origin) || !is_finite(ray.direction)) return std::nullopt;
  return geometry::ray_capsule(ray, max_t, bottom(), top(), radius_);
}

bool Capsule::contains(const Vec3& point) const {
  if (!is_finite(point)) return false;
  const Real z = std::clamp(point.z, -half_length_, half_length_);
  const Vec3 d(point.x, point.y, point.z - z);
  return glm::dot(d, d) <= radius_ * radius_;
}

SurfacePoint Capsule::closest_point(const Vec3& point) const {
  if (!is_finite(point)) {
    return SurfacePoint{Vec3(Real(0), Real(0), half_length_ + radius_), Vec3(Real(0), Real(0), Real(1)),
                        std::numeric_limits<Real>::infinity()};
  }
  const Vec3 core(Real(0), Real(0), std::clamp(point.z, -half_length_, half_length_));
  Vec3 unit;
  Real dist = Real(0);
  if (!unit_and_length(point - core, unit, dist)) unit = Vec3(Real(1), Real(0), Real(0));
  SurfacePoint r;
  r.normal = unit;
  r.point = core + radius_ * unit;
  r.signed_distance = dist - radius_;
  return r;
}

MassProperties Capsule::mass_properties(Real density) const {
  const Real r = radius_;
  const Real h = half_length_;
  const Real r2 = r * r;
  const Real cylinder_volume = kPi * r2 * (Real(2) * h);
  const Real sphere_volume = Real(4) / Real(3) * kPi * r2 * r;
  const Real mc = density * cylinder_volume;
  const Real ms = density * sphere_volume;
  // Cylinder about its centre: axial m r^2 / 2, transverse m (3 r^2 + (2h)^2) / 12.
  // Both hemispheres together (mass ms): axial 2/5 ms r^2; transverse, each one about its
  // flat face's centre 2/5 m r^2, moved to its centroid (-m (3r/8)^2) then to the capsule
  // centre (+m (h + 3r/8)^2): ms (2/5 r^2 + h^2 + 3/4 h r).
  const Real axial = mc * r2 * Real(0.5) + ms * Real(0.4) * r2;
  const Real transverse = mc * (r2 * Real(0.25) + h * h / Real(3)) + ms * (Real(0.4) * r2 + h * h + Real(0.75) * h * r);
  MassProperties m;
  m.volume = cylinder_volume + sphere_volume;
  m.mass = mc + ms;
  m.inertia = Mat3(Real(0));
  m.inertia[0][0] = transverse;
  m.inertia[1][1] = transverse;
  m.inertia[2][2] = axial;
  return m;
}

}  // namespace proxima
