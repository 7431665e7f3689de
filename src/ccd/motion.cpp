// Motion over a step: placement at t, angular velocity, and the speed bounds of motion.hpp.

#include <proxima/ccd/motion.hpp>
#include <proxima/core/tolerance.hpp>
#include <proxima/core/validate.hpp>

#include <cmath>
#include <limits>

namespace proxima {

Motion Motion::from_velocity(const Transform& pose, const Vec3& linear, const Vec3& angular, Real dt) {
  Motion m{pose, pose};
  m.end.position = pose.position + linear * dt;
  const Vec3 turn = angular * dt;
  const Real angle = glm::length(turn);
  if (angle > Real(0)) {
    const Quat step = glm::angleAxis(angle, turn / angle);
    m.end.rotation = glm::normalize(step * pose.rotation);
  }
  return m;
}

Transform Motion::at(Real t) const {
  Transform r;
  r.position = start.position + t * (end.position - start.position);
  r.rotation = glm::normalize(glm::slerp(start.rotation, end.rotation, t));
  return r;
}

Real Motion::rotation_angle() const {
  const Quat rel = glm::conjugate(start.rotation) * end.rotation;
  const Real v = std::sqrt(rel.x * rel.x + rel.y * rel.y + rel.z * rel.z);
  return Real(2) * std::atan2(v, std::abs(rel.w));
}

bool Motion::is_translation() const {
  const Quat& a = start.rotation;
  const Quat& b = end.rotation;
  return (a.w == b.w && a.x == b.x && a.y == b.y && a.z == b.z) ||
         (a.w == -b.w && a.x == -b.x && a.y == -b.y && a.z == -b.z);
}

Vec3 Motion::angular_velocity() const {
  if (is_translation()) return Vec3(Real(0));
  // World-frame rotation from start to end, on the shortest arc (w >= 0).
  Quat rel = end.rotation * glm::conjugate(start.rotation);
  if (rel.w < Real(0)) rel = -rel;
  const Vec3 axis(rel.x, rel.y, rel.z);
  const Real s = glm::length(axis);
  if (!(s > Real(0))) return Vec3(Real(0));
  const Real angle = Real(2) * std::atan2(s, rel.w);
  return axis * (angle / s);
}

std::optional<Error> validate_motion(const Motion& motion, std::string_view name) {
  if (validate::is_acceptable(motion.start.position) && validate::is_acceptable(motion.end.position) &&
      validate::is_unit(motion.start.rotation) && validate::is_unit(motion.end.rotation)) {
    return std::nullopt;  // the usual case: no field names built
  }
  const std::string n(name);
  if (auto e = validate::finite(motion.start.position, n + ".start.position")) return e;
  if (auto e = validate::unit_quaternion(motion.start.rotation, n + ".start.rotation")) return e;
  if (auto e = validate::finite(motion.end.position, n + ".end.position")) return e;
  if (auto e = validate::unit_quaternion(motion.end.rotation, n + ".end.rotation")) return e;
  return std::nullopt;
}

Real directional_speed_bound(const Vec3& n, const Vec3& linear, const Vec3& angular, Real radius) {
  const Real turn = glm::length(glm::cross(n, angular));
  const Real rotational = turn > Real(0) ? turn * radius : Real(0);
  return glm::dot(n, linear) + rotational;
}

}  // namespace proxima
