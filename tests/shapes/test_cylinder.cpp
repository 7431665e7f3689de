// Cylinder: every member checked against references the cylinder does not compute itself.
// The surface is written here as three parametric patches (side and two caps) evaluated in
// double: dense samples give brute-force answers, and a pattern search started from the
// best sample of each patch refines them to the precision of double (support, world box,
// closest point). The test's own implicit function max(rho - r, |z| - h) checks contains
// and drives the ray marching; mass properties are checked against closed forms (including
// the parallel-axis form about a cap) and a grid integration.
#include <gtest/gtest.h>

#include <proxima/core/tolerance.hpp>
#include <proxima/shapes/cylinder.hpp>
#include <proxima/shapes/placed.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <utility>
#include <vector>

#include "shapes/reference_surface.hpp"
#include "shapes/shape_test_util.hpp"
#include "support/random.hpp"

namespace proxima {
namespace test_cylinder {

using test::DPose, test::DVec3, test::march, test::MarchResult, test::kPiD, test::Patch, test::RefSurface, test::Sample,
    test::to_d;

// Length tolerance at scale `scale`: a fixed multiple of Real's relative tolerance.
Real tol_at(double scale) { return static_cast<Real>(4.0 * static_cast<double>(kRelativeTolerance) * scale); }

// ---------------------------------------------------------------------------------------
// Cylinder-specific references.

Cylinder make(Real r, Real h) { return Cylinder::create(r, h).value(); }

RefSurface cylinder_surface(double r, double h) {
  std::vector<Patch> p;
  p.push_back({0.0, 2.0 * kPiD, -h, h, true, 241, 61,
               [r](double a, double b) { return DVec3(r * std::cos(a), r * std::sin(a), b); }});
  for (const double zc : {h, -h}) {
    p.push_back({0.0, 2.0 * kPiD, 0.0, r, true, 241, 41,
                 [zc](double a, double b) { return DVec3(b * std::cos(a), b * std::sin(a), zc); }});
  }
  return RefSurface(std::move(p));
}

// Signed lower bound of the distance to the surface (exact inside and off the faces):
// max(rho - r, |z| - h).
double implicit(double r, double h, const DVec3& p) { return std::max(std::hypot(p.x, p.y) - r, std::abs(p.z) - h); }

struct Dims {
  Real r, h;
};

// Round, flat, long, aspect ratios 1e-3 and 1e3, huge and tiny.
const std::vector<Dims>& sweep_dims() {
  static const std::vector<Dims> dims = {
      {Real(1), Real(1)},    {Real(0.4), Real(1.7)}, {Real(2.5), Real(0.3)},
      {Real(1), Real(1e-3)}, {Real(1e-3), Real(1)},  {Real(1e3), Real(1)},
      {Real(1), Real(1e3)},  {Real(1e4), Real(2e4)}, {Real(2e-4), Real(1e-4)},
  };
  return dims;
}

// Random query point: uniform in the box inflated by half its size, on the axis, near a
// rim, or near a surface sample.
Vec3 random_query(test::Random& rng, const RefSurface& ref, Real r, Real h, int i) {
  const Vec3 e(Real(1.5) * r, Real(1.5) * r, Real(1.5) * h);
  switch (i % 5) {
    case 0:
    case 1: return rng.in_box(-e, e);
    case 2: return Vec3(0, 0, rng.uniform(-e.z, e.z));
    case 3: {
      const Real a = rng.uniform(Real(0), Real(2) * kPi);
      const Real s = std::max(r, h);
      const Vec3 jitter = rng.vec3(Real(-0.01) * s, Real(0.01) * s);
      return Vec3(r * std::cos(a), r * std::sin(a), rng.uniform(Real(0), Real(1)) < Real(0.5) ? h : -h) + jitter;
    }
    default: {
      const auto& s = ref.samples();
      const Sample& smp = s[static_cast<std::size_t>(rng.integer(0, static_cast<int>(s.size()) - 1))];
      const Real sc = std::max(r, h);
      return Vec3(smp.p) + rng.vec3(Real(-0.02) * sc, Real(0.02) * sc);
    }
  }
}

// Full closest-point check of one query against the refined reference.
void check_closest(const Cylinder& c, const RefSurface& ref, const Vec3& q) {
  const double r = c.radius();
  const double h = c.half_length();
  const double scale = std::max({r, h, static_cast<double>(test::max_abs(q))});
  const Real tol = tol_at(scale);
  const SurfacePoint sp = c.closest_point(q);
  ASSERT_TRUE(test::all_finite(sp.point) && test::all_finite(sp.normal) && std::isfinite(sp.signed_distance));
  const DVec3 qd = to_d(q);
  const DVec3 pd = to_d(sp.point);
  const double dist = std::abs(static_cast<double>(sp.signed_distance));
  // On the surface, at the reported distance, no farther than the refined reference.
  EXPECT_LE(std::abs(implicit(r, h, pd)), tol) << "point off the surface, query " << q.x << " " << q.y << " " << q.z;
  EXPECT_NEAR(glm::length(qd - pd), dist, tol);
  const auto best = ref.minimize([&qd](const DVec3& s) { return glm::length(s - qd); });
  EXPECT_LE(dist, best.first + tol) << "query " << q.x << " " << q.y << " " << q.z;
  // Sign agrees with contains (exactly) and with the implicit function away from the surface.
  if (sp.signed_distance < Real(0)) {
    EXPECT_TRUE(c.contains(q));
  }
  if (sp.signed_distance > Real(0)) {
    EXPECT_FALSE(c.contains(q));
  }
  const double f = implicit(r, h, qd);
  if (f < -tol) {
    EXPECT_LT(sp.signed_distance, Real(0)) << "query " << q.x << " " << q.y << " " << q.z;
  }
  if (f > tol) {
    EXPECT_GT(sp.signed_distance, Real(0)) << "query " << q.x << " " << q.y << " " << q.z;
  }
  // Unit normal of a supporting plane at the point; for q outside, along q - point.
  const DVec3 n = to_d(sp.normal);
  EXPECT_NEAR(glm::length(n), 1.0, 1e2 * static_cast<double>(kEpsilon));
  const double support_n = ref.maximize([&n](const DVec3& s) { return glm::dot(s, n); });
  EXPECT_LE(support_n, glm::dot(pd, n) + tol)
      << "normal is not a supporting plane, query " << q.x << " " << q.y << " " << q.z;
  if (f > tol && dist > 1e3 * tol) {
    const DVec3 dir = (qd - pd) / glm::length(qd - pd);
    EXPECT_NEAR(glm::length(n - dir), 0.0, 1e2 * static_cast<double>(tol) / dist);
  }
}

// ---------------------------------------------------------------------------------------

TEST(Cylinder, CreateValidatesEachField) {
  test::expect_positive_field_validated([](Real x) { return Cylinder::create(x, Real(1)); }, "radius");
  test::expect_positive_field_validated([](Real x) { return Cylinder::create(Real(1), x); }, "half_length");
  EXPECT_TRUE(Cylinder::create(Real(1e-20), Real(1e-20)).ok());
  EXPECT_TRUE(Cylinder::create(kMaxCoordinate, kMaxCoordinate).ok());
}

TEST(Cylinder, AccessorsAndCore) {
  const Cylinder c = make(Real(2), Real(3));
  EXPECT_EQ(Cylinder::kType, ShapeType::Cylinder);
  EXPECT_EQ(c.radius(), Real(2));
  EXPECT_EQ(c.half_length(), Real(3));
  EXPECT_EQ(c.core_radius(), Real(0));
  test::Random rng(2001);
  for (int i = 0; i < 100; ++i) {
    const Vec3 d = rng.vec3(Real(-1), Real(1));
    EXPECT_EQ(c.core_support(d), c.support(d));
  }
  const Aabb local = c.local_aabb();
  EXPECT_EQ(local.min, Vec3(-2, -2, -3));
  EXPECT_EQ(local.max, Vec3(2, 2, 3));
}

TEST(Cylinder, SupportMatchesRefinedSurfaceMaximum) {
  test::Random rng(2002);
  for (const Dims& dm : sweep_dims()) {
    const Cylinder c = make(dm.r, dm.h);
    const RefSurface ref = cylinder_surface(dm.r, dm.h);
    const Real tol = tol_at(std::max(dm.r, dm.h));
    for (int i = 0; i < 300; ++i) {
      // Random directions, some exactly along or across the axis.
      Vec3 d = rng.unit_vector();
      if (i % 10 == 0) d = Vec3(0, 0, i % 20 == 0 ? 1 : -1);
      if (i % 10 == 1) d.z = 0;
      d *= rng.uniform(Real(1e-3), Real(1e3));
      const Vec3 s = c.support(d);
      ASSERT_TRUE(test::all_finite(s));
      const DVec3 dd = to_d(d) / glm::length(to_d(d));
      // A point of the solid (on its surface), as far along d as the surface maximum.
      EXPECT_LE(std::abs(implicit(dm.r, dm.h, to_d(s))), tol);
      const double ref_max = ref.maximize([&dd](const DVec3& p) { return glm::dot(p, dd); });
      EXPECT_GE(glm::dot(to_d(s), dd), ref_max - tol) << "direction " << d.x << " " << d.y << " " << d.z;
    }
  }
}

TEST(Cylinder, SupportOfDegenerateDirections) {
  const Cylinder c = make(Real(2), Real(1));
  EXPECT_EQ(c.support(Vec3(0)), Vec3(0, 0, 1));
  EXPECT_EQ(c.support(Vec3(0, 0, -5)), Vec3(0, 0, -1));
  const Real tiny = std::numeric_limits<Real>::denorm_min();
  const Real huge = std::numeric_limits<Real>::max();
  // Denormal and huge directions keep their meaning (no underflow to the axis, no overflow).
  test::expect_vec_near(c.support(Vec3(tiny, 0, -tiny)), Vec3(2, 0, -1), tol_at(2));
  test::expect_vec_near(c.support(Vec3(huge, huge, huge)), Vec3(std::sqrt(Real(2)), std::sqrt(Real(2)), 1), tol_at(2));
  test::expect_vec_near(c.support(Vec3(-huge, 0, -huge)), Vec3(-2, 0, -1), tol_at(2));
}

TEST(Cylinder, WorldAabbIsTheExactBoxOfTheSurface) {
  test::Random rng(2003);
  for (const Dims& dm : sweep_dims()) {
    const Cylinder c = make(dm.r, dm.h);
    const RefSurface ref = cylinder_surface(dm.r, dm.h);
    const double size = std::max(dm.r, dm.h);
    for (int i = 0; i < 40; ++i) {
      Transform pose = rng.pose(Real(3) * static_cast<Real>(size));
      if (i == 0) pose.rotation = kIdentityQuat;
      if (i == 1) pose.rotation = glm::angleAxis(kPi / 2, Vec3(1, 0, 0));
      const DPose dp(pose);
      const Aabb box = c.world_aabb(pose);
      const Real tol = tol_at(4 * size);
      for (int a = 0; a < 3; ++a) {
        const double hi = ref.maximize([&dp, a](const DVec3& p) { return dp.apply(p)[a]; });
        const double lo = -ref.maximize([&dp, a](const DVec3& p) { return -dp.apply(p)[a]; });
        // Contains every surface point (the refined extreme is a surface point) and is tight.
        EXPECT_NEAR(box.max[a], hi, tol) << "pose " << i << " axis " << a;
        EXPECT_NEAR(box.min[a], lo, tol) << "pose " << i << " axis " << a;
      }
      // And every sample, transformed in Real, lies in the box.
      for (std::size_t k = 0; k < ref.samples().size(); k += 7) {
        const Vec3 w = pose.apply(Vec3(ref.samples()[k].p));
        EXPECT_TRUE(box.inflated(tol).contains(w)) << "pose " << i << " sample " << k;
      }
    }
  }
}

TEST(Cylinder, ContainsMatchesImplicitFunction) {
  test::Random rng(2004);
  for (const Dims& dm : sweep_dims()) {
    const Cylinder c = make(dm.r, dm.h);
    const Real tol = tol_at(std::max(dm.r, dm.h));
    const Vec3 half(Real(1.3) * dm.r, Real(1.3) * dm.r, Real(1.3) * dm.h);
    int in = 0;
    int out = 0;
    for (int i = 0; i < 5000; ++i) {
      const Vec3 p = rng.in_box(-half, half);
      const double f = implicit(dm.r, dm.h, to_d(p));
      if (std::abs(f) <= tol) continue;
      EXPECT_EQ(c.contains(p), f < 0) << p.x << " " << p.y << " " << p.z;
      (f < 0 ? in : out) += 1;
    }
    EXPECT_GT(in, 1000);
    EXPECT_GT(out, 1000);
    // The boundary counts as inside: cap centres, rim points, side points.
    EXPECT_TRUE(c.contains(Vec3(0)));
    EXPECT_TRUE(c.contains(Vec3(0, 0, dm.h)));
    EXPECT_TRUE(c.contains(Vec3(0, 0, -dm.h)));
    EXPECT_TRUE(c.contains(Vec3(dm.r, 0, dm.h)));
    EXPECT_TRUE(c.contains(Vec3(0, -dm.r, 0)));
    EXPECT_FALSE(c.contains(Vec3(0, 0, dm.h * Real(1.001))));
    EXPECT_FALSE(c.contains(Vec3(dm.r * Real(1.001), 0, 0)));
  }
}

TEST(Cylinder, ClosestPointMatchesRefinedBruteForce) {
  test::Random rng(2005);
  for (const Dims& dm : sweep_dims()) {
    const Cylinder c = make(dm.r, dm.h);
    const RefSurface ref = cylinder_surface(dm.r, dm.h);
    for (int i = 0; i < 150; ++i) check_closest(c, ref, random_query(rng, ref, dm.r, dm.h, i));
  }
}

TEST(Cylinder, ClosestPointNamedCases) {
  const Cylinder c = make(Real(2), Real(3));
  const RefSurface ref = cylinder_surface(2, 3);
  const Real tol = tol_at(4);
  // Inside, nearer the side.
  SurfacePoint sp = c.closest_point(Vec3(Real(1.5), 0, Real(0.5)));
  test::expect_vec_near(sp.point, Vec3(2, 0, Real(0.5)), tol);
  test::expect_vec_near(sp.normal, Vec3(1, 0, 0), tol);
  EXPECT_NEAR(sp.signed_distance, Real(-0.5), tol);
  // Inside, nearer the bottom cap.
  sp = c.closest_point(Vec3(Real(0.3), Real(-0.2), Real(-2.5)));
  test::expect_vec_near(sp.point, Vec3(Real(0.3), Real(-0.2), -3), tol);
  test::expect_vec_near(sp.normal, Vec3(0, 0, -1), tol);
  EXPECT_NEAR(sp.signed_distance, Real(-0.5), tol);
  // The centre: the side is nearer (2 < 3), any radial direction.
  sp = c.closest_point(Vec3(0));
  EXPECT_NEAR(sp.signed_distance, Real(-2), tol);
  EXPECT_NEAR(glm::length(sp.normal), Real(1), tol);
  EXPECT_NEAR(sp.normal.z, Real(0), tol);
  // On the axis above the cap, and inside on the axis near the cap.
  sp = c.closest_point(Vec3(0, 0, 7));
  test::expect_vec_near(sp.point, Vec3(0, 0, 3), tol);
  test::expect_vec_near(sp.normal, Vec3(0, 0, 1), tol);
  EXPECT_NEAR(sp.signed_distance, Real(4), tol);
  sp = c.closest_point(Vec3(0, 0, Real(-2.25)));
  test::expect_vec_near(sp.point, Vec3(0, 0, -3), tol);
  EXPECT_NEAR(sp.signed_distance, Real(-0.75), tol);
  // Beyond the rim: the rim circle, normal along the diagonal.
  sp = c.closest_point(Vec3(0, 5, 7));
  test::expect_vec_near(sp.point, Vec3(0, 2, 3), tol);
  test::expect_vec_near(sp.normal, Vec3(0, Real(0.6), Real(0.8)), tol);
  EXPECT_NEAR(sp.signed_distance, Real(5), tol);
  // Exactly on the rim, on a cap, on the side: distance 0.
  for (const Vec3& p : {Vec3(2, 0, 3), Vec3(0, -2, -3), Vec3(1, 1, 3), Vec3(0, 2, Real(-1.25))}) {
    sp = c.closest_point(p);
    EXPECT_EQ(sp.signed_distance, Real(0)) << p.x << " " << p.y << " " << p.z;
    test::expect_vec_near(sp.point, p, tol);
    check_closest(c, ref, p);
  }
  // Equidistant from side and cap (a tie): either face, distance -1.
  sp = c.closest_point(Vec3(1, 0, 2));
  EXPECT_NEAR(sp.signed_distance, Real(-1), tol);
  for (const Vec3& p : {Vec3(0), Vec3(1, 0, 2), Vec3(0, 0, 7), Vec3(0, 5, 7), Vec3(0, 0, Real(-2.25))}) {
    check_closest(c, ref, p);
  }
}

TEST(Cylinder, ClosestPointPlacedFarFromOrigin) {
  test::Random rng(2006);
  const Cylinder c = make(Real(0.5), Real(2));
  const RefSurface ref = cylinder_surface(0.5, 2);
  for (int i = 0; i < 100; ++i) {
    const Transform pose{rng.vec3(Real(-1e4), Real(1e4)), rng.rotation()};
    const Vec3 local = random_query(rng, ref, Real(0.5), Real(2), i);
    const Vec3 q = pose.apply(local);
    const SurfacePoint sp = closest_point(c, pose, q);
    // Coordinates of 1e4 carry an absolute rounding error of ~1e4 * epsilon.
    const Real tol = tol_at(4e4);
    const DPose dp(pose);
    const DVec3 qd = dp.apply(to_d(local));
    const auto best = ref.minimize([&](const DVec3& s) { return glm::length(dp.apply(s) - qd); });
    EXPECT_LE(std::abs(sp.signed_distance), best.first + tol);
    EXPECT_NEAR(glm::length(q - sp.point), std::abs(sp.signed_distance), tol);
    EXPECT_LE(std::abs(implicit(0.5, 2, to_d(pose.inverse_apply(sp.point)))), tol);
  }
}

TEST(Cylinder, RaycastMatchesMarching) {
  test::Random rng(2007);
  int hits = 0;
  int misses = 0;
  for (const Dims& dm : sweep_dims()) {
    const Cylinder c = make(dm.r, dm.h);
    const RefSurface ref = cylinder_surface(dm.r, dm.h);
    const double size = std::max(dm.r, dm.h);
    const Real tol = tol_at(8 * size);
    const auto f = [&dm](const DVec3& p) { return implicit(dm.r, dm.h, p); };
    const auto inside = [&c](const Vec3& p) { return c.contains(p); };
    for (int i = 0; i < 300; ++i) {
      const Vec3 e(Real(2) * dm.r, Real(2) * dm.r, Real(2) * dm.h);
      const Vec3 o = rng.in_box(-e, e);
      const Vec3 target = rng.in_box(-e, e) * Real(0.5);
      Vec3 dir = target - o;
      if (i % 7 == 0) dir = Vec3(0, 0, o.z > 0 ? -1 : 1) * static_cast<Real>(size);  // along the axis
      if (i % 7 == 1) dir.z = 0;                                                     // across the axis
      if (!(glm::length(dir) > Real(0))) continue;
      const Real max_t = rng.uniform(Real(0.2), Real(3));
      const Ray ray{o, dir};
      const auto hit = c.raycast(ray, max_t);
      const MarchResult m = march(f, inside, ray, max_t, tol, 4000);
      const double len = glm::length(to_d(dir));
      const double t_tol = tol / len;
      if (m.deep) {
        ASSERT_TRUE(hit.has_value()) << "missed ray " << i;
        EXPECT_LE(hit->t, m.t_deep + t_tol);
      }
      if (!hit) {
        ++misses;
        continue;
      }
      ++hits;
      EXPECT_GE(hit->t, Real(0));
      EXPECT_LE(hit->t, max_t);
      test::expect_vec_near(hit->point, ray.at(hit->t), tol);
      EXPECT_NEAR(glm::length(hit->normal), Real(1), Real(1e2) * kEpsilon);
      if (hit->t == Real(0) && c.contains(o)) {
        test::expect_vec_near(hit->normal, -dir / glm::length(dir), Real(1e2) * kEpsilon);
        continue;
      }
      // On the surface, nothing deep inside before it, and as early as the bisected entry.
      EXPECT_LE(std::abs(implicit(dm.r, dm.h, to_d(hit->point))), tol) << "ray " << i;
      EXPECT_FALSE(m.deep && m.t_deep < hit->t - t_tol) << "ray " << i;
      if (m.entered) {
        EXPECT_NEAR(hit->t, m.t_bisect, t_tol) << "ray " << i;
      }
      // The normal faces the ray and is a supporting plane at the hit.
      const DVec3 n = to_d(hit->normal);
      EXPECT_LE(glm::dot(n, to_d(dir)), 0.0 + tol);
      const double support_n = ref.maximize([&n](const DVec3& s) { return glm::dot(s, n); });
      EXPECT_LE(support_n, glm::dot(to_d(hit->point), n) + tol) << "ray " << i;
    }
  }
  EXPECT_GT(hits, 500);
  EXPECT_GT(misses, 300);
}

TEST(Cylinder, RaycastNamedCases) {
  const Cylinder c = make(Real(1), Real(2));
  const Real tol = tol_at(8);
  // Onto the side, direction of length 2: t in units of |direction|.
  auto hit = c.raycast(Ray{Vec3(-5, 0, Real(0.5)), Vec3(2, 0, 0)}, Real(10));
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->t, Real(2), tol);
  test::expect_vec_near(hit->normal, Vec3(-1, 0, 0), tol);
  // Onto the top cap along the axis.
  hit = c.raycast(Ray{Vec3(Real(0.2), Real(0.1), 6), Vec3(0, 0, -1)}, Real(10));
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->t, Real(4), tol);
  test::expect_vec_near(hit->normal, Vec3(0, 0, 1), tol);
  // Parallel to the axis, just outside the side: miss.
  EXPECT_FALSE(c.raycast(Ray{Vec3(Real(1.01), 0, 6), Vec3(0, 0, -1)}, Real(100)));
  // Parallel to a cap, just above it: miss.
  EXPECT_FALSE(c.raycast(Ray{Vec3(-5, 0, Real(2.01)), Vec3(1, 0, 0)}, Real(100)));
  // Too short, and pointing away.
  EXPECT_FALSE(c.raycast(Ray{Vec3(-5, 0, 0), Vec3(1, 0, 0)}, Real(3.9)));
  EXPECT_FALSE(c.raycast(Ray{Vec3(-5, 0, 0), Vec3(-1, 0, 0)}, Real(100)));
  // Origin inside: t = 0 with normal -direction / |direction|.
  hit = c.raycast(Ray{Vec3(0, Real(0.5), 1), Vec3(0, 3, 0)}, Real(10));
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->t, Real(0));
  test::expect_vec_near(hit->normal, Vec3(0, -1, 0), tol);
  // Zero direction: hits only from inside.
  EXPECT_TRUE(c.raycast(Ray{Vec3(0, 0, 1), Vec3(0)}, Real(1)));
  EXPECT_FALSE(c.raycast(Ray{Vec3(0, 0, 3), Vec3(0)}, Real(1)));
  // Placed far from the origin.
  const Transform pose{Vec3(Real(1e4), Real(-2e4), Real(5e3)), glm::angleAxis(kPi / 2, Vec3(1, 0, 0))};
  hit = raycast(c, pose, Ray{pose.position + Vec3(0, -10, 0), Vec3(0, 1, 0)}, Real(20));
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->t, Real(8), tol_at(4e4));
  test::expect_vec_near(hit->normal, Vec3(0, -1, 0), tol_at(1e2));
}

