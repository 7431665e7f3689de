// Sphere against capsule (Ericson, Real-Time Collision Detection, 4.5.1 and 5.1.2).
//
// Steps:
//  1. the capsule's core segment in world; the closest point q of it to the sphere centre c;
//  2. signed distance |q - c| - both radii, normal (q - c) / |q - c| (A to B), q - c taken
//     exactly across the core where q is inside it (across_direction); a centre on the core
//     (to rounding, offset_noise, where the direction of q - c is noise) takes the capsule's
//     local +x axis (perpendicular to the core);
//  3. witnesses: c and q pushed out along the normal by their radii.
// Manifold: that single point; feature id: sphere surface against the capsule's bottom end
// (vertex 0), top end (vertex 1) or side (edge 0). intersect compares the squared distance of
// the centre to the core (capsule frame) with (contact reach + radii)^2, and asks
// pair_distance when rounding could decide (decide_contact_squared).
#include <proxima/geometry/closest_points.hpp>

#include "narrowphase/pairs_rounded.hpp"
#include "narrowphase/rounded_common.hpp"

namespace proxima::narrow {

namespace {

struct SphereCapsule {
  DistanceResult result;
  Real t = Real(0);
};

SphereCapsule sphere_capsule(const Sphere& a, const Transform& pose_a, const Capsule& b, const Transform& pose_b,
                             const PairRequest& request) {
  const Vec3 c = pose_a.position;
  // The core's half axis rotated once: the ends are the centre less and plus it, bit for bit
  // pose_b.apply(bottom()) and pose_b.apply(top()) (as capsule_capsule.cpp).
  const Vec3 half = pose_b.apply_vector(b.top());
  const Vec3 p0 = pose_b.position - half;
  const Vec3 p1 = pose_b.position + half;
  const geometry::SegmentPoint q = geometry::closest_point_segment(c, p0, p1);
  const Real scale = detail::pair_scale(pose_a, pose_b, a.radius() + b.radius() + b.half_length());
  const Real tol = resolve_tolerance(request, scale);
  // Inside the core the offset is exactly across it (the core's support has a kink there).
  const Vec3 offset = q.t > Real(0) && q.t < Real(1) ? across_direction(q.point - c, p1 - p0) : q.point - c;
  Vec3 n;
  Real length = Real(0);
  if (!unit_and_length(offset, n, length) || !(length > detail::offset_noise(scale))) {
    // Centre on the core (to rounding): the direction of q - c is noise; the capsule's local
    // +x axis, perpendicular to the core, rotated only here.
    n = pose_b.apply_vector(Vec3(Real(1), Real(0), Real(0)));
    length = Real(0);
  }
  return {detail::rounded_result(c, q.point, n, length, a.radius(), b.radius(), tol), q.t};
}

}  // namespace

DistanceResult pair_distance(const Sphere& a, const Transform& pose_a, const Capsule& b, const Transform& pose_b,
                             const PairRequest& request, PairCache* /*cache*/) {
  if (!poses_in_range(pose_a, pose_b)) return invalid_distance();
  return sphere_capsule(a, pose_a, b, pose_b, request).result;
}

bool pair_intersect(const Sphere& a, const Transform& pose_a, const Capsule& b, const Transform& pose_b,
                    const PairRequest& request, PairCache* /*cache*/) {
  if (!poses_in_range(pose_a, pose_b)) return false;
  // Squared distance of the centre to the core (in the capsule's frame, where the core is
  // the z axis from -half_length to half_length) against (contact reach + radii)^2.
  const Vec3 c = pose_b.inverse_apply(pose_a.position);
  const Real hl = b.half_length();
  const Real dz = c.z - std::clamp(c.z, -hl, hl);
  const Real d2 = c.x * c.x + c.y * c.y + dz * dz;
  const Real tol =
      resolve_tolerance(request, detail::pair_scale(pose_a, pose_b, a.radius() + b.radius() + b.half_length()));
  return decide_contact_squared(
      d2, a.radius() + b.radius(), contact_reach(request.contact_distance, tol), Real(0.25) * tol,
      [&] { return in_contact(pair_distance(a, pose_a, b, pose_b, request, nullptr), request); });
}

ContactManifold pair_collide(const Sphere& a, const Transform& pose_a, const Capsule& b, const Transform& pose_b,
                             const PairRequest& request, PairCache* /*cache*/) {
  if (!poses_in_range(pose_a, pose_b)) return invalid_manifold();
  const SphereCapsule sc = sphere_capsule(a, pose_a, b, pose_b, request);
  FeatureKind kind{};
  std::uint32_t index = 0;
  detail::capsule_feature(sc.t, kind, index);
  return manifold_from_distance(sc.result, request, make_feature_id(FeatureKind::Surface, 0, kind, index));
}

}  // namespace proxima::narrow
