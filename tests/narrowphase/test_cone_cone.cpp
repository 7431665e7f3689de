// Two coaxial cones: the closed form (cone_cone.cpp) against references that share no code
// with it (pair_reference.hpp, long double): the overlap of the two cones' support functions
// along the reported normal is the reported depth (minus the distance) within 8 ulps of the
// pair's size (64 in float), a search over directions finds no direction with less overlap,
// the witnesses lie on the surfaces, and the generic ladder agrees to its own precision.
// Axes turned apart, or B's centre off A's axis, by more than rounding go to the generic
// ladder. Named cases with answers by hand: an apex 0.1 into the base above it, two apexes
// nested (a circle of normals), and two bases face to face.
#include <gtest/gtest.h>

#include <proxima/narrowphase/narrowphase.hpp>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

#include "narrowphase/closed_form_check.hpp"
#include "narrowphase/narrowphase_test_util.hpp"
#include "narrowphase/pair_reference.hpp"
#include "support/random.hpp"
#include "sweep_size.hpp"

namespace proxima {
namespace test_cone_cone {

using test::LD;
using test::LVec;

/// B's pose: A's rotation turned about its own axis by `spin`, flipped end over end when
/// `flip` (the axes stay on one line), its centre at height `z` on A's axis.
Transform coaxial_pose(const Transform& pa, Real spin, bool flip, Real z) {
  Quat q = pa.rotation * glm::angleAxis(spin, Vec3(Real(0), Real(0), Real(1)));
  if (flip) q = q * glm::angleAxis(kPi, Vec3(Real(1), Real(0), Real(0)));
  return Transform{pa.apply(Vec3(Real(0), Real(0), z)), q};
}

/// Distance of (x, z) from segment p q in the plane (long double).
LD segment_distance_2d(LD x, LD z, LD px, LD pz, LD qx, LD qz) {
  const LD dx = qx - px, dz = qz - pz;
  const LD t = std::clamp(((x - px) * dx + (z - pz) * dz) / (dx * dx + dz * dz), LD(0), LD(1));
  return std::hypot(x - (px + t * dx), z - (pz + t * dz));
}

/// Signed distance of a world point from the cone's surface (long double, the cone's
/// definition: base disc of radius R at z = -h, apex at z = +h): > 0 outside.
LD surface_distance(const Cone& c, const Transform& pose, const Vec3& world) {
  const test::LPose lp(pose);
  const LVec p = lp.to_local(test::ld(world));
  const LD rho = std::sqrt(p.x * p.x + p.y * p.y);
  const LD r = LD(c.radius()), h = LD(c.half_length());
  const LD to_base = segment_distance_2d(rho, p.z, 0, -h, r, -h);
  const LD to_slant = segment_distance_2d(rho, p.z, r, -h, 0, h);
  const bool inside = p.z >= -h && rho * 2 * h <= r * (h - p.z);
  return inside ? -std::min(to_base, to_slant) : std::min(to_base, to_slant);
}

std::string describe(const Cone& a, const Transform& pa, const Cone& b, const Transform& pb, const DistanceResult& d) {
  std::ostringstream o;
  o.precision(17);
  o << test::describe(Shape(a), pa) << " | " << test::describe(Shape(b), pb) << " sd=" << d.signed_distance;
  return o.str();
}

// Cases by hand, equal cones (R = 1, h = 1) at 32 poses of A (identity first), B turned
// about the axis at random:
//  - B 1.9 above A: A's apex 0.1 into B's base, along A's axis (any tilt needs more);
//  - B flipped (apex down) 1.5 above: the apexes nested 0.5 deep along the axis, but a slant
//    normal (2, 1) / sqrt 5 of A (at any azimuth: a circle of answers) needs only
//    0.5 / sqrt 5, the normal's component along the axis 1 / sqrt 5;
//  - B flipped 2.1 below: its base (on top, at -1.1) 0.1 under A's base, apart along -z.
TEST(ConeCone, CoaxialCasesByHand) {
  const Cone c = Cone::create(Real(1), Real(1)).value();
  test::Random rng(1902);
  struct Case {
    Real z;
    bool flip;
    Real sd;
    Real normal_z;  // the normal's component along A's axis
  };
  const Real root5 = std::sqrt(Real(5));
  for (const Case k :
       {Case{Real(1.9), false, Real(-0.1), Real(1)}, Case{Real(1.5), true, Real(-0.5) / root5, Real(1) / root5},
        Case{Real(-2.1), true, Real(0.1), Real(-1)}}) {
    for (int i = 0; i < 32; ++i) {
      const Transform pa = i == 0 ? Transform{Vec3(Real(0)), kIdentityQuat} : rng.pose(Real(10));
      const Transform pb = coaxial_pose(pa, rng.uniform(Real(0), Real(6.283)), k.flip, k.z);
      const DistanceResult d = distance(c, pa, c, pb);
      const Vec3 axis = pa.apply_vector(Vec3(Real(0), Real(0), Real(1)));
      const Real size = std::max(Real(3), max_abs_component(pa.position));
      EXPECT_EQ(d.method, PairMethod::Analytic) << k.z << " " << i;
      EXPECT_NEAR(d.signed_distance, k.sd, Real(16) * kEpsilon * size) << k.z << " " << i;
      EXPECT_NEAR(glm::dot(d.normal, axis), k.normal_z, Real(16) * kEpsilon * size) << k.z << " " << i;
      EXPECT_NEAR(glm::length(d.normal), Real(1), Real(4) * kEpsilon) << k.z << " " << i;
      EXPECT_EQ(intersect(c, pa, c, pb), k.sd < Real(0)) << k.z << " " << i;
      const ContactManifold m = collide(c, pa, c, pb);
      EXPECT_EQ(m.count > 0, k.sd < Real(0)) << k.z << " " << i;
      for (int p = 0; p < m.count; ++p) {
        EXPECT_NEAR(m.points[static_cast<std::size_t>(p)].depth, -k.sd, Real(1e-3)) << k.z << " " << i;
      }
    }
  }
}

// Random coaxial pairs: sizes 1e-2 to 1e2, A anywhere within 1e3 of the origin, B's centre
// on A's axis from well below to well above (apart, apex into base, apex into apex, nested,
// base against base), B turned about the axis and flipped.
TEST(ConeCone, CoaxialMatchesTheSupportFunctionReferences) {
  test::Random rng(7718);
  const int cases = test::sweep_size(1000);
  double worst_ulps = 0;
  std::string worst_case;
  int meeting = 0;
  for (int i = 0; i < cases; ++i) {
    const Real s = test::log_uniform(rng, Real(1e-2), Real(1e2));
    const Cone a = Cone::create(s * rng.uniform(Real(0.2), Real(1)), s * rng.uniform(Real(0.2), Real(1))).value();
    const Cone b = Cone::create(s * rng.uniform(Real(0.2), Real(1)), s * rng.uniform(Real(0.2), Real(1))).value();
    const Transform pa = rng.pose(i % 2 == 0 ? Real(0) : Real(1e3));
    const Real reach = a.half_length() + b.half_length();
    const Transform pb =
        coaxial_pose(pa, rng.uniform(Real(0), Real(6.283)), i % 3 == 0, rng.uniform(Real(-2), Real(2)) * reach);
    const DistanceResult d = distance(a, pa, b, pb);
    ASSERT_EQ(d.method, PairMethod::Analytic) << describe(a, pa, b, pb, d);
    meeting += d.signed_distance < Real(0) ? 1 : 0;
    const double ulps = test::check_closed_form_answer(
        a, pa, b, pb, d,
        [](const Cone& shape, const Transform& p, const Vec3& x) { return surface_distance(shape, p, x); },
        describe(a, pa, b, pb, d));
    if (ulps > worst_ulps) {
      worst_ulps = ulps;
      worst_case = describe(a, pa, b, pb, d);
    }
  }
  EXPECT_LE(worst_ulps, test::kClosedFormUlps) << "worst case: " << worst_case;
  EXPECT_GT(meeting, cases / 4);
  EXPECT_LT(meeting, cases - cases / 4);
}

// Axes turned apart, or B's centre moved off A's axis, beyond rounding go to the generic
// ladder, which agrees with the closed form to first order in the change.
TEST(ConeCone, OffAxisOrTurnedGoesToTheGenericLadder) {
  const Cone c = Cone::create(Real(1), Real(2)).value();
  const Transform pa{Vec3(Real(0)), kIdentityQuat};
  const Vec3 centre(Real(0), Real(0), Real(3.5));
  const DistanceResult coaxial = distance(c, pa, c, Transform{centre, kIdentityQuat});
  EXPECT_EQ(coaxial.method, PairMethod::Analytic);
  EXPECT_NEAR(coaxial.signed_distance, Real(-0.5), Real(16) * kEpsilon * Real(4));  // A's apex in B's base
  for (const Real change : {Real(1e-3), Real(1e-2)}) {
    const DistanceResult turned =
        distance(c, pa, c, Transform{centre, glm::angleAxis(change, Vec3(Real(0), Real(1), Real(0)))});
    const DistanceResult moved = distance(c, pa, c, Transform{centre + Vec3(change, Real(0), Real(0)), kIdentityQuat});
    EXPECT_NE(turned.method, PairMethod::Analytic) << change;
    EXPECT_NE(moved.method, PairMethod::Analytic) << change;
    EXPECT_NEAR(turned.signed_distance, coaxial.signed_distance, Real(8) * change) << change;
    EXPECT_NEAR(moved.signed_distance, coaxial.signed_distance, Real(8) * change) << change;
  }
}

}  // namespace test_cone_cone
}  // namespace proxima