// Closed forms written here: V = pi r^2 L, I_axis = m r^2 / 2, I_transverse about the
// centroid = m (3 r^2 + L^2) / 12; and independently the transverse inertia about a cap
// diameter, m (r^2 / 4 + L^2 / 3), shifted to the centroid by the parallel-axis theorem.
MassProperties analytic_mass(double r, double h, double density) {
  const double len = 2 * h;
  const double m = density * kPiD * r * r * len;
  MassProperties mp;
  mp.volume = static_cast<Real>(kPiD * r * r * len);
  mp.mass = static_cast<Real>(m);
  mp.inertia = Mat3(Real(0));
  mp.inertia[0][0] = mp.inertia[1][1] = static_cast<Real>(m * (3 * r * r + len * len) / 12);
  mp.inertia[2][2] = static_cast<Real>(m * r * r / 2);
  return mp;
}

TEST(Cylinder, MassPropertiesMatchClosedForms) {
  for (const Dims& dm : sweep_dims()) {
    const double r = dm.r;
    const double h = dm.h;
    const double density = 2.5;
    const MassProperties got = make(dm.r, dm.h).mass_properties(Real(2.5));
    test::expect_mass_near(got, analytic_mass(r, h, density), tol_at(1), tol_at(h));
    // Parallel-axis cross-check about a cap diameter.
    const double m = density * kPiD * r * r * 2 * h;
    const double about_cap = m * (r * r / 4 + (2 * h) * (2 * h) / 3);
    EXPECT_NEAR(got.inertia[0][0], about_cap - m * h * h, tol_at(about_cap));
    EXPECT_EQ(got.centroid, Vec3(0));
    for (int a = 0; a < 3; ++a) {
      for (int b = 0; b < 3; ++b) {
        if (a != b) {
          EXPECT_EQ(got.inertia[a][b], Real(0));
        }
      }
    }
  }
  // Default density 1.
  EXPECT_NEAR(make(1, 1).mass_properties().mass, Real(2) * kPi, tol_at(7));
}

