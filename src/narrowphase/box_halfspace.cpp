// Box against half-space (van den Bergen, Collision Detection in Interactive 3D
// Environments, 4.3: support mappings; the half-space is n . x <= d in B's frame).
//
// Steps:
//  1. the half-space's plane in world (normal n, offset relative to B's origin);
//  2. A's core support point x in the direction -n (A's frame), radius r subtracted along n:
//     signed distance n . x - d - r, normal -n (A to B), point_b the projection on the plane;
//  3. Box: its support corner; manifold: the up to 4 deepest of its 8 corners within the contact
//     distance (feature: vertex index with bit i set for the + side on axis i).
#include "narrowphase/halfspace_common.hpp"
#include "narrowphase/pairs_halfspace.hpp"

namespace proxima::narrow {

namespace {

Real tolerance_of(const Box& a, const Transform& pose_a, const HalfSpace& b, const Transform& pose_b,
                  const PairRequest& request) {
  return detail::halfspace_tolerance(request, pose_a, pose_b, b, max_abs_component(a.half_extents()));
}

}  // namespace

DistanceResult pair_distance(const Box& a, const Transform& pose_a, const HalfSpace& b, const Transform& pose_b,
                             const PairRequest& request, PairCache* /*cache*/) {
  if (!finite_poses(pose_a, pose_b)) return invalid_distance();
  return detail::halfspace_distance(a, pose_a, b, pose_b, tolerance_of(a, pose_a, b, pose_b, request));
}

bool pair_intersect(const Box& a, const Transform& pose_a, const HalfSpace& b, const Transform& pose_b,
                    const PairRequest& request, PairCache* cache) {
  if (!finite_poses(pose_a, pose_b)) return false;
  return pair_distance(a, pose_a, b, pose_b, request, cache).signed_distance <= request.contact_distance;
}

ContactManifold pair_collide(const Box& a, const Transform& pose_a, const HalfSpace& b, const Transform& pose_b,
                             const PairRequest& request, PairCache* /*cache*/) {
  if (!finite_poses(pose_a, pose_b)) return invalid_manifold();
  const Real tol = tolerance_of(a, pose_a, b, pose_b, request);
  const DistanceResult d = detail::halfspace_distance(a, pose_a, b, pose_b, tol);
  const detail::WorldPlane plane = detail::world_plane(b, pose_b);
  detail::Candidates c;
  const Vec3& h = a.half_extents();
  for (std::uint32_t i = 0; i < 8; ++i) {
    const Vec3 v((i & 1u) != 0u ? h.x : -h.x, (i & 2u) != 0u ? h.y : -h.y, (i & 4u) != 0u ? h.z : -h.z);
    c.add(pose_a.apply(v), i);
  }
  return detail::candidate_manifold(plane, c, Real(0), d, request, tol);
}

}  // namespace proxima::narrow
