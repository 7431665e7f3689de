// Point: the local origin as a shape without interior.
//
// Steps:
//  - support, core and boxes are the origin itself;
//  - contains and closest point measure the distance to the origin;
//  - ray cast: the ray's nearest approach to the origin is the projection of the origin on
//    the ray, t* = -(o . d) / |d|^2 clamped to [0, max_t] (Ericson, Real-Time Collision
//    Detection, 5.1.2); it is a hit when it passes within the linear tolerance of the
//    ray's coordinates. The direction is normalised by its largest component first so that
//    neither tiny nor huge directions underflow or overflow.
#include <proxima/core/tolerance.hpp>
#include <proxima/shapes/point.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace proxima {
Result<Point> Point::create() { return Point(); }

Aabb Point::local_aabb() const { return Aabb::from_point(Vec3(Real(0))); }

Aabb Point::world_aabb(const Transform& pose) const { return Aabb::from_point(pose.position); }

std::optional<RayHit> Point::raycast(const Ray& ray, Real max_t) const {
  if (!(max_t >= Real(0)) || !is_finite(ray.origin) || !is_finite(ray.direction)) return std::nullopt;
  const Real tol = linear_tolerance(max_abs_component(ray.origin));
  Vec3 unit;
  Real len = Real(0);
  if (!unit_and_length(ray.direction, unit, len)) {
    if (max_abs_component(ray.origin) > tol) return std::nullopt;
    return RayHit{Real(0), ray.origin, Vec3(Real(0), Real(0), Real(1))};
  }
  // Distance along the unit direction to the foot of the origin, then in units of |d|.
  const Real s = -glm::dot(ray.origin, unit);
  const Real t = std::min(std::max(s / len, Real(0)), max_t);
  const Vec3 p = ray.at(t);
  if (max_abs_component(p) > tol || glm::length(p) > tol) return std::nullopt;
  return RayHit{t, p, -unit};
}

bool Point::contains(const Vec3& point) const {
  if (!is_finite(point)) return false;
  const Real tol = linear_tolerance(Real(0));
  return max_abs_component(point) <= tol && glm::length(point) <= tol;
}

SurfacePoint Point::closest_point(const Vec3& point) const {
  SurfacePoint r;
  r.point = Vec3(Real(0));
  Vec3 unit;
  Real len = Real(0);
  if (!is_finite(point)) {
    r.signed_distance = std::numeric_limits<Real>::infinity();
  } else if (unit_and_length(point, unit, len)) {
    r.normal = unit;
    r.signed_distance = len;
  } else {
    r.normal = Vec3(Real(0), Real(0), Real(1));
    r.signed_distance = Real(0);
  }
  return r;
}

MassProperties Point::mass_properties(Real /*density*/) const { return MassProperties{}; }

}  // namespace proxima
