// Half-space against half-space: two unbounded solids, answered in closed form with a finite
// result (see pairs_halfspace.hpp for the documented answers). The generic routine of
// generic_halfspace.hpp does not serve here: its answer would come from a corner of the cube
// that clips A (HalfSpace::kSupportExtent) and differ from the documented one.
//
// Steps:
//  1. both planes in world: n_a . x <= d_a and n_b . x <= d_b (offsets taken at A's origin);
//  2. anti-parallel normals (n_a . n_b <= -(1 - kRelativeTolerance)): B is n_a . x >= -d_b,
//     the signed gap between the planes is -(d_a + d_b), normal n_a; point_a is the point of
//     A's plane nearest A's origin, point_b = point_a + gap n_a;
//  3. otherwise the solids overlap without bound: Penetrating, signed distance
//     -kHalfSpacePairDepth, normal n_a, point_a as above, point_b = point_a + signed_distance
//     n_a (a point inside both solids).
// Manifold: the single point (feature ids: face 0 of each).
#include "narrowphase/generic_halfspace.hpp"
#include "narrowphase/pairs_halfspace.hpp"

namespace proxima::narrow {

DistanceResult pair_distance(const HalfSpace& a, const Transform& pose_a, const HalfSpace& b, const Transform& pose_b,
                             const PairRequest& request, PairCache* /*cache*/) {
  if (!poses_in_range(pose_a, pose_b)) return invalid_distance();
  const detail::WorldPlane pa = detail::world_plane(a, pose_a);
  const detail::WorldPlane pb = detail::world_plane(b, pose_b);
  const Real tol = detail::halfspace_tolerance(request, pose_a, pose_b, b, std::abs(a.offset()));
  const Vec3 point_a = pa.origin + pa.offset * pa.n;
  DistanceResult d;
  d.normal = pa.n;
  d.point_a = point_a;
  d.method = PairMethod::Analytic;
  d.tolerance = tol;
  if (glm::dot(pa.n, pb.n) <= -(Real(1) - kRelativeTolerance)) {
    // point_a lies outside B by its height above B's plane, measured along n_a = -n_b.
    d.signed_distance = pb.gap(point_a);
    d.status = status_from_distance(d.signed_distance, tol);
  } else {
    d.signed_distance = -kHalfSpacePairDepth;
    d.status = PairStatus::Penetrating;
  }
  d.point_b = point_a + d.signed_distance * pa.n;
  return d;
}

bool pair_intersect(const HalfSpace& a, const Transform& pose_a, const HalfSpace& b, const Transform& pose_b,
                    const PairRequest& request, PairCache* cache) {
  if (!poses_in_range(pose_a, pose_b)) return false;
  return in_contact(pair_distance(a, pose_a, b, pose_b, request, cache), request);
}

ContactManifold pair_collide(const HalfSpace& a, const Transform& pose_a, const HalfSpace& b, const Transform& pose_b,
                             const PairRequest& request, PairCache* cache) {
  if (!poses_in_range(pose_a, pose_b)) return invalid_manifold();
  return manifold_from_distance(pair_distance(a, pose_a, b, pose_b, request, cache), request,
                                make_feature_id(FeatureKind::Face, 0, FeatureKind::Face, 0));
}

}  // namespace proxima::narrow
