// Ray against a solid box: axis-aligned (AABB) and oriented (OBB).
//
// Steps (slab method):
//  1. For each axis, the parameter interval where the ray lies between the two face
//     planes: t = (face - origin) / direction, divided (never multiplied by a reciprocal,
//     which could be 0 * inf = NaN for a face through the origin and a tiny direction
//     component). A zero direction component gives the whole line when the origin lies in
//     the closed slab and nothing otherwise, so a ray lying exactly in a face plane hits.
//  2. Intersect the three intervals, remembering which face bounds the entry.
//  3. Empty, or ending before 0: miss. Starting at or before 0: the origin is in every
//     closed slab, i.e. inside the box: t = 0 (the signs of (face - origin) / direction are
//     exact, so this agrees with the closed containment test). Otherwise the entry face
//     gives t and the outward normal.
//  4. OBB: the same in the box frame (origin and direction projected on the unit axes, t
//     unchanged by the rotation); the normal is the box axis of the entry face.
//
// Sources: Kay, Kajiya, "Ray Tracing Complex Scenes", SIGGRAPH 1986; Williams, Barrus,
// Morley, Shirley, "An Efficient and Robust Ray-Box Intersection Algorithm", JGT 2005;
// Ericson, Real-Time Collision Detection, 5.3.3.

#include <proxima/geometry/raycast.hpp>

#include "geometry/raycast_detail.hpp"

namespace proxima::geometry {

namespace {

/// Result of the slab method in the box's own axis-aligned frame.
struct SlabResult {
  enum class Kind { Miss, Inside, Hit } kind = Kind::Miss;  ///< what happened
  Real t = Real(0);                                         ///< entry parameter (Hit)
  int face = -1;  ///< entry face: 2 * axis for the min face, 2 * axis + 1 for the max face
};

SlabResult slabs(const Vec3& origin, const Vec3& direction, const Vec3& lo, const Vec3& hi) {
  detail::Interval span;
  for (int i = 0; i < 3; ++i) {
    span = span.clipped(detail::slab_interval(origin[i], direction[i], lo[i], hi[i], 2 * i, 2 * i + 1));
    if (span.empty()) return {};
  }
  if (span.hi < Real(0)) return {};
  if (span.lo <= Real(0)) return {SlabResult::Kind::Inside, Real(0), -1};
  return {SlabResult::Kind::Hit, span.lo, span.lo_feature};
}

/// Outward unit normal of face `face` in the box frame.
Vec3 face_normal(int face) {
  Vec3 n(Real(0));
  n[face / 2] = (face % 2) != 0 ? Real(1) : Real(-1);
  return n;
}

}  // namespace

std::optional<RayHit> ray_aabb(const Ray& ray, Real max_t, const Aabb& box) noexcept {
  detail::UnitRay r;
  if (!detail::prepare(ray, max_t, r) || !box.is_valid()) return std::nullopt;
  const SlabResult s = slabs(ray.origin, ray.direction, box.min, box.max);
  if (s.kind == SlabResult::Kind::Miss) return std::nullopt;
  if (s.kind == SlabResult::Kind::Inside) return detail::inside_hit(ray, r);
  auto hit = detail::surface_hit(ray, max_t, s.t, face_normal(s.face));
  if (!hit) return std::nullopt;
  // Put the point exactly on the box: on the entry face's plane, within the other slabs.
  const int axis = s.face / 2;
  hit->point = glm::clamp(hit->point, box.min, box.max);
  hit->point[axis] = (s.face % 2) != 0 ? box.max[axis] : box.min[axis];
  return hit;
}

std::optional<RayHit> ray_obb(const Ray& ray, Real max_t, const Vec3& center, const Mat3& axes,
                              const Vec3& half_extents) noexcept {
  detail::UnitRay r;
  if (!detail::prepare(ray, max_t, r) || !is_finite(center) || !is_finite(axes[0]) || !is_finite(axes[1]) ||
      !is_finite(axes[2]) || !is_finite(half_extents) || !(half_extents.x >= Real(0)) || !(half_extents.y >= Real(0)) ||
      !(half_extents.z >= Real(0))) {
    return std::nullopt;
  }
  const Vec3 m = ray.origin - center;
  const Vec3 o(glm::dot(m, axes[0]), glm::dot(m, axes[1]), glm::dot(m, axes[2]));
  const Vec3 d(glm::dot(ray.direction, axes[0]), glm::dot(ray.direction, axes[1]), glm::dot(ray.direction, axes[2]));
  const SlabResult s = slabs(o, d, -half_extents, half_extents);
  if (s.kind == SlabResult::Kind::Miss) return std::nullopt;
  if (s.kind == SlabResult::Kind::Inside) return detail::inside_hit(ray, r);
  const Real sign = (s.face % 2) != 0 ? Real(1) : Real(-1);
  return detail::surface_hit(ray, max_t, s.t, sign * axes[s.face / 2]);
}

}  // namespace proxima::geometry