TEST(Cylinder, MassPropertiesMatchGridIntegration) {
  for (const Dims& dm : {Dims{Real(1), Real(1)}, Dims{Real(0.5), Real(2)}, Dims{Real(3), Real(0.25)}}) {
    const Cylinder c = make(dm.r, dm.h);
    const auto inside = [&dm](const Vec3& p) { return implicit(dm.r, dm.h, to_d(p)) <= 0; };
    const MassProperties grid = test::integrate_mass_on_grid(inside, c.local_aabb(), 120, Real(3));
    test::expect_mass_near(c.mass_properties(Real(3)), grid, Real(0.01), Real(0.01) * std::max(dm.r, dm.h));
  }
}

TEST(Cylinder, NeverNaN) {
  const Real huge = std::numeric_limits<Real>::max() / Real(8);
  const Real tiny = std::numeric_limits<Real>::denorm_min();
  for (const Dims& dm : {Dims{Real(1), Real(1)}, Dims{Real(1e-3), Real(1e3)}, Dims{kMaxCoordinate, Real(1e-20)}}) {
    const Cylinder c = make(dm.r, dm.h);
    for (const Vec3& p :
         {Vec3(0), Vec3(tiny, 0, 0), Vec3(0, 0, tiny), Vec3(tiny, -tiny, tiny), Vec3(kMaxCoordinate, 0, 0),
          Vec3(0, 0, -kMaxCoordinate), Vec3(kMaxCoordinate, kMaxCoordinate, kMaxCoordinate)}) {
      const SurfacePoint sp = c.closest_point(p);
      EXPECT_TRUE(test::all_finite(sp.point) && test::all_finite(sp.normal) && std::isfinite(sp.signed_distance));
      EXPECT_NEAR(glm::length(sp.normal), Real(1), Real(1e2) * kEpsilon);
      (void)c.contains(p);
      EXPECT_TRUE(test::all_finite(c.support(p)));
      EXPECT_TRUE(test::all_finite(c.support(p * (huge / std::max(Real(1), test::max_abs(p))))));
      const auto hit = c.raycast(Ray{p, Vec3(1, 2, 3)}, Real(10));
      if (hit) {
        EXPECT_TRUE(test::all_finite(hit->point) && test::all_finite(hit->normal));
      }
    }
    const Aabb box = c.world_aabb(Transform{Vec3(0), glm::angleAxis(Real(0.3), glm::normalize(Vec3(1, 2, 3)))});
    EXPECT_TRUE(box.is_valid() && test::all_finite(box.min) && test::all_finite(box.max));
  }
}

