// Sphere against ellipsoid (D. Eberly, "Distance from a Point to an Ellipse, an Ellipsoid, or
// a Hyperellipsoid", Geometric Tools, 2013-2020: the robust 1-D root finder of
// Ellipsoid::closest_point).
//
// Steps:
//  1. the sphere centre c in the ellipsoid frame;
//  2. Ellipsoid::closest_point(c): the surface point q nearest c, found by bisection on the
//     one root of Eberly's secular function (to the rounding of the root's parameter), the
//     signed distance (negative inside) and the outward normal m at q, the gradient of the
//     implicit function there (from the ellipsoid's geometry, not from c - q);
//  3. signed distance: the core distance minus r; normal -m (from the sphere to the
//     ellipsoid); witnesses c + r (-m) on the sphere and q (turned to world).
// intersect first compares |c| with the radii: beyond r + the largest radius plus the
// tolerance the pair is apart, within r + the smallest radius minus it they overlap; only
// the shell between runs step 2.
// Manifold: that single point; feature id: the sphere's surface against the ellipsoid's.
#include "narrowphase/pairs_rounded.hpp"
#include "narrowphase/rounded_common.hpp"

namespace proxima::narrow {

namespace {

Real ellipsoid_tolerance(const Sphere& a, const Transform& pose_a, const Ellipsoid& b, const Transform& pose_b,
                         const PairRequest& request) {
  return resolve_tolerance(request, detail::pair_scale(pose_a, pose_b, a.radius() + max_abs_component(b.radii())));
}

/// Steps 1-3, decided with tolerance `tol`.
DistanceResult sphere_ellipsoid(const Sphere& a, const Transform& pose_a, const Ellipsoid& b, const Transform& pose_b,
                                Real tol) {
  const Vec3 c = pose_b.inverse_apply(pose_a.position);
  const SurfacePoint q = b.closest_point(c);
  const Vec3 n_local = -q.normal;
  return detail::rounded_result(pose_a.position, pose_b.apply(q.point), pose_b.apply_vector(n_local), q.signed_distance,
                                a.radius(), Real(0), tol);
}

}  // namespace

DistanceResult pair_distance(const Sphere& a, const Transform& pose_a, const Ellipsoid& b, const Transform& pose_b,
                             const PairRequest& request, PairCache* /*cache*/) {
  if (!poses_in_range(pose_a, pose_b)) return invalid_distance();
  return sphere_ellipsoid(a, pose_a, b, pose_b, ellipsoid_tolerance(a, pose_a, b, pose_b, request));
}

bool pair_intersect(const Sphere& a, const Transform& pose_a, const Ellipsoid& b, const Transform& pose_b,
                    const PairRequest& request, PairCache* /*cache*/) {
  if (!poses_in_range(pose_a, pose_b)) return false;
  const Real tol = ellipsoid_tolerance(a, pose_a, b, pose_b, request);
  const Real reach = std::max(request.contact_distance, tol);
  const Vec3 e = b.radii();
  const Real centres = glm::length(pose_a.position - pose_b.position);
  if (centres > a.radius() + max_abs_component(e) + reach + tol) return false;
  if (centres < a.radius() + std::min({e.x, e.y, e.z}) - tol) return true;
  return in_contact(sphere_ellipsoid(a, pose_a, b, pose_b, tol), request);
}

ContactManifold pair_collide(const Sphere& a, const Transform& pose_a, const Ellipsoid& b, const Transform& pose_b,
                             const PairRequest& request, PairCache* /*cache*/) {
  if (!poses_in_range(pose_a, pose_b)) return invalid_manifold();
  return manifold_from_distance(
      sphere_ellipsoid(a, pose_a, b, pose_b, ellipsoid_tolerance(a, pose_a, b, pose_b, request)), request,
      make_feature_id(FeatureKind::Surface, 0, FeatureKind::Surface, 0));
}

}  // namespace proxima::narrow
