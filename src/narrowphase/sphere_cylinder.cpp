// Sphere against cylinder (Ericson, Real-Time Collision Detection, 5.1: closest point of a
// convex solid; the cylinder reduced to its meridian rectangle).
//
// Steps:
//  1. the sphere centre c in the cylinder frame; its height z and its distance rho from the
//     axis, with the radial unit u = (c.x, c.y) / rho (the local +x axis when rho is 0);
//  2. in the (rho, z) half-plane the cylinder is the rectangle [0, R] x [-h, h]:
//     - beside the barrel (|z| <= h, rho > R): core distance rho - R, normal -u;
//     - over a cap (rho <= R, |z| > h): core distance |z| - h, normal -sign(z) z;
//     - beyond a rim (rho > R, |z| > h): the rim point, core distance |(rho - R, |z| - h)|,
//       normal minus that 2D direction mapped onto (u, sign(z) z);
//     - inside: the nearer of the barrel (depth R - rho, normal -u) and the cap on c's side
//       (depth h - |z|, normal -sign(z) z); ties go to the cap;
//     every normal thus comes from the cylinder's axis and c's radial direction, never from
//     the difference of two nearby points (a sphere over a wide thin disc gets the disc's
//     axis exactly);
//  3. signed distance: core distance minus r; witnesses c + r n on the sphere and the
//     cylinder's surface point c + core n (turned to world).
// Manifold: that single point; feature id: the sphere's surface against the bottom (face 0)
// or top cap (face 1), the barrel (surface 0) or the bottom / top rim (edge 0 / 1).
// intersect applies the touching rule (contact.hpp) to the same distance: O(1), one square
// root.
#include "narrowphase/pairs_rounded.hpp"
#include "narrowphase/rounded_common.hpp"

namespace proxima::narrow {

namespace {

struct SphereCylinder {
  DistanceResult result;
  std::uint32_t feature = 0;
};

SphereCylinder sphere_cylinder(const Sphere& a, const Transform& pose_a, const Cylinder& b, const Transform& pose_b,
                               const PairRequest& request) {
  const Real R = b.radius();
  const Real h = b.half_length();
  const Vec3 c = pose_b.inverse_apply(pose_a.position);
  const detail::CylinderRegion g = detail::cylinder_region(c, R, h);
  const std::uint32_t cap = c.z >= Real(0) ? 1u : 0u;
  const Real core = g.distance;
  const Vec3 n_local = -g.normal;
  const FeatureKind kind = g.kind == detail::CylinderRegion::kRim   ? FeatureKind::Edge
                           : g.kind == detail::CylinderRegion::kCap ? FeatureKind::Face
                                                                    : FeatureKind::Surface;
  const std::uint32_t index = g.kind == detail::CylinderRegion::kBarrel ? 0u : cap;
  const Vec3 q_local = c + core * n_local;
  const Real tol = resolve_tolerance(request, detail::pair_scale(pose_a, pose_b, a.radius() + std::max(R, h)));
  SphereCylinder sc;
  sc.result = detail::rounded_result(pose_a.position, pose_b.apply(q_local), pose_b.apply_vector(n_local), core,
                                     a.radius(), Real(0), tol);
  sc.feature = make_feature_id(FeatureKind::Surface, 0, kind, index);
  return sc;
}

}  // namespace

DistanceResult pair_distance(const Sphere& a, const Transform& pose_a, const Cylinder& b, const Transform& pose_b,
                             const PairRequest& request, PairCache* /*cache*/) {
  if (!poses_in_range(pose_a, pose_b)) return invalid_distance();
  return sphere_cylinder(a, pose_a, b, pose_b, request).result;
}

bool pair_intersect(const Sphere& a, const Transform& pose_a, const Cylinder& b, const Transform& pose_b,
                    const PairRequest& request, PairCache* /*cache*/) {
  if (!poses_in_range(pose_a, pose_b)) return false;
  return in_contact(sphere_cylinder(a, pose_a, b, pose_b, request).result, request);
}

ContactManifold pair_collide(const Sphere& a, const Transform& pose_a, const Cylinder& b, const Transform& pose_b,
                             const PairRequest& request, PairCache* /*cache*/) {
  if (!poses_in_range(pose_a, pose_b)) return invalid_manifold();
  const SphereCylinder sc = sphere_cylinder(a, pose_a, b, pose_b, request);
  return manifold_from_distance(sc.result, request, sc.feature);
}

}  // namespace proxima::narrow
