// Ray, segment and plane queries on bounding volumes.
//
// Steps:
//  - Plane side: the volume's projection interval on the normal (support in +n and -n)
//    compared with the offset.
//  - Rays against slab volumes (Aabb, Obb, k-DOP): the slab method — intersect the
//    parameter intervals in which the ray lies inside each slab; a ray parallel to a slab
//    (zero denominator) is inside it for all t or for none, so no 0 * inf is formed
//    (Kay and Kajiya, SIGGRAPH 1986; Ericson, Real-Time Collision Detection, 5.3.3).
//  - Ray against a ball: the cancellation-safe quadratic (roots as c / (-b + sqrt(disc))).
//  - Ray against a capsule: the capsule is the union of its cylinder body (an infinite
//    cylinder clipped to the segment's slab) and two end balls; the entry into a union is
//    the earliest entry into any part (Ericson 5.3.7 for the cylinder quadratic).
//  - Ray against a hull: ConvexHull::raycast (Cyrus-Beck clipping).
// The entry parameter is clamped to 0 when the origin is inside, following ray.hpp.
#include <proxima/bounds/volume_queries.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace proxima {
namespace {

// Interval [t0, t1] (double) of the ray inside {lo <= d . x <= hi}; false when empty.
struct Clip {
  double t0;
  double t1;
};

bool clip_slab(Clip& c, double origin_proj, double dir_proj, double lo, double hi) {
  if (dir_proj == 0.0) return origin_proj >= lo && origin_proj <= hi;
  double ta = (lo - origin_proj) / dir_proj;
  double tb = (hi - origin_proj) / dir_proj;
  if (ta > tb) std::swap(ta, tb);
  c.t0 = std::max(c.t0, ta);
  c.t1 = std::min(c.t1, tb);
  return c.t0 <= c.t1;
}

std::optional<Real> finish(const Clip& c) {
  if (!(c.t0 <= c.t1)) return std::nullopt;
  return Real(c.t0);
}

// Entry interval of the ball {|x - center| <= r} along the ray (double), intersected
// with [0, max_t].
bool ball_interval(const glm::dvec3& m, const glm::dvec3& d, double r, double max_t, Clip& c) {
  // |m + t d|^2 <= r^2: a t^2 + 2 b t + cc <= 0.
  const double a = glm::dot(d, d);
  const double b = glm::dot(m, d);
  const double cc = glm::dot(m, m) - r * r;
  c = {0.0, max_t};
  if (a == 0.0) return cc <= 0.0;
  const double disc = b * b - a * cc;
  if (disc < 0.0) return false;
  const double s = std::sqrt(disc);
  // Roots t = (-b -+ s) / a, written without cancellation.
  const double q = -(b + std::copysign(s, b));
  double t_lo, t_hi;
  if (q != 0.0) {
    const double r1 = q / a;
    const double r2 = cc / q;
    t_lo = std::min(r1, r2);
    t_hi = std::max(r1, r2);
  } else {
    t_lo = t_hi = 0.0;
  }
  c.t0 = std::max(c.t0, t_lo);
  c.t1 = std::min(c.t1, t_hi);
  return c.t0 <= c.t1;
}

}  // namespace

Interval projection_interval(const Aabb& volume, const Vec3& axis) {
  const Vec3 c = volume.max * Real(0.5) + volume.min * Real(0.5);
  const Vec3 h = volume.max * Real(0.5) - volume.min * Real(0.5);
  const Real center = glm::dot(c, axis);
  const Real r = h.x * std::abs(axis.x) + h.y * std::abs(axis.y) + h.z * std::abs(axis.z);
  return {center - r, center + r};
}

Interval projection_interval(const BoundingSphere& volume, const Vec3& axis) {
  const Real center = glm::dot(volume.center, axis);
  const Real r = volume.radius * glm::length(axis);
  return {center - r, center + r};
}

Interval projection_interval(const Obb& volume, const Vec3& axis) {
  const Real center = glm::dot(volume.center, axis);
  Real r = Real(0);
  for (int i = 0; i < 3; ++i) r += volume.half_extents[i] * std::abs(glm::dot(volume.axes[i], axis));
  return {center - r, center + r};
}

Interval projection_interval(const BoundingCapsule& volume, const Vec3& axis) {
  const Real a = glm::dot(volume.p0, axis);
  const Real b = glm::dot(volume.p1, axis);
  const Real r = volume.radius * glm::length(axis);
  return {std::min(a, b) - r, std::max(a, b) + r};
}

template <int K>
Interval projection_interval(const Kdop<K>& volume, const Vec3& axis) {
  const std::vector<Vec3> v = volume.vertices();
  if (v.empty()) return {kRealMax, -kRealMax};
  Interval r{kRealMax, -kRealMax};
  for (const Vec3& p : v) {
    const Real s = glm::dot(p, axis);
    r.lo = std::min(r.lo, s);
    r.hi = std::max(r.hi, s);
  }
  return r;
}

Interval projection_interval(const ConvexHull& volume, const Vec3& axis) {
  Interval r{kRealMax, -kRealMax};
  for (const Vec3& p : volume.vertices()) {
    const Real s = glm::dot(p, axis);
    r.lo = std::min(r.lo, s);
    r.hi = std::max(r.hi, s);
  }
  return r;
}

