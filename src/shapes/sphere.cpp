#include <proxima/core/validate.hpp>
#include <proxima/geometry/raycast.hpp>
#include <proxima/shapes/sphere.hpp>

namespace proxima {

Result<Sphere> Sphere::create(Real radius) {
  if (auto e = validate::positive(radius, "radius")) return *e;
  return Sphere(radius);
}

Vec3 Sphere::support(const Vec3& direction) const {
  const Real len2 = glm::dot(direction, direction);
  if (!(len2 > Real(0))) return Vec3(Real(0), Real(0), radius_);
  return direction * (radius_ / std::sqrt(len2));
}

Aabb Sphere::local_aabb() const { return {Vec3(-radius_), Vec3(radius_)}; }

Aabb Sphere::world_aabb(const Transform& pose) const {
  return {pose.position - Vec3(radius_), pose.position + Vec3(radius_)};
}

std::optional<RayHit> Sphere::raycast(const Ray& ray, Real max_t) const {
  return geometry::ray_sphere(ray, max_t, Vec3(Real(0)), radius_);
}

bool Sphere::contains(const Vec3& point) const { return glm::dot(point, point) <= radius_ * radius_; }

SurfacePoint Sphere::closest_point(const Vec3& point) const {
  const Real dist = glm::length(point);
  SurfacePoint r;
  r.normal = dist > Real(0) ? point / dist : Vec3(Real(0), Real(0), Real(1));
  r.point = r.normal * radius_;
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
