// Cylinder against cylinder: a closed form for parallel axes, the generic ladder otherwise.
//
// Steps (parallel axes: the sine of their angle within kParallelAxisSine, where the closed form's
// error, at most the sine times the larger size, is a few units in the last place):
//  1. B's centre c in A's frame; its height z along A's axis and its distance rho from it,
//     the radial unit u (A's local +x when rho is 0);
//  2. the Minkowski difference A - B of two parallel cylinders is the cylinder of radius
//     R = R_A + R_B and half length h = h_A + h_B about A's axis (two parallel discs sum to a
//     disc, two segments on one line to a segment), so the pair's signed distance is c's
//     from that cylinder: in the (rho, z) half-plane the rectangle [0, R] x [-h, h], as for a
//     sphere against a cylinder (sphere_cylinder.cpp): beside the barrel (normal u), over a
//     cap (normal +-z), beyond a rim (the rim's 2D direction), inside (the nearer of barrel
//     and cap, ties to the cap); the normal comes from A's axis and c's radial direction,
//     never from the difference of nearby points;
//  3. witnesses: A's point on its barrel at the middle of the two axial extents' overlap, on
//     its cap at the middle of the two discs' overlap along u, or on its rim; B's at A's plus
//     the signed distance along the normal (a point of B's surface by step 2).
// Manifold: the supporting features along the normal, clipped (supporting_face_manifold.hpp).
// intersect applies the touching rule (contact.hpp) to the parallel distance.
#include "narrowphase/closed_form_or_ladder.hpp"
#include "narrowphase/pairs_curved.hpp"
#include "narrowphase/rounded_common.hpp"

namespace proxima::narrow {

namespace {

/// Axes whose sine of angle is within this count as parallel.
const Real kParallelAxisSine = Real(4) * kEpsilon;

/// The closed form of two parallel cylinders (steps 1-3), false when the axes are not
/// parallel.
bool parallel_cylinders(const Cylinder& a, const Transform& pose_a, const Cylinder& b, const Transform& pose_b,
                        const PairRequest& request, DistanceResult& r) {
  // B's axis in A's frame through the relative rotation (one product: about 1 eps of tilt
  // where the two rotations agree; through the world, 4 to 5).
  const Vec3 axis_b = (glm::conjugate(pose_a.rotation) * pose_b.rotation) * Vec3(Real(0), Real(0), Real(1));
  if (!(std::sqrt(axis_b.x * axis_b.x + axis_b.y * axis_b.y) <= kParallelAxisSine)) return false;
  const Real ra = a.radius();
  const Real rb = b.radius();
  const Real ha = a.half_length();
  const Real hb = b.half_length();
  const Real R = ra + rb;
  const Real h = ha + hb;
  const Vec3 c = pose_a.inverse_apply(pose_b.position);
  const detail::CylinderRegion g = detail::cylinder_region(c, R, h);
  // The middle of the axial extents' overlap (along A's axis) and of the discs' along u.
  const Real mid_z = Real(0.5) * (std::max(-ha, c.z - hb) + std::min(ha, c.z + hb));
  const Real mid_u = Real(0.5) * (std::max(-ra, g.rho - rb) + std::min(ra, g.rho + rb));
  const Real sd = g.distance;
  const Vec3 n = g.normal;
  const Vec3 on_a = g.kind == detail::CylinderRegion::kRim      ? ra * g.u + ha * g.axis
                    : g.kind == detail::CylinderRegion::kBarrel ? ra * g.u + Vec3(Real(0), Real(0), mid_z)
                                                                : mid_u * g.u + ha * g.axis;
  const Real scale = detail::pair_scale(pose_a, pose_b, std::max({ra, rb, ha, hb}));
  r = detail::analytic_answer(pose_a, sd, n, on_a, request, scale);
  return true;
}

}  // namespace

PROXIMA_CLOSED_FORM_OR_LADDER(Cylinder, parallel_cylinders)

}  // namespace proxima::narrow