TEST(Cylinder, NonFiniteQueriesHaveDefinedAnswers) {
  test::ScopedNoFpTraps no_traps;
  const Cylinder s = make(Real(1), Real(2));
  const Real nan = test::nan_value();
  const Real inf = test::inf_value();
  for (const Vec3& p : {Vec3(nan, 0, 0), Vec3(0, inf, 0), Vec3(0, 0, -inf), Vec3(nan, nan, nan)}) {
    EXPECT_FALSE(s.contains(p));
    const SurfacePoint sp = s.closest_point(p);
    EXPECT_TRUE(test::all_finite(sp.point) && test::all_finite(sp.normal));
    EXPECT_EQ(sp.signed_distance, inf);
    EXPECT_TRUE(test::all_finite(s.support(p)));
    EXPECT_FALSE(s.raycast(Ray{p, Vec3(1, 0, 0)}, Real(10)));
    EXPECT_FALSE(s.raycast(Ray{Vec3(0), p}, Real(10)));
  }
  // max_t: NaN and negative never hit, +infinity is allowed.
  EXPECT_FALSE(s.raycast(Ray{Vec3(0), Vec3(1, 0, 0)}, nan));
  EXPECT_FALSE(s.raycast(Ray{Vec3(-50, 0, 0), Vec3(1, 0, 0)}, Real(-1)));
  const auto hit = s.raycast(Ray{Vec3(-50, 0, 0), Vec3(1, 0, 0)}, inf);
  ASSERT_TRUE(hit.has_value());
  EXPECT_TRUE(test::all_finite(hit->point) && std::isfinite(hit->t));
}

}  // namespace test_cylinder
}  // namespace proxima
