// Segment: the line segment ab as a shape without interior.
//
// Steps:
//  - support: the end point with the larger projection on the direction;
//  - contains / closest point: geometry::closest_point_segment (Ericson, Real-Time
//    Collision Detection, 5.1.2), then the distance compared with the segment's tolerance;
//  - ray cast: closest points of the ray (parameter clamped to [0, max_t]) and the segment,
//    Ericson's clamped line-line solution (5.1.9) written with unit directions so that an
//    unbounded max_t or a huge direction never overflows; a ray running along the segment
//    (both end points within tolerance of its line) hits where it enters the segment.
//    A hit is a pass within the tolerance of the segment or of the ray's coordinates.
#include <proxima/core/tolerance.hpp>
#include <proxima/core/validate.hpp>
#include <proxima/geometry/closest_points.hpp>
#include <proxima/shapes/segment.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace proxima {
namespace {

// Unit vector orthogonal to the unit vector `axis`.
Vec3 any_orthogonal(const Vec3& axis) {
  Vec3 t1;
  Vec3 t2;
  orthonormal_basis(axis, t1, t2);
  return glm::normalize(t1);
}

}  // namespace

Result<Segment> Segment::create(const Vec3& a, const Vec3& b) {
  if (auto e = validate::finite(a, "a")) return *e;
  if (auto e = validate::finite(b, "b")) return *e;
  const Real scale = std::max(max_abs_component(a), max_abs_component(b));
  const Real min_length = kRelativeTolerance * scale;
  const Vec3 e = b - a;
  if (!(glm::dot(e, e) > min_length * min_length) || !(glm::dot(e, e) > Real(0))) {
    return make_error(ErrorCode::Degenerate, "b", "coincides with a (the segment has no length)");
  }
  return Segment(a, b, linear_tolerance(scale));
}

Vec3 Segment::support(const Vec3& direction) const {
  return glm::dot(b_, direction) > glm::dot(a_, direction) ? b_ : a_;
}

Aabb Segment::local_aabb() const { return {min(a_, b_), max(a_, b_)}; }

Aabb Segment::world_aabb(const Transform& pose) const {
  const Vec3 wa = pose.apply(a_);
  const Vec3 wb = pose.apply(b_);
  return {min(wa, wb), max(wa, wb)};
}

std::optional<RayHit> Segment::raycast(const Ray& ray, Real max_t) const {
  if (!(max_t >= Real(0)) || !is_finite(ray.origin) || !is_finite(ray.direction)) return std::nullopt;
  const Real tol = std::max(tolerance_, linear_tolerance(max_abs_component(ray.origin)));
  Vec3 w(Real(0), Real(0), Real(1));
  Real seg_len = Real(0);
  unit_and_length(b_ - a_, w, seg_len);  // never zero: checked at construction
  Vec3 u;
  Real len = Real(0);
  if (!unit_and_length(ray.direction, u, len)) {
    const auto q = geometry::closest_point_segment(ray.origin, a_, b_);
    if (glm::length(ray.origin - q.point) > tol) return std::nullopt;
    return RayHit{Real(0), ray.origin, any_orthogonal(w)};
  }
  // Ray parameter s measured in length along u, limited to [0, s_max].
  const Real s_max = max_t > Real(0) ? max_t * len : Real(0);
  const Vec3 r = ray.origin - a_;
  const Real c = glm::dot(u, r);  // ray origin's coordinate along u, relative to a
  const Real cos_angle = glm::dot(u, w);
  const Real f = glm::dot(w, r);  // ray origin's coordinate along w, relative to a
  // Perpendicular offsets of the end points from the ray's line.
  const Vec3 oa = a_ - ray.origin;
  const Vec3 ob = b_ - ray.origin;
  const Real sa = glm::dot(oa, u);
  const Real sb = glm::dot(ob, u);
  const bool along = glm::length(oa - sa * u) <= tol && glm::length(ob - sb * u) <= tol;
  Real s = Real(0);
  Vec3 normal = -u;
  if (along) {
    const Real s0 = std::min(sa, sb);
    const Real s1 = std::max(sa, sb);
    if (s1 < Real(0) || s0 > s_max) return std::nullopt;
    s = std::max(s0, Real(0));
  } else {
    const Real denom = Real(1) - cos_angle * cos_angle;
    s = denom > Real(0) ? (cos_angle * f - c) / denom : Real(0);
    s = std::min(std::max(s, Real(0)), s_max);
    // Clamp the segment parameter t = f + cos_angle * s to [0, seg_len], then re-solve s.
    const Real t = f + cos_angle * s;
    if (t < Real(0)) {
      s = std::min(std::max(-c, Real(0)), s_max);
    } else if (t > seg_len) {
      s = std::min(std::max(cos_angle * seg_len - c, Real(0)), s_max);
    }
    const Vec3 on_ray = ray.origin + s * u;
    const auto q = geometry::closest_point_segment(on_ray, a_, b_);
    if (glm::length(on_ray - q.point) > tol) return std::nullopt;
    // The part of -u orthogonal to the segment, projected twice so that rounding leaves no
    // component along w even for nearly parallel rays.
    Vec3 across = -(u - cos_angle * w);
    across -= glm::dot(across, w) * w;
    Vec3 unit_across;
    Real across_len = Real(0);
    if (unit_and_length(across, unit_across, across_len)) normal = unit_across;
  }
  const Real t_hit = std::min(s / len, max_t);
  return RayHit{t_hit, ray.at(t_hit), normal};
}

bool Segment::contains(const Vec3& point) const {
  if (!is_finite(point)) return false;
  const auto q = geometry::closest_point_segment(point, a_, b_);
  return glm::length(point - q.point) <= tolerance_;
}

SurfacePoint Segment::closest_point(const Vec3& point) const {
  if (!is_finite(point)) {
    Vec3 w(Real(0), Real(0), Real(1));
    Real len = Real(0);
    unit_and_length(b_ - a_, w, len);
    return SurfacePoint{a_, any_orthogonal(w), std::numeric_limits<Real>::infinity()};
  }
  const auto q = geometry::closest_point_segment(point, a_, b_);
  SurfacePoint r;
  r.point = q.point;
  Vec3 unit;
  Real dist = Real(0);
  if (unit_and_length(point - q.point, unit, dist) && dist > tolerance_) {
    r.normal = unit;
  } else {
    Vec3 w(Real(0), Real(0), Real(1));
    Real len = Real(0);
    unit_and_length(b_ - a_, w, len);
    // Keep the direction towards the point when it is still meaningful.
    const Vec3 across = (point - q.point) - glm::dot(point - q.point, w) * w;
    Vec3 unit_across;
    Real across_len = Real(0);
    r.normal = unit_and_length(across, unit_across, across_len) ? unit_across : any_orthogonal(w);
  }
  r.signed_distance = dist;
  return r;
}

MassProperties Segment::mass_properties(Real /*density*/) const {
  MassProperties m;
  m.centroid = (a_ + b_) * Real(0.5);
  return m;
}

}  // namespace proxima
