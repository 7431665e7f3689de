// Triangle against half-space (van den Bergen, Collision Detection in Interactive 3D
// Environments, 4.3: support mappings; the half-space is n . x <= d in B's frame).
//
// Steps:
//  1. the half-space's plane in world (normal n, offset relative to B's origin);
//  2. A's core support point x in the direction -n (A's frame), radius r subtracted along n:
//     signed distance n . x - d - r, normal -n (A to B), point_b the projection on the plane;
//  3. Triangle: the lowest vertex is the support point; manifold: the vertices within the contact
//     distance (feature: vertex 0..2 = a, b, c).
#include "narrowphase/halfspace_common.hpp"
#include "narrowphase/pairs_halfspace.hpp"

namespace proxima::narrow {

namespace {

Real geometry_size(std::initializer_list<Vec3> vs) {
  Real m = Real(0);
  for (const Vec3& v : vs) m = std::max(m, max_abs_component(v));
  return m;
}

Real tolerance_of(const Triangle& a, const Transform& pose_a, const HalfSpace& b, const Transform& pose_b,
                  const PairRequest& request) {
  return detail::halfspace_tolerance(request, pose_a, pose_b, b, geometry_size({a.a(), a.b(), a.c()}));
}

}  // namespace

DistanceResult pair_distance(const Triangle& a, const Transform& pose_a, const HalfSpace& b, const Transform& pose_b,
                             const PairRequest& request, PairCache* /*cache*/) {
  if (!finite_poses(pose_a, pose_b)) return invalid_distance();
  return detail::halfspace_distance(a, pose_a, b, pose_b, tolerance_of(a, pose_a, b, pose_b, request));
}

bool pair_intersect(const Triangle& a, const Transform& pose_a, const HalfSpace& b, const Transform& pose_b,
                    const PairRequest& request, PairCache* cache) {
  if (!finite_poses(pose_a, pose_b)) return false;
  return pair_distance(a, pose_a, b, pose_b, request, cache).signed_distance <= request.contact_distance;
}

ContactManifold pair_collide(const Triangle& a, const Transform& pose_a, const HalfSpace& b, const Transform& pose_b,
                             const PairRequest& request, PairCache* /*cache*/) {
  if (!finite_poses(pose_a, pose_b)) return invalid_manifold();
  const Real tol = tolerance_of(a, pose_a, b, pose_b, request);
  const DistanceResult d = detail::halfspace_distance(a, pose_a, b, pose_b, tol);
  const detail::WorldPlane plane = detail::world_plane(b, pose_b);
  detail::Candidates c;
  c.add(pose_a.apply(a.a()), 0);
  c.add(pose_a.apply(a.b()), 1);
  c.add(pose_a.apply(a.c()), 2);
  return detail::candidate_manifold(plane, c, Real(0), d, request, tol);
}

}  // namespace proxima::narrow
