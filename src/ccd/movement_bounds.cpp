// Movement bounds and swept volumes of a shape moving between two poses.
//
// Steps (bounding volumes of motions as in Ericson, Real-Time Collision Detection, 2005,
// section 9.5 and 5.5; van den Bergen, Collision Detection in Interactive 3D Environments,
// 2003, section 6.1 for the sweep of a convex set as the hull of start and end):
//  1. Pure translation: every placement is the start placement shifted by t d, so the swept
//     set is the Minkowski sum of the start set and the segment [0, d]. Its box is the union
//     of the end boxes, its smallest ball the ball of the swept centre segment, and for a
//     convex set it is the hull of the start and end placements (all exact).
//  2. With rotation: every point x of the shape stays within |x| <= R of the moving origin,
//     whose path is the segment from start to end position: the box, ball and oriented box
//     of that swept ball are conservative for any rotation path.
//  3. Swept hull with rotation: sample n + 1 placements with rotation steps of at most
//     max_angle_step; between samples a point rotating by step about a fixed axis strays at
//     most R step^2 / 8 from the chord (the linear-interpolation error bound |f''| s (1 - s)
//     / 2 <= R step^2 / 8 of the arc), so growing every sampled point into a cube of that half
//     side makes the hull of the samples contain every placement.

#include <proxima/ccd/movement_bounds.hpp>
#include <proxima/core/tolerance.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

