// Cone against half-space (van den Bergen, Collision Detection in Interactive 3D
// Environments, 4.3: support mappings; the half-space is n . x <= d in B's frame).
//
// Steps:
//  1. the half-space's plane in world (normal n, offset relative to B's origin);
//  2. A's core support point x in the direction -n (A's frame), radius r subtracted along n:
//     signed distance n . x - d - r, normal -n (A to B), point_b the projection on the plane;
//  3. Cone: its support point (apex or base rim point); manifold: the apex and the deepest base rim
//     point, with the rim points at 90, 180 and 270 degrees from it: a cone on its side gives 2
//     points, standing on its base 4 (feature: 0 apex, 1 deepest rim point, 2..4 the turned
//     points).
#include "narrowphase/halfspace_common.hpp"
#include "narrowphase/pairs_halfspace.hpp"
#include "shapes/radial.hpp"

namespace proxima::narrow {

namespace {

Real tolerance_of(const Cone& a, const Transform& pose_a, const HalfSpace& b, const Transform& pose_b,
                  const PairRequest& request) {
  return detail::halfspace_tolerance(request, pose_a, pose_b, b, std::max(a.radius(), a.half_length()));
}

}  // namespace

DistanceResult pair_distance(const Cone& a, const Transform& pose_a, const HalfSpace& b, const Transform& pose_b,
                             const PairRequest& request, PairCache* /*cache*/) {
  if (!finite_poses(pose_a, pose_b)) return invalid_distance();
  return detail::halfspace_distance(a, pose_a, b, pose_b, tolerance_of(a, pose_a, b, pose_b, request));
}

bool pair_intersect(const Cone& a, const Transform& pose_a, const HalfSpace& b, const Transform& pose_b,
                    const PairRequest& request, PairCache* cache) {
  if (!finite_poses(pose_a, pose_b)) return false;
  return pair_distance(a, pose_a, b, pose_b, request, cache).signed_distance <= request.contact_distance;
}

ContactManifold pair_collide(const Cone& a, const Transform& pose_a, const HalfSpace& b, const Transform& pose_b,
                             const PairRequest& request, PairCache* /*cache*/) {
  if (!finite_poses(pose_a, pose_b)) return invalid_manifold();
  const Real tol = tolerance_of(a, pose_a, b, pose_b, request);
  const DistanceResult d = detail::halfspace_distance(a, pose_a, b, pose_b, tol);
  const detail::WorldPlane plane = detail::world_plane(b, pose_b);
  detail::Candidates c;
  const Vec3 u = pose_a.inverse_apply_vector(-plane.n);
  Real ux = Real(1);
  Real uy = Real(0);
  static_cast<void>(::proxima::detail::radial_direction(u.x, u.y, ux, uy));
  const Real r = a.radius();
  const Real hl = a.half_length();
  c.add(pose_a.apply(Vec3(Real(0), Real(0), hl)), 0);
  c.add(pose_a.apply(Vec3(r * ux, r * uy, -hl)), 1);
  c.add(pose_a.apply(Vec3(-r * uy, r * ux, -hl)), 2);
  c.add(pose_a.apply(Vec3(-r * ux, -r * uy, -hl)), 3);
  c.add(pose_a.apply(Vec3(r * uy, -r * ux, -hl)), 4);
  return detail::candidate_manifold(plane, c, Real(0), d, request, tol);
}

}  // namespace proxima::narrow
