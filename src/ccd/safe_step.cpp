// Safe time step from the current distance and the directional motion bound.
//
// Steps (the bound of motion.hpp; Mirtich 1996, ch. 3, for conservative advancement):
//  1. One narrow-phase distance query gives the distance d (an upper bound) and the normal
//     n from A to B; for two bounded convex shapes the gap along n from one support call
//     per shape, g <= distance, replaces d (a proved lower bound), otherwise d less the
//     narrow phase's error is used.
//  2. mu = n.(v_a - v_b) + |n x w_a| r_a + |n x w_b| r_b bounds how fast that gap closes at
//     every future time (constant velocities); dt = (gap - target) / mu.
//  3. The directional bound needs a gap that bounds the distance at every time: two convex
//     shapes, or a still (or translating) half-space's plane against anything. Meshes,
//     compounds and turning half-spaces use the Lipschitz bound |v_a - v_b| + |w| R of the
//     distance itself.

#include <proxima/ccd/motion.hpp>
#include <proxima/ccd/safe_step.hpp>
#include <proxima/core/tolerance.hpp>
#include <proxima/core/validate.hpp>
#include <proxima/narrowphase/narrowphase.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "ccd/shape_radii.hpp"

namespace proxima {

namespace {

std::optional<Error> validate_body(const MovingBody& body, const std::string& name) {
  if (validate::is_acceptable(body.pose.position) && validate::is_unit(body.pose.rotation) &&
      validate::is_acceptable(body.linear) && validate::is_acceptable(body.angular)) {
    return std::nullopt;
  }
  if (auto e = validate::finite(body.pose.position, name + ".pose.position")) return e;
  if (auto e = validate::unit_quaternion(body.pose.rotation, name + ".pose.rotation")) return e;
  if (auto e = validate::finite(body.linear, name + ".linear")) return e;
  return validate::finite(body.angular, name + ".angular");
}

Real rotating(const Vec3& w, Real radius) {
  const Real speed = glm::length(w);
  return speed > Real(0) ? speed * radius : Real(0);
}

// The step of one validated pair.
Real pair_step(const MovingBody& a, const MovingBody& b, Real target) {
  const DistanceResult d = distance(a.shape, a.pose, b.shape, b.pose);
  if (!std::isfinite(d.signed_distance)) return d.signed_distance > Real(0) ? kRealInfinity : Real(0);
  const detail::ShapeRadii ra = detail::shape_radii(a.shape), rb = detail::shape_radii(b.shape);
  const Real scale = std::max({Real(1), glm::length(a.pose.position - b.pose.position) +
                                            (ra.halfspace ? Real(0) : ra.full) + (rb.halfspace ? Real(0) : rb.full)});
  const Vec3 n = d.normal;
  if (ra.convex && rb.convex) {
    const Real g = glm::dot(n, detail::world_support(b.shape, b.pose, -n)) -
                   glm::dot(n, detail::world_support(a.shape, a.pose, n));
    return safe_time_step_from_distance(g, n, a.linear, a.angular, ra.core, b.linear, b.angular, rb.core, target);
  }
  const Real lower = d.signed_distance - Real(16) * kEpsilon * scale - Real(8) * kEpsilon * std::abs(d.signed_distance);
  // A still or translating half-space keeps its plane, the exact projection of its solid on
  // the normal: the directional bound holds against any other shape.
  const bool plane_a = ra.halfspace && !(glm::length(a.angular) > Real(0));
  const bool plane_b = rb.halfspace && !(glm::length(b.angular) > Real(0));
  if ((plane_a && !rb.halfspace) || (plane_b && !ra.halfspace)) {
    const Real core_a = ra.halfspace ? Real(0) : ra.full, core_b = rb.halfspace ? Real(0) : rb.full;
    return safe_time_step_from_distance(lower, n, a.linear, a.angular, core_a, b.linear, b.angular, core_b, target);
  }
  // Otherwise (a mesh, a compound, a turning half-space) only the Lipschitz bound of the
  // distance holds: no point approaches faster than |v_a - v_b| + |w_a| R_a + |w_b| R_b, with
  // R for a half-space the farthest point of the other shape from its origin.
  const Real reach = glm::length(a.pose.position - b.pose.position);
  const Real lip_a = ra.halfspace ? reach + rb.full : ra.full;
  const Real lip_b = rb.halfspace ? reach + ra.full : rb.full;
  const Real speed = glm::length(a.linear - b.linear) + rotating(a.angular, lip_a) + rotating(b.angular, lip_b);
  if (!(lower > target)) return Real(0);
  return speed > Real(0) ? (lower - target) / speed : kRealInfinity;
}

}  // namespace

Real safe_time_step_from_distance(Real gap, const Vec3& n, const Vec3& linear_a, const Vec3& angular_a, Real radius_a,
                                  const Vec3& linear_b, const Vec3& angular_b, Real radius_b, Real target_distance) {
  if (!(gap > target_distance)) return Real(0);
  const Real mu = directional_speed_bound(n, linear_a - linear_b, angular_a, radius_a) +
                  directional_speed_bound(n, Vec3(Real(0)), angular_b, radius_b);
  return mu > Real(0) ? (gap - target_distance) / mu : kRealInfinity;
}

Real rotation_radius(ShapeRef shape) { return detail::shape_radii(shape).core; }

Result<Real> safe_time_step(const MovingBody& a, const MovingBody& b, Real target_distance) {
  if (auto e = validate_body(a, "a")) return *e;
  if (auto e = validate_body(b, "b")) return *e;
  if (!(target_distance >= Real(0) && target_distance <= kMaxCoordinate)) {
    if (auto e = validate::non_negative(target_distance, "target_distance")) return *e;
  }
  return pair_step(a, b, target_distance);
}

Result<Real> safe_time_steps(const MovingBody& a, std::span<const MovingBody> others, std::span<Real> steps,
                             Real target_distance) {
  if (auto e = validate_body(a, "a")) return *e;
  for (std::size_t i = 0; i < others.size(); ++i) {
    if (auto e = validate_body(others[i], "others[" + std::to_string(i) + "]")) return *e;
  }
  if (auto e = validate::non_negative(target_distance, "target_distance")) return *e;
  if (steps.size() != others.size()) {
    return make_error(ErrorCode::InvalidArgument, "steps", "must have one entry per body of others");
  }
  Real least = kRealInfinity;
  for (std::size_t i = 0; i < others.size(); ++i) {
    steps[i] = pair_step(a, others[i], target_distance);
    least = std::min(least, steps[i]);
  }
  return least;
}

}  // namespace proxima
