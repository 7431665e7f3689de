// Fast bounding spheres: centroid, box centre and Ritter's growing sphere.
//
// Steps (Ritter): pick any point x, the point y farthest from x, the point z farthest
// from y; start with the sphere of diameter yz; for every point outside, move the centre
// towards it and grow the radius so that the new sphere just covers the old one and the
// point. Every result is finished by taking the radius as the largest distance from the
// chosen centre (evaluated as BoundingSphere::contains does), which never enlarges it.
// Sources: J. Ritter, "An Efficient Bounding Sphere", Graphics Gems, 1990; Ericson,
// Real-Time Collision Detection, 4.3.2.
#include <proxima/bounds/fit_sphere.hpp>

#include <glm/geometric.hpp>

#include "bounds/fit_util.hpp"

namespace proxima {

Result<BoundingSphere> fit_sphere_centroid(std::span<const Vec3> points) {
  if (auto e = detail::validate_points(points)) return *e;
  const glm::dvec3 origin(points[0]);
  glm::dvec3 sum(0.0);
  for (const Vec3& p : points) sum += glm::dvec3(p) - origin;
  return detail::finish_sphere(points, Vec3(origin + sum / static_cast<double>(points.size())));
}

Result<BoundingSphere> fit_sphere_aabb_center(std::span<const Vec3> points) {
  if (auto e = detail::validate_points(points)) return *e;
  Aabb box = Aabb::from_point(points[0]);
  for (const Vec3& p : points) box.grow(p);
  return detail::finish_sphere(points, box.max * Real(0.5) + box.min * Real(0.5));
}

Result<BoundingSphere> fit_sphere_ritter(std::span<const Vec3> points) {
  if (auto e = detail::validate_points(points)) return *e;
  const glm::dvec3 origin(points[0]);
  auto rel = [&](const Vec3& p) { return glm::dvec3(p) - origin; };
  auto farthest = [&](const glm::dvec3& from) {
    glm::dvec3 best = rel(points[0]);
    double best_d = -1.0;
    for (const Vec3& p : points) {
      const glm::dvec3 q = rel(p);
      const double d = glm::dot(q - from, q - from);
      if (d > best_d) {
        best_d = d;
        best = q;
      }
    }
    return best;
  };
  const glm::dvec3 y = farthest(glm::dvec3(0.0));
  const glm::dvec3 z = farthest(y);
  glm::dvec3 c = 0.5 * (y + z);
  double r = 0.5 * glm::length(z - y);
  for (const Vec3& p : points) {
    const glm::dvec3 q = rel(p);
    const double d = glm::length(q - c);
    if (d > r) {
      const double new_r = 0.5 * (r + d);
      c += (new_r - r) / d * (q - c);
      r = new_r;
    }
  }
  return detail::finish_sphere(points, Vec3(origin + c));
}

Result<BoundingSphere> fit_sphere(std::span<const Vec3> points, SphereFit method) {
  switch (method) {
    case SphereFit::Centroid: return fit_sphere_centroid(points);
    case SphereFit::AabbCenter: return fit_sphere_aabb_center(points);
    case SphereFit::Ritter: return fit_sphere_ritter(points);
    case SphereFit::Minimal: break;
  }
  return fit_sphere_minimal(points);
}

}  // namespace proxima
