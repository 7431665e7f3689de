// Two cylinders with parallel axes: the closed form (cylinder_cylinder.cpp) against references
// that share no code with it (pair_reference.hpp, long double): the overlap of the two
// cylinders' support functions along the reported normal is the reported depth (minus the
// distance) within 8 ulps of the pair's size (64 in float), a search over directions finds
// no direction with less overlap, the witnesses lie on the surfaces, and the generic ladder
// agrees to its own precision. Axes turned apart by more than rounding go to the generic
// ladder. The exactness issue's example (defect 1): two cylinders of radius 1 and half
// length 1 side by side with centres 1.9 apart, depth 0.1 along the line between their axes
// (EPA's normal was 9e-4 off).
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
namespace {

using test::LD;
using test::LVec;

/// B's pose: A's rotation turned about its own axis by `spin`, flipped end over end when
/// `flip` (the axes stay parallel), its centre at `local` in A's frame.
Transform parallel_pose(const Transform& pa, Real spin, bool flip, const Vec3& local) {
  Quat q = pa.rotation * glm::angleAxis(spin, Vec3(Real(0), Real(0), Real(1)));
  if (flip) q = q * glm::angleAxis(kPi, Vec3(Real(1), Real(0), Real(0)));
  return Transform{pa.apply(local), q};
}

/// Signed distance of local point p from the cylinder's surface (long double, the cylinder's
/// definition): > 0 outside.
LD surface_distance(const Cylinder& c, const Transform& pose, const Vec3& world) {
  const test::LPose lp(pose);
  const LVec p = lp.to_local(test::ld(world));
  const LD rho = std::sqrt(p.x * p.x + p.y * p.y);
  const LD out_r = rho - LD(c.radius());
  const LD out_z = std::abs(p.z) - LD(c.half_length());
  if (out_r > 0 && out_z > 0) return std::sqrt(out_r * out_r + out_z * out_z);
  return std::max(out_r, out_z);
}

TEST(CylinderCylinder, ParallelSideBySideIsTheIssuesExample) {
  const Cylinder c = Cylinder::create(Real(1), Real(1)).value();
  test::Random rng(1901);
  for (int i = 0; i < 64; ++i) {
    const Transform pa = i == 0 ? Transform{Vec3(Real(0)), kIdentityQuat} : rng.pose(Real(10));
    const Transform pb = parallel_pose(pa, rng.uniform(Real(0), Real(6.283)), i % 2 == 1, Vec3(Real(1.9), 0, 0));
    const DistanceResult d = distance(c, pa, c, pb);
    const Vec3 x = pa.apply_vector(Vec3(Real(1), Real(0), Real(0)));
    const Real size = std::max(Real(2), max_abs_component(pa.position));
    EXPECT_EQ(d.method, PairMethod::Analytic) << i;
    EXPECT_NEAR(d.signed_distance, Real(-0.1), Real(16) * kEpsilon * size) << i;
    EXPECT_LE(glm::length(d.normal - x), Real(16) * kEpsilon * size) << i;
    EXPECT_TRUE(intersect(c, pa, c, pb)) << i;
    const ContactManifold m = collide(c, pa, c, pb);
    ASSERT_GE(m.count, 1) << i;
    EXPECT_EQ(m.normal, d.normal) << i;
    for (int k = 0; k < m.count; ++k) {
      EXPECT_NEAR(m.points[static_cast<std::size_t>(k)].depth, Real(0.1), Real(1e-3)) << i;
    }
  }
}

std::string describe(const Cylinder& a, const Transform& pa, const Cylinder& b, const Transform& pb,
                     const DistanceResult& d) {
  std::ostringstream o;
  o.precision(17);
  o << test::describe(Shape(a), pa) << " | " << test::describe(Shape(b), pb) << " sd=" << d.signed_distance;
  return o.str();
}

// Random parallel pairs: sizes 1e-2 to 1e2, A anywhere within 1e3 of the origin, B's centre
// around A's in A's frame so that every region is met (beside the barrel, over a cap, beyond
// a rim, inside nearer the barrel or the cap), B turned about its axis and flipped.
TEST(CylinderCylinder, ParallelAxesMatchTheSupportFunctionReferences) {
  test::Random rng(7717);
  const int cases = test::sweep_size(2000);
  double worst_ulps = 0;
  std::string worst_case;
  for (int i = 0; i < cases; ++i) {
    const Real s = test::log_uniform(rng, Real(1e-2), Real(1e2));
    const Cylinder a =
        Cylinder::create(s * rng.uniform(Real(0.2), Real(1)), s * rng.uniform(Real(0.2), Real(1))).value();
    const Cylinder b =
        Cylinder::create(s * rng.uniform(Real(0.2), Real(1)), s * rng.uniform(Real(0.2), Real(1))).value();
    const Transform pa = rng.pose(i % 2 == 0 ? Real(0) : Real(1e3));
    const Real reach_r = a.radius() + b.radius();
    const Real reach_z = a.half_length() + b.half_length();
    const Real angle = rng.uniform(Real(0), Real(6.283));
    const Real rho = rng.uniform(Real(0), Real(1.5)) * reach_r;
    const Vec3 local(rho * std::cos(angle), rho * std::sin(angle), rng.uniform(Real(-1.5), Real(1.5)) * reach_z);
    const Transform pb = parallel_pose(pa, rng.uniform(Real(0), Real(6.283)), i % 3 == 0, local);
    const DistanceResult d = distance(a, pa, b, pb);
    ASSERT_EQ(d.method, PairMethod::Analytic) << describe(a, pa, b, pb, d);
    const double ulps = test::check_closed_form_answer(
        a, pa, b, pb, d,
        [](const Cylinder& shape, const Transform& p, const Vec3& x) { return surface_distance(shape, p, x); },
        describe(a, pa, b, pb, d));
    if (ulps > worst_ulps) {
      worst_ulps = ulps;
      worst_case = describe(a, pa, b, pb, d);
    }
  }
  EXPECT_LE(worst_ulps, test::kClosedFormUlps) << "worst case: " << worst_case;
}

// Axes turned apart beyond rounding go to the generic ladder, which agrees with the closed
// form to first order in the angle; within rounding the closed form answers.
TEST(CylinderCylinder, TurnedAxesGoToTheGenericLadder) {
  const Cylinder c = Cylinder::create(Real(1), Real(2)).value();
  const Transform pa{Vec3(Real(0)), kIdentityQuat};
  const Vec3 centre(Real(1.5), Real(0.5), Real(1));
  for (const Real tilt : {Real(1e-3), Real(1e-2)}) {
    const Transform pb{centre, glm::angleAxis(tilt, Vec3(Real(0), Real(1), Real(0)))};
    const DistanceResult d = distance(c, pa, c, pb);
    EXPECT_NE(d.method, PairMethod::Analytic) << tilt;
    const DistanceResult parallel = distance(c, pa, c, Transform{centre, kIdentityQuat});
    EXPECT_EQ(parallel.method, PairMethod::Analytic);
    EXPECT_NEAR(d.signed_distance, parallel.signed_distance, Real(4) * tilt) << tilt;
  }
}

}  // namespace
}  // namespace proxima