std::optional<Real> ray_entry(const Aabb& volume, const Ray& ray, Real max_t) {
  if (!volume.is_valid() || !(max_t >= Real(0))) return std::nullopt;
  Clip c{0.0, double(max_t)};
  for (int i = 0; i < 3; ++i) {
    if (!clip_slab(c, double(ray.origin[i]), double(ray.direction[i]), double(volume.min[i]), double(volume.max[i]))) {
      return std::nullopt;
    }
  }
  return finish(c);
}

std::optional<Real> ray_entry(const BoundingSphere& volume, const Ray& ray, Real max_t) {
  if (!(max_t >= Real(0))) return std::nullopt;
  Clip c{};
  const glm::dvec3 m = glm::dvec3(ray.origin) - glm::dvec3(volume.center);
  if (!ball_interval(m, glm::dvec3(ray.direction), double(volume.radius), double(max_t), c)) return std::nullopt;
  return finish(c);
}

std::optional<Real> ray_entry(const Obb& volume, const Ray& ray, Real max_t) {
  if (!(max_t >= Real(0))) return std::nullopt;
  Clip c{0.0, double(max_t)};
  const glm::dvec3 m = glm::dvec3(ray.origin) - glm::dvec3(volume.center);
  const glm::dvec3 d(ray.direction);
  for (int i = 0; i < 3; ++i) {
    const glm::dvec3 axis(volume.axes[i]);
    const double h = double(volume.half_extents[i]);
    if (!clip_slab(c, glm::dot(m, axis), glm::dot(d, axis), -h, h)) return std::nullopt;
  }
  return finish(c);
}

std::optional<Real> ray_entry(const BoundingCapsule& volume, const Ray& ray, Real max_t) {
  if (!(max_t >= Real(0))) return std::nullopt;
  const glm::dvec3 p0(volume.p0);
  const glm::dvec3 u = glm::dvec3(volume.p1) - p0;
  const glm::dvec3 m = glm::dvec3(ray.origin) - p0;
  const glm::dvec3 d(ray.direction);
  const double r = double(volume.radius);
  double best = std::numeric_limits<double>::infinity();
  Clip c{};
  if (ball_interval(m, d, r, double(max_t), c)) best = std::min(best, c.t0);
  if (ball_interval(m - u, d, r, double(max_t), c)) best = std::min(best, c.t0);
  const double uu = glm::dot(u, u);
  if (uu > 0.0) {
    // Body: the infinite cylinder around the axis, clipped to 0 <= (x - p0) . u <= |u|^2.
    Clip body{0.0, double(max_t)};
    bool hit = clip_slab(body, glm::dot(m, u), glm::dot(d, u), 0.0, uu);
    if (hit) {
      const glm::dvec3 mp = m - (glm::dot(m, u) / uu) * u;
      const glm::dvec3 dp = d - (glm::dot(d, u) / uu) * u;
      Clip cyl{};
      hit = ball_interval(mp, dp, r, double(max_t), cyl);
      if (hit) {
        body.t0 = std::max(body.t0, cyl.t0);
        body.t1 = std::min(body.t1, cyl.t1);
        if (body.t0 <= body.t1) best = std::min(best, body.t0);
      }
    }
  }
  if (!(best <= double(max_t))) return std::nullopt;
  return Real(best);
}

template <int K>
std::optional<Real> ray_entry(const Kdop<K>& volume, const Ray& ray, Real max_t) {
  if (!(max_t >= Real(0))) return std::nullopt;
  Clip c{0.0, double(max_t)};
  // Work relative to the centre of the axis slabs for precision far from the origin.
  const glm::dvec3 center(0.5 * double(volume.min[0]) + 0.5 * double(volume.max[0]),
                          0.5 * double(volume.min[1]) + 0.5 * double(volume.max[1]),
                          0.5 * double(volume.min[2]) + 0.5 * double(volume.max[2]));
  const glm::dvec3 m = glm::dvec3(ray.origin) - center;
  const glm::dvec3 d(ray.direction);
  for (int i = 0; i < K / 2; ++i) {
    if (!(volume.min[i] <= volume.max[i])) return std::nullopt;
    const glm::dvec3 n(Kdop<K>::direction(i));
    const double shift = glm::dot(n, center);
    if (!clip_slab(c, glm::dot(n, m), glm::dot(n, d), double(volume.min[i]) - shift, double(volume.max[i]) - shift)) {
      return std::nullopt;
    }
  }
  return finish(c);
}

std::optional<Real> ray_entry(const ConvexHull& volume, const Ray& ray, Real max_t) {
  if (!(max_t >= Real(0))) return std::nullopt;
  const auto hit = volume.raycast(ray, max_t);
  if (!hit) return std::nullopt;
  return hit->t;
}

#define PROXIMA_INSTANTIATE_KDOP_QUERIES(K)                              \
  template Interval projection_interval<K>(const Kdop<K>&, const Vec3&); \
  template std::optional<Real> ray_entry<K>(const Kdop<K>&, const Ray&, Real);

PROXIMA_INSTANTIATE_KDOP_QUERIES(6)
PROXIMA_INSTANTIATE_KDOP_QUERIES(14)
PROXIMA_INSTANTIATE_KDOP_QUERIES(18)
PROXIMA_INSTANTIATE_KDOP_QUERIES(26)
#undef PROXIMA_INSTANTIATE_KDOP_QUERIES

}  // namespace proxima
