/// @file core_queries.cpp
/// Ray casts, containment and closest points of rounded 2D cores and chain segments.
///
/// Steps (Ericson, Real-Time Collision Detection §5.1.2, §5.3.2, §5.3.8):
///   - containment and closest point: inside a polygon core the nearest edge line decides;
///     outside, the nearest point of the core's edges; the radius then moves the answer out;
///   - ray cast: a rounded core is the union of its offset edges' band and a disc at each
///     vertex, so the first entry along the ray is the earliest crossing among the offset
///     edges (crossed against their normal) and the vertex circles; an unrounded polygon is
///     clipped by its edge lines (Cyrus–Beck); an origin inside answers t = 0.

#include <proxima/d2/convex_queries.hpp>

#include <cmath>

namespace proxima::d2 {
namespace {

/// The nearest point of segment (p, q) to x.
Vec2 closest_on_segment(const Vec2& p, const Vec2& q, const Vec2& x) {
  const Vec2 e = q - p;
  const Real ee = glm::dot(e, e);
  const Real t = ee > Real(0) ? std::clamp(glm::dot(x - p, e) / ee, Real(0), Real(1)) : Real(0);
  return p + t * e;
}

/// Surface point in the core's local frame.
SurfacePoint local_closest_point(const ConvexCore& core, const Vec2& q) {
  SurfacePoint out;
  if (core.count >= 3) {  // inside the polygon core: the nearest edge line
    int edge = 0;
    Real best = -std::numeric_limits<Real>::infinity();
    for (int i = 0; i < core.count; ++i) {
      const Real s = glm::dot(core.normals[i], q - core.vertices[i]);
      if (s > best) best = s, edge = i;
    }
    if (best <= Real(0)) {
      out.normal = core.normals[edge];
      out.point = q + (core.radius - best) * out.normal;
      out.signed_distance = best - core.radius;
      return out;
    }
  }
  Vec2 nearest = core.vertices[0];
  int nearest_edge = 0;
  const int edges = core.count == 1 ? 0 : (core.count == 2 ? 1 : core.count);
  for (int i = 0; i < edges; ++i) {
    const Vec2 p = closest_on_segment(core.vertices[i], core.vertices[(i + 1) % core.count], q);
    if (length_squared(q - p) < length_squared(q - nearest) || i == 0) nearest = p, nearest_edge = i;
  }
  Vec2 n;
  Real d;
  if (!unit_and_length(q - nearest, n, d)) {  // on the core's boundary (or its point)
    n = core.count >= 2 ? core.normals[nearest_edge] : Vec2(Real(1), Real(0));
    d = Real(0);
  }
  out.normal = n;
  out.point = nearest + core.radius * n;
  out.signed_distance = d - core.radius;
  return out;
}

/// Parameter at which the ray enters the circle (c, r) from outside, or a negative value.
Real ray_circle_entry(const Vec2& o, const Vec2& d, const Vec2& c, Real r) {
  const Vec2 m = o - c;
  const Real b = glm::dot(m, d), cc = glm::dot(m, m) - r * r, dd = glm::dot(d, d);
  if (cc > Real(0) && b > Real(0)) return Real(-1);
  const Real disc = b * b - dd * cc;
  if (disc < Real(0)) return Real(-1);
  return (-b - std::sqrt(disc)) / dd;
}

/// Parameter at which the ray crosses segment (p, q) against normal n, or a negative value.
Real ray_segment_crossing(const Vec2& o, const Vec2& d, const Vec2& p, const Vec2& q, const Vec2& n) {
  const Real den = glm::dot(n, d);
  if (!(den < Real(0))) return Real(-1);
  const Real t = glm::dot(n, p - o) / den;
  if (t < Real(0)) return Real(-1);
  const Vec2 e = q - p;
  const Real s = glm::dot(o + t * d - p, e);
  return s >= Real(0) && s <= glm::dot(e, e) ? t : Real(-1);
}

struct LocalHit {
  Real t = std::numeric_limits<Real>::infinity();
  Vec2 normal{Real(1), Real(0)};
  void offer(Real candidate, const Vec2& n) {
    if (candidate >= Real(0) && candidate < t) t = candidate, normal = n;
  }
};

/// Cyrus–Beck clipping of the ray by an unrounded polygon core (origin outside).
LocalHit ray_polygon(const ConvexCore& core, const Vec2& o, const Vec2& d, Real max_t) {
  Real enter = Real(0), exit = max_t;
  Vec2 normal(Real(1), Real(0));
  bool entered = false;
  for (int i = 0; i < core.count; ++i) {
    const Real num = glm::dot(core.normals[i], core.vertices[i] - o);
    const Real den = glm::dot(core.normals[i], d);
    if (den == Real(0)) {
      if (num < Real(0)) return {};
      continue;
    }
    const Real t = num / den;
    if (den < Real(0)) {
      if (t >= enter) enter = t, normal = core.normals[i], entered = true;
    } else {
      exit = std::min(exit, t);
    }
    if (enter > exit) return {};
  }
  LocalHit hit;
  if (entered) hit.offer(enter, normal);
  return hit;
}

LocalHit local_raycast(const ConvexCore& core, const Vec2& o, const Vec2& d, Real max_t) {
  if (core.count >= 3 && core.radius == Real(0)) return ray_polygon(core, o, d, max_t);
  LocalHit hit;
  if (core.count == 1 && core.radius == Real(0)) {  // a point: hit only when on the ray
    const Vec2 m = core.vertices[0] - o;
    const Real t = glm::dot(m, d) / glm::dot(d, d);
    if (cross(d, m) == Real(0) && t >= Real(0)) hit.offer(t, -glm::normalize(d));
    return hit;
  }
  const int edges = core.count == 1 ? 0 : core.count;
  for (int i = 0; i < edges; ++i) {
    const Vec2 offset = core.radius * core.normals[i];
    const Vec2 n = core.normals[i];
    hit.offer(ray_segment_crossing(o, d, core.vertices[i] + offset, core.vertices[(i + 1) % core.count] + offset, n),
              n);
  }
  if (core.radius > Real(0)) {
    for (int i = 0; i < core.count; ++i) {
      const Real t = ray_circle_entry(o, d, core.vertices[i], core.radius);
      if (t >= Real(0) && t < hit.t) hit.offer(t, glm::normalize(o + t * d - core.vertices[i]));
    }
  }
  return hit;
}

bool valid_ray(const Ray& ray, Real max_t) {
  return is_finite(ray.origin) && is_finite(ray.direction) && max_t >= Real(0) &&
         length_squared(ray.direction) > Real(0) && std::isfinite(length_squared(ray.direction));
}

}  // namespace

SurfacePoint core_closest_point(const ConvexCore& core, const Pose& pose, const Vec2& point) {
  SurfacePoint s = local_closest_point(core, pose.inverse_apply(point));
  s.point = pose.apply(s.point);
  s.normal = pose.apply_vector(s.normal);
  return s;
}

bool core_contains(const ConvexCore& core, const Pose& pose, const Vec2& point) {
  if (!is_finite(point)) return false;
  return local_closest_point(core, pose.inverse_apply(point)).signed_distance <= Real(0);
}

std::optional<RayHit> core_raycast(const ConvexCore& core, const Pose& pose, const Ray& ray, Real max_t) {
  if (!valid_ray(ray, max_t)) return std::nullopt;
  const Vec2 o = pose.inverse_apply(ray.origin);
  const Vec2 d = pose.inverse_apply_vector(ray.direction);
  if (local_closest_point(core, o).signed_distance <= Real(0)) {
    return RayHit{Real(0), ray.origin, -glm::normalize(ray.direction)};
  }
  const LocalHit hit = local_raycast(core, o, d, max_t);
  if (!(hit.t <= max_t)) return std::nullopt;
  return RayHit{hit.t, ray.at(hit.t), pose.apply_vector(hit.normal)};
}

std::optional<RayHit> chain_segment_raycast(const ChainSegment& segment, const Pose& pose, const Ray& ray, Real max_t) {
  if (!valid_ray(ray, max_t)) return std::nullopt;
  const Vec2 o = pose.inverse_apply(ray.origin);
  const Vec2 d = pose.inverse_apply_vector(ray.direction);
  const Vec2 n = segment.normal();
  const Real t = ray_segment_crossing(o, d, segment.a, segment.b, n);
  if (t < Real(0) || t > max_t) return std::nullopt;
  return RayHit{t, ray.at(t), pose.apply_vector(n)};
}

}  // namespace proxima::d2
