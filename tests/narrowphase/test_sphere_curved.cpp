// Tests of the closed-form sphere-cylinder, sphere-cone and sphere-ellipsoid routines: seeded
// sweeps at random poses (near the origin and far from it) against long double references
// written independently of the routines (cylinder and cone: the distance of the centre to
// the shape's meridian polygon as the minimum over its edges, and the depth inside as the
// nearest surface face; ellipsoid: the Lagrange condition x_i = e_i^2 y_i / (t + e_i^2) with
// its one root t > -min e_i^2 by plain bisection in long double), both the signed distance
// and the normal; the common convention checks (pair_check.hpp: witnesses, sampled minimum
// overlap, flip of intersect, manifold); self-consistency (the overlap along the reported
// normal equals the depth); and the named regressions of the exactness issue: a sphere
// inside a cylinder near its barrel, and a small sphere over a wide thin disc (the normal is
// the disc's axis however far from the centre).
#include <gtest/gtest.h>

#include <proxima/narrowphase/contact.hpp>
#include <proxima/narrowphase/narrowphase.hpp>

#include <array>
#include <string>

#include "narrowphase/pair_check.hpp"
#include "narrowphase/pairs_rounded.hpp"
#include "support/random.hpp"
#include "sweep_size.hpp"

namespace proxima {
namespace test_sphere_curved {

using test::LD;
using test::LVec;

// The reference answer in the shape's frame: core signed distance of the centre (< 0
// inside) and the unit normal from the sphere towards the shape; `ambiguous` when two faces
// (inside) or the closest point's direction (outside, within 1e-4 of the shape) leave the
// normal ill-conditioned.
struct RefAnswer {
  LD core = 0;
  LVec normal{0, 0, 1};
  bool ambiguous = false;
};

// Closest point of the 2D segment p0 p1 to x (long double), as (rho, z) pairs.
struct P2 {
  LD r, z;
};
P2 closest_on_segment(P2 x, P2 p0, P2 p1) {
  const LD dr = p1.r - p0.r, dz = p1.z - p0.z;
  LD t = ((x.r - p0.r) * dr + (x.z - p0.z) * dz) / (dr * dr + dz * dz);
  t = std::clamp(t, LD(0), LD(1));
  return {p0.r + t * dr, p0.z + t * dz};
}

// Distance of x to the line through p0 p1, positive on the side of `outward` (unit 2D).
LD line_distance(P2 x, P2 p0, P2 outward) { return (x.r - p0.r) * outward.r + (x.z - p0.z) * outward.z; }

// The reference for a meridian polygon: `surface` edges (rho >= 0 side; the axis is not a
// surface) with their outward normals; `inside` says whether x is in the polygon.
template <std::size_t N>
RefAnswer meridian_reference(const LVec& c, const std::array<std::array<P2, 2>, N>& edges,
                             const std::array<P2, N>& outward, bool inside) {
  const LD rho = std::sqrt(c.x * c.x + c.y * c.y);
  const LVec u = rho > 0 ? LVec(c.x / rho, c.y / rho, 0) : LVec(1, 0, 0);
  const P2 x{rho, c.z};
  RefAnswer a;
  if (inside) {
    LD best = -1e300L, second = -1e300L;
    for (std::size_t k = 0; k < N; ++k) {
      const LD d = line_distance(x, edges[k][0], outward[k]);
      if (d > best) {
        second = best;
        best = d;
        a.normal = -(outward[k].r * u + LVec(0, 0, outward[k].z));
      } else if (d > second) {
        second = d;
      }
    }
    a.core = best;
    a.ambiguous = best - second < 1e-4L || rho < 1e-4L;
    return a;
  }
  LD best2 = 1e300L;
  P2 q{0, 0};
  for (const auto& e : edges) {
    const P2 p = closest_on_segment(x, e[0], e[1]);
    const LD d2 = (p.r - x.r) * (p.r - x.r) + (p.z - x.z) * (p.z - x.z);
    if (d2 < best2) {
      best2 = d2;
      q = p;
    }
  }
  a.core = std::sqrt(best2);
  const LVec diff = (q.r - x.r) * u + LVec(0, 0, q.z - x.z);
  a.normal = a.core > 0 ? diff / a.core : LVec(0, 0, 1);
  a.ambiguous = a.core < 1e-4L || rho < 1e-4L;
  return a;
}

RefAnswer reference(const Cylinder& b, const LVec& c) {
  const LD R = b.radius(), h = b.half_length();
  const std::array<std::array<P2, 2>, 3> edges{{{{{0, h}, {R, h}}}, {{{R, h}, {R, -h}}}, {{{R, -h}, {0, -h}}}}};
  const std::array<P2, 3> outward{{{0, 1}, {1, 0}, {0, -1}}};
  const LD rho = std::sqrt(c.x * c.x + c.y * c.y);
  return meridian_reference(c, edges, outward, rho <= R && std::abs(c.z) <= h);
}

RefAnswer reference(const Cone& b, const LVec& c) {
  const LD R = b.radius(), h = b.half_length();
  const LD L = std::sqrt(4 * h * h + R * R);
  const std::array<std::array<P2, 2>, 2> edges{{{{{0, h}, {R, -h}}}, {{{R, -h}, {0, -h}}}}};
  const std::array<P2, 2> outward{{{2 * h / L, R / L}, {0, -1}}};
  const LD rho = std::sqrt(c.x * c.x + c.y * c.y);
  const P2 x{rho, c.z};
  const bool inside = c.z >= -h && line_distance(x, edges[0][0], outward[0]) <= 0;
  return meridian_reference(c, edges, outward, inside);
}

// The ellipsoid's reference: the nearest point x of the surface sum (x_i / e_i)^2 = 1 to y
// satisfies x_i = e_i^2 y_i / (t + e_i^2) for the one root t > -min e_i^2 of
// F(t) = sum (e_i y_i / (t + e_i^2))^2 - 1 (F falls from +inf to -1 there), found by
// bisection in long double. Ambiguous where the centre lies within 1e-4 of the plane of the
// two larger axes inside (the nearest point is then not unique or F has no root there) or
// within 1e-4 of the surface (the direction y - x is ill-conditioned).
RefAnswer reference(const Ellipsoid& b, const LVec& y) {
  const LVec e(b.radii().x, b.radii().y, b.radii().z);
  const LD e_min = std::min({e.x, e.y, e.z});
  const auto F = [&](LD t) {
    LD f = -1;
    for (int i = 0; i < 3; ++i) {
      const LD q = e[i] * y[i] / (t + e[i] * e[i]);
      f += q * q;
    }
    return f;
  };
  LD lo = -e_min * e_min;
  LD hi = std::max(LD(1), test::lnorm(y)) * std::max({e.x, e.y, e.z}) * 4;
  while (F(hi) > 0) hi *= 2;
  for (int k = 0; k < 400 && hi - lo > 0; ++k) {
    const LD mid = lo + (hi - lo) / 2;
    if (mid <= lo || mid >= hi) break;
    (F(mid) > 0 ? lo : hi) = mid;
  }
  const LD t = (lo + hi) / 2;
  LVec x;
  for (int i = 0; i < 3; ++i) x[i] = e[i] * e[i] * y[i] / (t + e[i] * e[i]);
  const bool inside = (y.x / e.x) * (y.x / e.x) + (y.y / e.y) * (y.y / e.y) + (y.z / e.z) * (y.z / e.z) < 1;
  RefAnswer a;
  const LD dist = test::lnorm(y - x);
  a.core = inside ? -dist : dist;
  LVec grad(x.x / (e.x * e.x), x.y / (e.y * e.y), x.z / (e.z * e.z));
  a.normal = -grad / test::lnorm(grad);  // from the sphere towards the ellipsoid
  int minor = 0;
  for (int i = 1; i < 3; ++i)
    if (e[i] < e[minor]) minor = i;
  a.ambiguous = dist < 1e-4L || (inside && std::abs(y[minor]) < 1e-4L);
  return a;
}

// The largest extent of the shape, for the pair's size.
Real extent(const Cylinder& b) { return std::max(b.radius(), b.half_length()); }
Real extent(const Cone& b) { return std::max(b.radius(), b.half_length()); }
Real extent(const Ellipsoid& b) { return max_abs_component(b.radii()); }

// The smallest distance from the shape's axis that keeps the reference's radial direction
// well conditioned: the centre's distance from the axis (cylinder, cone), 1 for the
// ellipsoid (no axis).
LD axis_lever(const Cylinder& /*b*/, const LVec& c) { return std::sqrt(c.x * c.x + c.y * c.y); }
LD axis_lever(const Cone& /*b*/, const LVec& c) { return std::sqrt(c.x * c.x + c.y * c.y); }
LD axis_lever(const Ellipsoid& /*b*/, const LVec& /*c*/) { return 1; }

Transform random_pose(test::Random& rng, const Vec3& centre, Real extent) {
  Transform t = rng.pose(extent);
  t.position += centre;
  return t;
}

// One case: distance and normal against the reference, the convention checks, and the
// overlap along the reported normal.
template <class B>
void check_case(const Sphere& a, const Transform& pa, const B& b, const Transform& pb, Real cd,
                const std::string& ctx) {
  const Real size = a.radius() + extent(b);
  const Real far = std::max(max_abs_component(pa.position), max_abs_component(pb.position));
  const Real tol = test::pair_tol(far + size);
  const test::LPose lb(pb);
  const RefAnswer ref = reference(b, lb.to_local(test::ld(pa.position)));
  test::Reference r;
  r.has_distance = true;
  r.distance = ref.core - LD(a.radius());
  test::check_pair(a, pa, b, pb, r, tol, cd, ctx);
  const DistanceResult d = narrow::pair_distance(a, pa, b, pb, PairRequest{}, nullptr);
  if (!ref.ambiguous) {
    const LVec n_world = lb.rot.apply(ref.normal);
    // Normals from geometry: within a few ulps of the rotated reference. The centre's
    // coordinates in the shape's frame carry a rounding of about eps times the distance from
    // the origin, which turns the radial direction by that over rho (over the distance to a
    // rim or apex outside).
    const LVec c = lb.to_local(test::ld(pa.position));
    const LD lever = std::min({LD(1), axis_lever(b, c), ref.core > 0 ? ref.core : LD(1)});
    const LD bound = 64.0L * LD(kEpsilon) * (1 + LD(far)) / lever;
    const LD err = test::lnorm(test::ld(d.normal) - n_world);
    EXPECT_LE(double(err), double(bound)) << ctx << " normal error " << double(err);
  }
}

constexpr int kSweep = 2000;
const Vec3 kCentres[2] = {Vec3(Real(0)), Vec3(Real(300), Real(-200), Real(100))};

// kSweep random spheres against shapes from make_b, half near the origin, half far from it.
template <class MakeB>
void sweep(std::uint64_t seed, const std::string& name, MakeB make_b) {
  test::Random rng(seed);
  const int n = test::sweep_size(kSweep);
  for (int i = 0; i < n; ++i) {
    const Vec3 c = kCentres[i % 2];
    const Sphere a = Sphere::create(rng.uniform(Real(0.05), Real(1.2))).value();
    const auto b = make_b(rng);
    const Transform pa = random_pose(rng, c, Real(1.5));
    const Transform pb = random_pose(rng, c, Real(1.5));
    check_case(a, pa, b, pb, rng.uniform(Real(0), Real(0.2)), name + " " + std::to_string(i));
  }
}

TEST(SphereCylinderCone, SphereCylinderSweep) {
  sweep(301, "sphere-cylinder", [](test::Random& rng) {
    return Cylinder::create(rng.uniform(Real(0.1), Real(1.5)), rng.uniform(Real(0.02), Real(1.5))).value();
  });
}

TEST(SphereCylinderCone, SphereConeSweep) {
  sweep(302, "sphere-cone", [](test::Random& rng) {
    return Cone::create(rng.uniform(Real(0.1), Real(1.5)), rng.uniform(Real(0.05), Real(1.5))).value();
  });
}

TEST(SphereCylinderCone, SphereEllipsoidSweep) {
  sweep(304, "sphere-ellipsoid", [](test::Random& rng) {
    const Real x = rng.uniform(Real(0.05), Real(1.5));  // one draw per statement: the same
    const Real y = rng.uniform(Real(0.05), Real(1.5));  // case under GCC and clang
    const Real z = rng.uniform(Real(0.05), Real(1.5));
    return Ellipsoid::create(Vec3(x, y, z)).value();
  });
}

// Analytic ellipsoid cases: beyond each pole, and inside on an axis (the nearer pole wins).
TEST(SphereCylinderCone, SphereEllipsoidAnalytic) {
  const Sphere a = Sphere::create(Real(0.25)).value();
  const Ellipsoid b = Ellipsoid::create(Vec3(Real(2), Real(1), Real(0.5))).value();
  const Transform pb{Vec3(Real(0)), kIdentityQuat};
  const auto at = [](Real x, Real y, Real z) { return Transform{Vec3(x, y, z), kIdentityQuat}; };
  DistanceResult d = distance(a, at(3, 0, 0), b, pb);
  EXPECT_EQ(d.method, PairMethod::Analytic);
  EXPECT_NEAR(d.signed_distance, Real(0.75), Real(8) * kEpsilon);
  EXPECT_LE(glm::length(d.normal - Vec3(-1, 0, 0)), Real(8) * kEpsilon);
  d = distance(a, at(0, -1.5, 0), b, pb);
  EXPECT_NEAR(d.signed_distance, Real(0.25), Real(8) * kEpsilon);
  EXPECT_LE(glm::length(d.normal - Vec3(0, 1, 0)), Real(8) * kEpsilon);
  d = distance(a, at(0, 0, Real(0.3)), b, pb);  // inside, 0.2 under the top pole
  EXPECT_NEAR(d.signed_distance, Real(-0.45), Real(8) * kEpsilon);
  EXPECT_LE(glm::length(d.normal - Vec3(0, 0, -1)), Real(8) * kEpsilon);
  EXPECT_TRUE(intersect(a, at(0, 0, Real(0.3)), b, pb));
  EXPECT_FALSE(intersect(a, at(3, 0, 0), b, pb));
  EXPECT_TRUE(intersect(a, at(Real(2.2), 0, 0), b, pb));
}

// The case (defect 1): a sphere of radius 0.5 whose centre is inside a cylinder
// (radius 1, half length 1) 0.1 from its barrel: depth 0.6, normal towards the axis, exact
// to rounding at any orientation (EPA gave it 1e-3 off).
TEST(SphereCylinderCone, SphereInsideCylinderNearTheBarrel) {
  const Sphere a = Sphere::create(Real(0.5)).value();
  const Cylinder b = Cylinder::create(Real(1), Real(1)).value();
  test::Random rng(303);
  for (int i = 0; i < 64; ++i) {
    const Transform pb = rng.pose(Real(2));
    const Real angle = rng.uniform(Real(0), Real(6.283));
    const Real z = rng.uniform(Real(-0.3), Real(0.3));
    const Vec3 u_local(std::cos(angle), std::sin(angle), Real(0));
    const Transform pa{pb.apply(Real(0.9) * u_local + Vec3(Real(0), Real(0), z)), kIdentityQuat};
    const DistanceResult d = distance(a, pa, b, pb);
    const Vec3 exact = -pb.apply_vector(u_local);
    EXPECT_EQ(d.method, PairMethod::Analytic);
    EXPECT_NEAR(d.signed_distance, Real(-0.6), Real(32) * kEpsilon) << i;
    EXPECT_LE(glm::length(d.normal - exact), Real(32) * kEpsilon) << i;
    // Self-consistency: the overlap along the reported normal is the depth.
    const LVec n = test::ld(d.normal);
    EXPECT_NEAR(double(-test::overlap_along(a, pa, b, pb, n)), double(d.signed_distance), 32.0 * double(kEpsilon)) << i;
  }
}

// The case (defect 2): a sphere of radius 0.0015 over a thin disc (a cylinder of
// radius 9, half length 0.00125), its centre 7.5e-4 above the disc anywhere over it: the
// normal is the disc's axis exactly (differences of the nearby witnesses tilted it 1.6e-4),
// the depth 7.5e-4.
TEST(SphereCylinderCone, SmallSphereOverAThinDisc) {
  const Sphere a = Sphere::create(Real(0.0015)).value();
  const Cylinder b = Cylinder::create(Real(9), Real(0.00125)).value();
  const Transform pb{Vec3(Real(0)), kIdentityQuat};
  for (int ix = -6; ix <= 6; ++ix) {
    for (int iy = -6; iy <= 6; ++iy) {
      const Real x = Real(1.05) * Real(ix);
      const Real y = Real(1.05) * Real(iy);
      if (x * x + y * y > Real(80)) continue;
      const Transform pa{Vec3(x, y, Real(0.00125) + Real(7.5e-4)), kIdentityQuat};
      const DistanceResult d = distance(a, pa, b, pb);
      EXPECT_EQ(d.normal, Vec3(Real(0), Real(0), Real(-1))) << x << "," << y;
      EXPECT_NEAR(d.signed_distance, Real(-7.5e-4), Real(16) * kEpsilon * Real(9)) << x << "," << y;
      EXPECT_TRUE(intersect(a, pa, b, pb));
      const ContactManifold m = collide(a, pa, b, pb);
      ASSERT_EQ(m.count, 1);
      EXPECT_EQ(m.normal, d.normal);
    }
  }
}

// Analytic cone cases: over the apex, under the base, beside the slant, inside near the base.
TEST(SphereCylinderCone, SphereConeAnalytic) {
  const Sphere a = Sphere::create(Real(0.25)).value();
  const Cone b = Cone::create(Real(1), Real(1)).value();  // apex (0,0,1), base z = -1, radius 1
  const Transform pb{Vec3(Real(0)), kIdentityQuat};
  const auto at = [](Real x, Real y, Real z) { return Transform{Vec3(x, y, z), kIdentityQuat}; };
  // Over the apex by 1: distance 0.75, normal -z.
  DistanceResult d = distance(a, at(0, 0, 2), b, pb);
  EXPECT_NEAR(d.signed_distance, Real(0.75), Real(8) * kEpsilon);
  EXPECT_EQ(d.normal, Vec3(Real(0), Real(0), Real(-1)));
  // Under the base by 0.5: distance 0.25, normal +z.
  d = distance(a, at(Real(0.3), Real(-0.2), Real(-1.5)), b, pb);
  EXPECT_NEAR(d.signed_distance, Real(0.25), Real(8) * kEpsilon);
  EXPECT_EQ(d.normal, Vec3(Real(0), Real(0), Real(1)));
  // Beside the slant at height 0 (the slant passes (0.5, 0)), 1 out along its normal
  // (2, 1) / sqrt(5): distance 0.75, normal -(2, 0, 1) / sqrt(5).
  const Real s5 = std::sqrt(Real(5));
  d = distance(a, at(Real(0.5) + Real(2) / s5, 0, Real(1) / s5), b, pb);
  EXPECT_NEAR(d.signed_distance, Real(0.75), Real(16) * kEpsilon);
  EXPECT_LE(glm::length(d.normal + Vec3(Real(2), Real(0), Real(1)) / s5), Real(8) * kEpsilon);
  // Inside, 0.1 above the base on the axis: depth 0.35, normal +z.
  d = distance(a, at(0, 0, Real(-0.9)), b, pb);
  EXPECT_NEAR(d.signed_distance, Real(-0.35), Real(8) * kEpsilon);
  EXPECT_EQ(d.normal, Vec3(Real(0), Real(0), Real(1)));
}

}  // namespace test_sphere_curved
}  // namespace proxima
