#pragma once
/// @file placed.hpp
/// World-frame versions of the shape queries for the concrete shapes placed at a Transform
/// (constrained by the concepts of convex_shape.hpp; a mesh answers raycast, contains and
/// closest_point too). They map the input into the local frame, call the shape, and map the
/// answer back. For a shape known only at run time, shape_queries.hpp takes a ShapeRef.

#include <proxima/core/transform.hpp>
#include <proxima/geometry/ray.hpp>
#include <proxima/shapes/convex_shape.hpp>
#include <proxima/shapes/surface_point.hpp>

#include <optional>

namespace proxima {

/// Ray cast against `shape` placed at `pose`; ray and hit in world coordinates.
template <RayCastable S>
std::optional<RayHit> raycast(const S& shape, const Transform& pose, const Ray& ray, Real max_t) {
  auto hit = shape.raycast(ray.to_local(pose), max_t);
  if (!hit) return std::nullopt;
  return hit->to_world(pose);
}

/// Containment of a world point in `shape` placed at `pose`.
template <PointQueryable S>
bool contains(const S& shape, const Transform& pose, const Vec3& point) {
  return shape.contains(pose.inverse_apply(point));
}

/// Nearest surface point (world) of `shape` placed at `pose` to a world point.
template <PointQueryable S>
SurfacePoint closest_point(const S& shape, const Transform& pose, const Vec3& point) {
  SurfacePoint r = shape.closest_point(pose.inverse_apply(point));
  r.point = pose.apply(r.point);
  r.normal = pose.apply_vector(r.normal);
  return r;
}

/// World support point of `shape` placed at `pose` in world `direction`.
template <ConvexShape S>
Vec3 support(const S& shape, const Transform& pose, const Vec3& direction) {
  return pose.apply(shape.support(pose.inverse_apply_vector(direction)));
}

}  // namespace proxima
