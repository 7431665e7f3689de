#pragma once
/// @file ray.hpp
/// Ray and RayHit, the input and output of every ray cast (primitives, shapes, later
/// meshes and the world).
///
/// Convention: the ray is the set of points origin + t * direction with 0 <= t <= max_t.
/// `direction` need not be unit: t is measured in units of |direction| (so a segment from
/// p to q is the ray {p, q - p} with max_t = 1). A ray whose origin is inside a solid
/// reports a hit at t = 0 with point = origin and normal = -direction / |direction|.
/// A zero direction hits only when the origin is inside (t = 0).

#include <proxima/core/math.hpp>
#include <proxima/core/sub_shape_id.hpp>
#include <proxima/core/transform.hpp>

#include <optional>

namespace proxima {

/// A ray (or, with max_t = 1 and direction = q - p, the segment pq).
struct Ray {
  Vec3 origin{Real(0)};     ///< start point
  Vec3 direction{Real(0)};  ///< direction; t is in units of its length

  /// The point at parameter t.
  Vec3 at(Real t) const { return origin + t * direction; }
  /// The ray expressed in the local frame of `pose` (for casting against a placed shape).
  Ray to_local(const Transform& pose) const {
    return {pose.inverse_apply(origin), pose.inverse_apply_vector(direction)};
  }
};

/// The first intersection of a ray with a surface.
struct RayHit {
  Real t = Real(0);      ///< ray parameter of the hit, in [0, max_t]
  Vec3 point{Real(0)};   ///< hit point = origin + t * direction
  Vec3 normal{Real(0)};  ///< unit normal at the hit: outward for solids; for surfaces without
                         ///< interior (triangle, plane) the face normal turned to face the ray
  SubShapeId sub{};      ///< the mesh triangle / compound child hit (kNoIndex for a convex shape)

  /// The hit expressed in the parent frame of `pose` (t unchanged).
  RayHit to_world(const Transform& pose) const { return {t, pose.apply(point), pose.apply_vector(normal), sub}; }
};

}  // namespace proxima