namespace proxima {

namespace {

// Rotation taking +z to the unit vector `axis`.
Quat rotation_from_z(const Vec3& axis) {
  const Real w = Real(1) + axis.z;
  if (w <= kRelativeTolerance) return Quat(Real(0), Real(1), Real(0), Real(0));  // pi about x
  return glm::normalize(Quat(w, -axis.y, axis.x, Real(0)));                      // (1 + z.a, z x a)
}

bool finite_motion(const Motion& m) {
  return is_finite(m.start.position) && is_finite(m.end.position) && is_finite(m.start.rotation) &&
         is_finite(m.end.rotation);
}

// Pads a box outward by a few ulps of its coordinates so that rounded transformed points pass.
Aabb padded(const Aabb& box) {
  Aabb r = box;
  for (int i = 0; i < 3; ++i) {
    r.min[i] = detail::pad_down(r.min[i], Real(0));
    r.max[i] = detail::pad_up(r.max[i], Real(0));
  }
  return r;
}

}  // namespace

Real radius_about_origin(const Aabb& local_box) {
  const Vec3 far = glm::max(glm::abs(local_box.min), glm::abs(local_box.max));
  return glm::length(far);
}

Aabb motion_aabb(const Aabb& local_box, const Motion& motion, Real radius) {
  if (motion.is_translation()) {
    return padded(merge(local_box.transformed(motion.start), local_box.transformed(motion.end)));
  }
  const Real r = radius >= Real(0) ? radius : radius_about_origin(local_box);
  if (!(r < kRealMax)) return {Vec3(-kRealMax), Vec3(kRealMax)};
  Aabb box = Aabb::from_point(motion.start.position);
  box.grow(motion.end.position);
  return padded(box.inflated(r));
}

BoundingSphere motion_sphere(const BoundingSphere& local_sphere, const Motion& motion) {
  BoundingSphere s;
  if (motion.is_translation()) {
    const Vec3 c0 = motion.start.apply(local_sphere.center);
    const Vec3 c1 = motion.end.apply(local_sphere.center);
    s.center = c0 * Real(0.5) + c1 * Real(0.5);
    s.radius = Real(0.5) * glm::length(c1 - c0) + local_sphere.radius;
  } else {
    s.center = motion.start.position * Real(0.5) + motion.end.position * Real(0.5);
    s.radius = Real(0.5) * glm::length(motion.displacement()) + glm::length(local_sphere.center) + local_sphere.radius;
  }
  const Real scale = max_abs_component(s.center);
  s.radius = detail::pad_up(s.radius, scale);
  return s;
}

Obb motion_obb(const Aabb& local_box, const Motion& motion, Real radius) {
  const Vec3 d = motion.displacement();
  Vec3 dir;
  Real len = Real(0);
  const bool moves = unit_and_length(d, dir, len);
  Obb best;
  if (motion.is_translation()) {
    const Mat3 rot = motion.start.rotation_matrix();
    const Vec3 h = local_box.half_extents();
    const Vec3 c0 = motion.start.apply(local_box.center());
    best.center = c0 + d * Real(0.5);
    // (A) axes of the start rotation, each grown by half the displacement along it.
    best.axes = rot;
    for (int i = 0; i < 3; ++i) best.half_extents[i] = h[i] + Real(0.5) * std::abs(glm::dot(d, rot[i]));
    if (moves) {
      // (B) first axis along the displacement; second from the box axis least aligned with it.
      int k = 0;
      for (int i = 1; i < 3; ++i) {
        if (std::abs(glm::dot(rot[i], dir)) < std::abs(glm::dot(rot[k], dir))) k = i;
      }
      const Vec3 u1 = glm::normalize(rot[k] - glm::dot(rot[k], dir) * dir);
      const Vec3 u2 = glm::cross(dir, u1);
      Obb b;
      b.center = best.center;
      b.axes = Mat3(dir, u1, u2);
      for (int j = 0; j < 3; ++j) {
        Real e = Real(0);
        for (int i = 0; i < 3; ++i) e += std::abs(glm::dot(b.axes[j], rot[i])) * h[i];
        b.half_extents[j] = e;
      }
      b.half_extents[0] += Real(0.5) * len;
      if (b.volume() < best.volume()) best = b;
    }
  } else {
    const Real r = radius >= Real(0) ? radius : radius_about_origin(local_box);
    best.center = motion.start.position * Real(0.5) + motion.end.position * Real(0.5);
    if (!(r < kRealMax)) {
      best.half_extents = Vec3(kRealMax);
      return best;
    }
    if (moves) {
      Vec3 u1;
      Vec3 u2;
      orthonormal_basis(dir, u1, u2);
      best.axes = Mat3(dir, u1, u2);
    }
    best.half_extents = Vec3(Real(0.5) * len + r, r, r);
  }
  const Real scale = max_abs_component(best.center) + max_abs_component(best.half_extents);
  for (int i = 0; i < 3; ++i) best.half_extents[i] = detail::pad_up(best.half_extents[i], scale);
  return best;
}

Result<PlacedCapsule> swept_sphere(const Vec3& from, const Vec3& to, Real radius) {
  if (!is_finite(from)) return make_error(ErrorCode::NotFinite, "from", "start centre must be finite");
  if (!is_finite(to)) return make_error(ErrorCode::NotFinite, "to", "end centre must be finite");
  Vec3 dir(Real(0), Real(0), Real(1));
  Real len = Real(0);
  if (!unit_and_length(to - from, dir, len)) {
    dir = Vec3(Real(0), Real(0), Real(1));
    len = Real(0);
  }
  Result<Capsule> capsule = Capsule::create(radius, Real(0.5) * len);
  if (!capsule) return capsule.error();
  PlacedCapsule placed{*capsule, Transform{from * Real(0.5) + to * Real(0.5), rotation_from_z(dir)}};
  return placed;
}

Result<PlacedCapsule> swept_sphere(const Sphere& sphere, const Motion& motion) {
  return swept_sphere(motion.start.position, motion.end.position, sphere.radius());
}

Result<ConvexHull> swept_hull(std::span<const Vec3> local_points, const Motion& motion, const SweepOptions& options) {
  if (!finite_motion(motion)) return make_error(ErrorCode::NotFinite, "motion", "poses must be finite");
  if (!(options.max_angle_step > Real(0)) || !std::isfinite(options.max_angle_step)) {
    return make_error(ErrorCode::OutOfRange, "options.max_angle_step", "must be finite and > 0");
  }
  std::vector<Vec3> points;
  if (motion.is_translation()) {
    points.reserve(local_points.size() * 2);
    for (const Vec3& p : local_points) {
      points.push_back(motion.start.apply(p));
      points.push_back(motion.end.apply(p));
    }
    return ConvexHull::create(points);
  }
  Real radius = Real(0);
  for (const Vec3& p : local_points) {
    if (!is_finite(p)) break;  // ConvexHull::create below names the bad point
    radius = std::max(radius, glm::length(p));
  }
  const Real angle = motion.rotation_angle();
  const int n = std::max(1, static_cast<int>(std::ceil(angle / options.max_angle_step)));
  const Real step = angle / Real(n);
  // Grow by the chord deviation bound plus a few ulps of the coordinates for rounding.
  const Real scale = max_abs_component(motion.start.position) + max_abs_component(motion.end.position) + radius;
  const Real delta = radius * step * step / Real(8) + Real(16) * kEpsilon * scale;
  points.reserve(local_points.size() * std::size_t(n + 1) * 8);
  for (int i = 0; i <= n; ++i) {
    const Transform pose = motion.at(Real(i) / Real(n));
    for (const Vec3& p : local_points) {
      const Vec3 w = pose.apply(p);
      for (int c = 0; c < 8; ++c) {
        points.push_back(w + Vec3((c & 1) ? delta : -delta, (c & 2) ? delta : -delta, (c & 4) ? delta : -delta));
      }
    }
  }
  return ConvexHull::create(points);
}

Result<ConvexHull> swept_hull(const ConvexHull& hull, const Motion& motion, const SweepOptions& options) {
  return swept_hull(hull.vertices(), motion, options);
}

Result<ConvexHull> swept_box(const Box& box, const Motion& motion, const SweepOptions& options) {
  const Vec3 h = box.half_extents();
  std::array<Vec3, 8> corners;
  for (int c = 0; c < 8; ++c)
    corners[std::size_t(c)] = Vec3((c & 1) ? h.x : -h.x, (c & 2) ? h.y : -h.y, (c & 4) ? h.z : -h.z);
  return swept_hull(corners, motion, options);
}

}  // namespace proxima
