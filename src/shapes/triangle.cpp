// Triangle: a two-sided flat triangle as a shape without interior.
//
// Steps:
//  - construction: the normal is (b - a) x (c - a), rescaled by its largest component
//    before normalising so that tiny and huge triangles neither underflow nor overflow; a
//    cross product shorter than kRelativeTolerance times the longest edge squared (the
//    sine of the flattest angle below ~1e-5 in float) is rejected as degenerate;
//  - support: the vertex with the largest projection;
//  - contains / closest point: geometry::closest_point_triangle (Voronoi regions, Ericson,
//    Real-Time Collision Detection, 5.1.5), the distance compared with the tolerance;
//  - ray cast: geometry::ray_triangle (Woop, Benthin, Wald, "Watertight Ray/Triangle
//    Intersection", JCGT 2013).
#include <proxima/core/assert.hpp>
#include <proxima/core/tolerance.hpp>
#include <proxima/core/validate.hpp>
#include <proxima/geometry/closest_points.hpp>
#include <proxima/geometry/raycast.hpp>
#include <proxima/shapes/triangle.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>

namespace proxima {
Result<Triangle> Triangle::create(const Vec3& a, const Vec3& b, const Vec3& c) {
  if (auto e = validate::finite(a, "a")) return *e;
  if (auto e = validate::finite(b, "b")) return *e;
  if (auto e = validate::finite(c, "c")) return *e;
  const Vec3 e0 = b - a;
  const Vec3 e1 = c - b;
  const Vec3 e2 = a - c;
  // Longest edge, rescaled like the cross product below (both scale as length^2).
  const Real longest = std::max({glm::length(e0), glm::length(e1), glm::length(e2)});
  Vec3 normal;
  Real twice_area = Real(0);
  if (!unit_and_length(glm::cross(e0, c - a), normal, twice_area) ||
      !(twice_area > kRelativeTolerance * longest * longest)) {
    return make_error(ErrorCode::Degenerate, "vertices", "the three vertices are collinear (zero area)");
  }
  const Real scale = std::max({max_abs_component(a), max_abs_component(b), max_abs_component(c)});
  return Triangle(a, b, c, normal, linear_tolerance(scale));
}

const Vec3& Triangle::vertex(int i) const {
  PROXIMA_ASSERT(i >= 0 && i < 3);
  return v_[static_cast<std::size_t>(i) % 3];
}

Real Triangle::area() const {
  Vec3 unit;
  Real twice_area = Real(0);
  unit_and_length(glm::cross(v_[1] - v_[0], v_[2] - v_[0]), unit, twice_area);
  return Real(0.5) * twice_area;
}

Vec3 Triangle::support(const Vec3& direction) const {
  std::size_t best = 0;
  Real best_dot = glm::dot(v_[0], direction);
  for (std::size_t i = 1; i < 3; ++i) {
    const Real d = glm::dot(v_[i], direction);
    if (d > best_dot) {
      best_dot = d;
      best = i;
    }
  }
  return v_[best];
}

Aabb Triangle::local_aabb() const { return {min(min(v_[0], v_[1]), v_[2]), max(max(v_[0], v_[1]), v_[2])}; }

Aabb Triangle::world_aabb(const Transform& pose) const {
  Aabb box = Aabb::from_point(pose.apply(v_[0]));
  box.grow(pose.apply(v_[1]));
  box.grow(pose.apply(v_[2]));
  return box;
}

std::optional<RayHit> Triangle::raycast(const Ray& ray, Real max_t) const {
  if (!(max_t >= Real(0)) || !is_finite(ray.origin) || !is_finite(ray.direction)) return std::nullopt;
  return geometry::ray_triangle(ray, max_t, v_[0], v_[1], v_[2]);
}

bool Triangle::contains(const Vec3& point) const {
  if (!is_finite(point)) return false;
  const auto q = geometry::closest_point_triangle(point, v_[0], v_[1], v_[2]);
  const Vec3 d = point - q.point;
  return max_abs_component(d) <= tolerance_ && glm::length(d) <= tolerance_;
}

SurfacePoint Triangle::closest_point(const Vec3& point) const {
  if (!is_finite(point)) return SurfacePoint{v_[0], normal_, std::numeric_limits<Real>::infinity()};
  const auto q = geometry::closest_point_triangle(point, v_[0], v_[1], v_[2]);
  SurfacePoint r;
  r.point = q.point;
  const Vec3 d = point - q.point;
  Vec3 unit;
  Real dist = Real(0);
  const bool apart = unit_and_length(d, unit, dist);
  if (apart && dist > tolerance_) {
    r.normal = unit;
  } else {
    r.normal = glm::dot(d, normal_) < Real(0) ? -normal_ : normal_;
  }
  r.signed_distance = dist;
  return r;
}

MassProperties Triangle::mass_properties(Real /*density*/) const {
  MassProperties m;
  m.centroid = (v_[0] + v_[1] + v_[2]) / Real(3);
  return m;
}

}  // namespace proxima
