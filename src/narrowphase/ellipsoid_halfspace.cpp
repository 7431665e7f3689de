// Ellipsoid against half-space (van den Bergen, Collision Detection in Interactive 3D
// Environments, 4.3: support mappings; the half-space is n . x <= d in B's frame).
//
// Steps:
//  1. the half-space's plane in world (normal n, offset relative to B's origin);
//  2. A's core support point x in the direction -n (A's frame), radius r subtracted along n:
//     signed distance n . x - d - r, normal -n (A to B), point_b the projection on the plane;
//  3. Ellipsoid: its support point; one point.
#include "narrowphase/halfspace_common.hpp"
#include "narrowphase/pairs_halfspace.hpp"

namespace proxima::narrow {

namespace {

Real tolerance_of(const Ellipsoid& a, const Transform& pose_a, const HalfSpace& b, const Transform& pose_b,
                  const PairRequest& request) {
  return detail::halfspace_tolerance(request, pose_a, pose_b, b, max_abs_component(a.radii()));
}

}  // namespace

DistanceResult pair_distance(const Ellipsoid& a, const Transform& pose_a, const HalfSpace& b, const Transform& pose_b,
                             const PairRequest& request, PairCache* /*cache*/) {
  if (!finite_poses(pose_a, pose_b)) return invalid_distance();
  return detail::halfspace_distance(a, pose_a, b, pose_b, tolerance_of(a, pose_a, b, pose_b, request));
}

bool pair_intersect(const Ellipsoid& a, const Transform& pose_a, const HalfSpace& b, const Transform& pose_b,
                    const PairRequest& request, PairCache* cache) {
  if (!finite_poses(pose_a, pose_b)) return false;
  return pair_distance(a, pose_a, b, pose_b, request, cache).signed_distance <= request.contact_distance;
}

ContactManifold pair_collide(const Ellipsoid& a, const Transform& pose_a, const HalfSpace& b, const Transform& pose_b,
                             const PairRequest& request, PairCache* /*cache*/) {
  if (!finite_poses(pose_a, pose_b)) return invalid_manifold();
  const Real tol = tolerance_of(a, pose_a, b, pose_b, request);
  const DistanceResult d = detail::halfspace_distance(a, pose_a, b, pose_b, tol);
  return manifold_from_distance(d, request, make_feature_id(FeatureKind::Surface, 0, FeatureKind::Face, 0));
}

}  // namespace proxima::narrow
