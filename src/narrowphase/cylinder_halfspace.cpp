// Cylinder against half-space (van den Bergen, Collision Detection in Interactive 3D
// Environments, 4.3: support mappings; the half-space is n . x <= d in B's frame).
//
// Steps:
//  1. the half-space's plane in world (normal n, offset relative to B's origin);
//  2. A's core support point x in the direction -n (A's frame), radius r subtracted along n:
//     signed distance n . x - d - r, normal -n (A to B), point_b the projection on the plane;
//  3. Cylinder: its support point (a rim point of the lower cap); manifold: the deepest rim point
//     of each cap and, on the deeper cap, the rim points at 90, 180 and 270 degrees from it: a
//     cylinder on its side gives 2 points, standing on a cap 4 (feature: 4 * cap + k, cap 0 =
//     bottom, k = 0 deepest, 1..3 the turned points).
#include "narrowphase/halfspace_common.hpp"
#include "narrowphase/pairs_halfspace.hpp"
#include "shapes/radial.hpp"

namespace proxima::narrow {

namespace {

Real tolerance_of(const Cylinder& a, const Transform& pose_a, const HalfSpace& b, const Transform& pose_b,
                  const PairRequest& request) {
  return detail::halfspace_tolerance(request, pose_a, pose_b, b, std::max(a.radius(), a.half_length()));
}

}  // namespace

DistanceResult pair_distance(const Cylinder& a, const Transform& pose_a, const HalfSpace& b, const Transform& pose_b,
                             const PairRequest& request, PairCache* /*cache*/) {
  if (!finite_poses(pose_a, pose_b)) return invalid_distance();
  return detail::halfspace_distance(a, pose_a, b, pose_b, tolerance_of(a, pose_a, b, pose_b, request));
}

bool pair_intersect(const Cylinder& a, const Transform& pose_a, const HalfSpace& b, const Transform& pose_b,
                    const PairRequest& request, PairCache* cache) {
  if (!finite_poses(pose_a, pose_b)) return false;
  return pair_distance(a, pose_a, b, pose_b, request, cache).signed_distance <= request.contact_distance;
}

ContactManifold pair_collide(const Cylinder& a, const Transform& pose_a, const HalfSpace& b, const Transform& pose_b,
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
  const std::uint32_t deep = u.z >= Real(0) ? 1u : 0u;  // the cap facing the plane
  const Real zd = deep == 1u ? hl : -hl;
  c.add(pose_a.apply(Vec3(r * ux, r * uy, -hl)), 0);
  c.add(pose_a.apply(Vec3(r * ux, r * uy, hl)), 4);
  c.add(pose_a.apply(Vec3(-r * uy, r * ux, zd)), 4 * deep + 1);
  c.add(pose_a.apply(Vec3(-r * ux, -r * uy, zd)), 4 * deep + 2);
  c.add(pose_a.apply(Vec3(r * uy, -r * ux, zd)), 4 * deep + 3);
  return detail::candidate_manifold(plane, c, Real(0), d, request, tol);
}

}  // namespace proxima::narrow
