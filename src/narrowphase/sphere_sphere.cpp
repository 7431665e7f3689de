// Sphere against sphere (Ericson, Real-Time Collision Detection, 4.3.1).
//
// Steps:
//  1. v = centre_b - centre_a; its length minus both radii is the signed distance;
//  2. the normal is v / |v|; coincident centres take A's local +x axis (world frame);
//  3. witnesses: each centre pushed out along the normal by its radius.
// Manifold: that single point (feature ids: the surfaces of both spheres). intersect compares
// the squared centre distance with (contact reach + radii)^2, and asks pair_distance when
// rounding could decide (decide_contact_squared).
#include "narrowphase/pairs_rounded.hpp"
#include "narrowphase/rounded_common.hpp"

namespace proxima::narrow {

DistanceResult pair_distance(const Sphere& a, const Transform& pose_a, const Sphere& b, const Transform& pose_b,
                             const PairRequest& request, PairCache* /*cache*/) {
  if (!poses_in_range(pose_a, pose_b)) return invalid_distance();
  const Vec3 ca = pose_a.position;
  const Vec3 cb = pose_b.position;
  Real length = Real(0);
  const Vec3 n = detail::unit_or(cb - ca, pose_a.apply_vector(Vec3(Real(1), Real(0), Real(0))), length);
  const Real tol = resolve_tolerance(request, detail::pair_scale(pose_a, pose_b, a.radius() + b.radius()));
  return detail::rounded_result(ca, cb, n, length, a.radius(), b.radius(), tol);
}

bool pair_intersect(const Sphere& a, const Transform& pose_a, const Sphere& b, const Transform& pose_b,
                    const PairRequest& request, PairCache* /*cache*/) {
  if (!poses_in_range(pose_a, pose_b)) return false;
  // |cb - ca| - ra - rb <= contact reach, without the square root away from the threshold.
  const Real tol = resolve_tolerance(request, detail::pair_scale(pose_a, pose_b, a.radius() + b.radius()));
  return decide_contact_squared(length_squared(pose_b.position - pose_a.position), a.radius() + b.radius(),
                                contact_reach(request.contact_distance, tol), Real(0.25) * tol, [&] {
                                  return in_contact(pair_distance(a, pose_a, b, pose_b, request, nullptr), request);
                                });
}

ContactManifold pair_collide(const Sphere& a, const Transform& pose_a, const Sphere& b, const Transform& pose_b,
                             const PairRequest& request, PairCache* cache) {
  if (!poses_in_range(pose_a, pose_b)) return invalid_manifold();
  return manifold_from_distance(pair_distance(a, pose_a, b, pose_b, request, cache), request,
                                make_feature_id(FeatureKind::Surface, 0, FeatureKind::Surface, 0));
}

}  // namespace proxima::narrow
