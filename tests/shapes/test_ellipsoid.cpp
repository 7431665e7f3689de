// Ellipsoid: every member checked against references the ellipsoid does not compute itself.
// The surface is written here as the (theta, phi) parametric patch evaluated in double:
// dense samples give brute-force answers, and a pattern search started from the best sample
// refines them to the precision of double (support, world box, closest point). The test's
// own implicit functions ((x/a)^2 + (y/b)^2 + (z/c)^2 and its first-order distance) check
// contains and drive the ray marching; mass properties are checked against the second
// moments of the scaled unit ball and against a grid integration. The closest-point sweep
// covers the branches of Eberly's method: points on the axes, on the symmetry planes (inside
// and outside the evolute region), within 1e-30 of them, the centre, and radii ratios up to
// 1e6.
#include <gtest/gtest.h>

#include <proxima/core/tolerance.hpp>
#include <proxima/shapes/ellipsoid.hpp>
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
namespace test_ellipsoid {

using test::DPose, test::DVec3, test::march, test::MarchResult, test::kPiD, test::Patch, test::RefSurface, test::Sample,
    test::to_d;

// Length tolerance at scale `scale`: a fixed multiple of Real's relative tolerance.
Real tol_at(double scale) { return static_cast<Real>(4.0 * static_cast<double>(kRelativeTolerance) * scale); }
// ---------------------------------------------------------------------------------------
// Ellipsoid-specific references.

Ellipsoid make(const Vec3& radii) { return Ellipsoid::create(radii).value(); }

RefSurface ellipsoid_surface(const Vec3& radii) {
  const DVec3 r = to_d(radii);
  std::vector<Patch> p;
  // a = phi (periodic), b = theta from the +z pole.
  p.push_back({0.0, 2.0 * kPiD, 0.0, kPiD, true, 361, 181, [r](double a, double b) {
                 return DVec3(r.x * std::sin(b) * std::cos(a), r.y * std::sin(b) * std::sin(a), r.z * std::cos(b));
               }});
  return RefSurface(std::move(p));
}

double min_radius(const Vec3& r) { return std::min({r.x, r.y, r.z}); }
double max_radius(const Vec3& r) { return std::max({r.x, r.y, r.z}); }

// Signed lower bound of the distance to the surface (sign exact): (|p / R| - 1) * r_min.
double implicit(const Vec3& radii, const DVec3& p) {
  const DVec3 r = to_d(radii);
  return (glm::length(p / r) - 1.0) * min_radius(radii);
}

// First-order distance to the surface, g / |grad g| with g = |p / R| - 1: accurate near the
// surface whatever the ratio of radii (used to check that a point lies on the surface).
double surface_offset(const Vec3& radii, const DVec3& p) {
  const DVec3 r = to_d(radii);
  const double len = glm::length(p / r);
  if (len == 0.0) return -min_radius(radii);
  const DVec3 grad = p / (r * r) / len;
  return (len - 1.0) / glm::length(grad);
}

// Round, triaxial in both orders, two equal radii (prolate, oblate), ratios 1e3 on each
// axis, a ratio 1e6, huge and tiny.
const std::vector<Vec3>& sweep_radii() {
  static const std::vector<Vec3> radii = {
      {Real(1), Real(1), Real(1)},      {Real(1), Real(2), Real(3)},       {Real(3), Real(2), Real(1)},
      {Real(2), Real(1), Real(2)},      {Real(1), Real(1), Real(3)},       {Real(3), Real(3), Real(1)},
      {Real(1e3), Real(1), Real(1)},    {Real(1), Real(1e3), Real(2)},     {Real(1), Real(1), Real(1e-3)},
      {Real(1e3), Real(1), Real(1e-3)}, {Real(1e4), Real(2e4), Real(3e4)}, {Real(1e-4), Real(2e-4), Real(5e-5)},
  };
  return radii;
}

// Random query point: uniform in the box inflated by half its size, on an axis, on a
// symmetry plane, within 1e-30 of a plane, near the centre, or near a surface sample.
Vec3 random_query(test::Random& rng, const RefSurface& ref, const Vec3& radii, int i) {
  const Vec3 e = Real(1.5) * radii;
  const Vec3 u = rng.in_box(-e, e);
  const int axis = rng.integer(0, 2);
  switch (i % 7) {
    case 0: return u;
    case 1: {
      Vec3 p(0);
      p[axis] = u[axis];
      return p;
    }
    case 2: {
      Vec3 p = u;
      p[axis] = 0;
      return p;
    }
    case 3: {
      Vec3 p = u * Real(0.6);  // mostly inside, in the evolute region
      p[axis] = std::numeric_limits<Real>::min() * Real(1e8) * (rng.integer(0, 1) ? 1 : -1);
      return p;
    }
    case 4: return u * Real(0.05);
    default: {
      const auto& s = ref.samples();
      const Sample& x = s[static_cast<std::size_t>(rng.integer(0, static_cast<int>(s.size()) - 1))];
      return Vec3(x.p) + rng.vec3(Real(-0.02), Real(0.02)) * static_cast<Real>(min_radius(radii));
    }
  }
}

// Full closest-point check of one query against the refined reference.
void check_closest(const Ellipsoid& el, const RefSurface& ref, const Vec3& q) {
  const Vec3& radii = el.radii();
  const double scale = std::max(max_radius(radii), static_cast<double>(test::max_abs(q)));
  const Real tol = tol_at(scale);
  const SurfacePoint sp = el.closest_point(q);
  ASSERT_TRUE(test::all_finite(sp.point) && test::all_finite(sp.normal) && std::isfinite(sp.signed_distance));
  const DVec3 qd = to_d(q);
  const DVec3 pd = to_d(sp.point);
  const double dist = std::abs(static_cast<double>(sp.signed_distance));
  // On the surface, at the reported distance, no farther than the refined reference.
  EXPECT_LE(std::abs(surface_offset(radii, pd)), tol)
      << "point off the surface, query " << q.x << " " << q.y << " " << q.z;
  EXPECT_NEAR(glm::length(qd - pd), dist, tol);
  const auto best = ref.minimize([&qd](const DVec3& s) { return glm::length(s - qd); });
  EXPECT_LE(dist, best.first + tol) << "query " << q.x << " " << q.y << " " << q.z << " radii " << radii.x << " "
                                    << radii.y << " " << radii.z;
  // Sign agrees with contains (exactly) and with the implicit function away from the surface.
  if (sp.signed_distance < Real(0)) {
    EXPECT_TRUE(el.contains(q));
  }
  if (sp.signed_distance > Real(0)) {
    EXPECT_FALSE(el.contains(q));
  }
  const double f = implicit(radii, qd);
  if (f < -tol) {
    EXPECT_LT(sp.signed_distance, Real(0)) << "query " << q.x << " " << q.y << " " << q.z;
  }
  if (f > tol) {
    EXPECT_GT(sp.signed_distance, Real(0)) << "query " << q.x << " " << q.y << " " << q.z;
  }
  // Unit normal of the supporting plane at the point; for q outside, along q - point.
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

TEST(Ellipsoid, CreateValidatesEachField) {
  static const char* const kField[] = {"radii.x", "radii.y", "radii.z"};
  for (int i = 0; i < 3; ++i) {
    test::expect_positive_field_validated(
        [i](Real x) {
          Vec3 r(1, 2, 3);
          r[i] = x;
          return Ellipsoid::create(r);
        },
        kField[i]);
  }
  // The first bad component is the one named.
  {
    test::ScopedNoFpTraps no_traps;
    test::expect_error(Ellipsoid::create(Vec3(1, test::nan_value(), -1)), ErrorCode::NotFinite, "radii.y");
    test::expect_error(Ellipsoid::create(Vec3(0, 0, 0)), ErrorCode::NonPositive, "radii.x");
  }
  EXPECT_TRUE(Ellipsoid::create(Vec3(Real(1e-20))).ok());
  EXPECT_TRUE(Ellipsoid::create(Vec3(kMaxCoordinate)).ok());
}

TEST(Ellipsoid, AccessorsAndCore) {
  const Ellipsoid el = make(Vec3(1, 2, 3));
  EXPECT_EQ(Ellipsoid::kType, ShapeType::Ellipsoid);
  EXPECT_EQ(el.radii(), Vec3(1, 2, 3));
  EXPECT_EQ(el.core_radius(), Real(0));
  test::Random rng(4001);
  for (int i = 0; i < 100; ++i) {
    const Vec3 d = rng.vec3(Real(-1), Real(1));
    EXPECT_EQ(el.core_support(d), el.support(d));
  }
  const Aabb local = el.local_aabb();
  EXPECT_EQ(local.min, Vec3(-1, -2, -3));
  EXPECT_EQ(local.max, Vec3(1, 2, 3));
}

TEST(Ellipsoid, SupportMatchesRefinedSurfaceMaximum) {
  test::Random rng(4002);
  for (const Vec3& radii : sweep_radii()) {
    const Ellipsoid el = make(radii);
    const RefSurface ref = ellipsoid_surface(radii);
    const Real tol = tol_at(max_radius(radii));
    for (int i = 0; i < 200; ++i) {
      Vec3 d = rng.unit_vector();
      if (i % 10 == 0) d = Vec3(0);
      if (i % 10 == 0) d[i % 3] = i % 20 == 0 ? 1 : -1;  // along an axis
      d *= rng.uniform(Real(1e-3), Real(1e3));
      const Vec3 s = el.support(d);
      ASSERT_TRUE(test::all_finite(s));
      const DVec3 dd = to_d(d) / glm::length(to_d(d));
      EXPECT_LE(std::abs(surface_offset(radii, to_d(s))), tol);
      const double ref_max = ref.maximize([&dd](const DVec3& p) { return glm::dot(p, dd); });
      EXPECT_GE(glm::dot(to_d(s), dd), ref_max - tol) << "direction " << d.x << " " << d.y << " " << d.z;
      // Closed form written independently: max of d.x over the ellipsoid is |R d|.
      EXPECT_NEAR(glm::dot(to_d(s), dd), glm::length(to_d(radii) * dd), tol);
    }
  }
}

TEST(Ellipsoid, SupportOfDegenerateDirections) {
  const Ellipsoid el = make(Vec3(3, 2, 1));
  EXPECT_EQ(el.support(Vec3(0)), Vec3(0, 0, 1));
  EXPECT_EQ(el.support(Vec3(0, -5, 0)), Vec3(0, -2, 0));
  const Real tiny = std::numeric_limits<Real>::denorm_min();
  const Real huge = std::numeric_limits<Real>::max();
  test::expect_vec_near(el.support(Vec3(tiny, 0, 0)), Vec3(3, 0, 0), tol_at(3));
  test::expect_vec_near(el.support(Vec3(0, -huge, 0)), Vec3(0, -2, 0), tol_at(3));
  const Vec3 s = el.support(Vec3(huge, huge, huge));
  EXPECT_TRUE(test::all_finite(s));
  EXPECT_NEAR(surface_offset(el.radii(), to_d(s)), 0.0, tol_at(3));
  // A ratio of radii of 1e30 (float: the squares of the ratio overflow) stays finite.
  const Ellipsoid flat = make(Vec3(kMaxCoordinate, Real(1), kMaxCoordinate * Real(1e-30)));
  for (const Vec3& d : {Vec3(1, 1, 1), Vec3(0, 0, 1), Vec3(tiny, tiny, 1), Vec3(1, tiny, tiny)}) {
    EXPECT_TRUE(test::all_finite(flat.support(d)));
  }
}

TEST(Ellipsoid, WorldAabbIsTheExactBoxOfTheSurface) {
  test::Random rng(4003);
  for (const Vec3& radii : sweep_radii()) {
    const Ellipsoid el = make(radii);
    const RefSurface ref = ellipsoid_surface(radii);
    const double size = max_radius(radii);
    for (int i = 0; i < 30; ++i) {
      Transform pose = rng.pose(Real(3) * static_cast<Real>(size));
      if (i == 0) pose.rotation = kIdentityQuat;
      if (i == 1) pose.rotation = glm::angleAxis(kPi / 2, Vec3(1, 0, 0));
      const DPose dp(pose);
      const Aabb box = el.world_aabb(pose);
      const Real tol = tol_at(4 * size);
      for (int a = 0; a < 3; ++a) {
        const double hi = ref.maximize([&dp, a](const DVec3& p) { return dp.apply(p)[a]; });
        const double lo = -ref.maximize([&dp, a](const DVec3& p) { return -dp.apply(p)[a]; });
        EXPECT_NEAR(box.max[a], hi, tol) << "pose " << i << " axis " << a;
        EXPECT_NEAR(box.min[a], lo, tol) << "pose " << i << " axis " << a;
      }
      for (std::size_t k = 0; k < ref.samples().size(); k += 11) {
        const Vec3 w = pose.apply(Vec3(ref.samples()[k].p));
        EXPECT_TRUE(box.inflated(tol).contains(w)) << "pose " << i << " sample " << k;
      }
    }
  }
}

TEST(Ellipsoid, ContainsMatchesImplicitFunction) {
  test::Random rng(4004);
  for (const Vec3& radii : sweep_radii()) {
    const Ellipsoid el = make(radii);
    int in = 0;
    int out = 0;
    for (int i = 0; i < 5000; ++i) {
      const Vec3 e = Real(1.2) * radii;
      const Vec3 p = rng.in_box(-e, e);
      // Skip points whose level |p / R| is within rounding of 1.
      const double f = glm::length(to_d(p) / to_d(radii)) - 1.0;
      if (std::abs(f) <= 4.0 * static_cast<double>(kRelativeTolerance)) continue;
      EXPECT_EQ(el.contains(p), f < 0) << p.x << " " << p.y << " " << p.z;
      (f < 0 ? in : out) += 1;
    }
    EXPECT_GT(in, 1000);
    EXPECT_GT(out, 1000);
    // The boundary counts as inside: the six axis tips.
    EXPECT_TRUE(el.contains(Vec3(0)));
    for (int a = 0; a < 3; ++a) {
      Vec3 p(0);
      p[a] = radii[a];
      EXPECT_TRUE(el.contains(p));
      EXPECT_TRUE(el.contains(-p));
      EXPECT_FALSE(el.contains(p * Real(1.001)));
    }
  }
}

TEST(Ellipsoid, ClosestPointMatchesRefinedBruteForce) {
  test::Random rng(4005);
  for (const Vec3& radii : sweep_radii()) {
    const Ellipsoid el = make(radii);
    const RefSurface ref = ellipsoid_surface(radii);
    for (int i = 0; i < 140; ++i) check_closest(el, ref, random_query(rng, ref, radii, i));
  }
}

TEST(Ellipsoid, ClosestPointNamedCases) {
  const Ellipsoid el = make(Vec3(3, 2, 1));
  const RefSurface ref = ellipsoid_surface(Vec3(3, 2, 1));
  const Real tol = tol_at(4);
  // Outside on the major axis: the tip.
  SurfacePoint sp = el.closest_point(Vec3(5, 0, 0));
  test::expect_vec_near(sp.point, Vec3(3, 0, 0), tol);
  test::expect_vec_near(sp.normal, Vec3(1, 0, 0), tol);
  EXPECT_NEAR(sp.signed_distance, Real(2), tol);
  // The centre: the tips of the minor axis, distance -1.
  sp = el.closest_point(Vec3(0));
  EXPECT_NEAR(sp.signed_distance, Real(-1), tol);
  EXPECT_NEAR(std::abs(sp.point.z), Real(1), tol);
  EXPECT_NEAR(std::abs(sp.normal.z), Real(1), tol);
  // Inside on the major axis at x = 1 (within the evolute): the nearest point leaves the
  // axis, (9/8, 0, +-sqrt(55)/8) at distance sqrt(56)/8 (Lagrange conditions solved by hand).
  sp = el.closest_point(Vec3(1, 0, 0));
  EXPECT_NEAR(sp.signed_distance, -std::sqrt(Real(56)) / 8, tol);
  EXPECT_NEAR(sp.point.x, Real(9) / 8, tol);
  EXPECT_NEAR(sp.point.y, Real(0), tol);
  EXPECT_NEAR(std::abs(sp.point.z), std::sqrt(Real(55)) / 8, tol);
  // Inside on the major axis beyond the evolute (x = 2.9): the tip.
  sp = el.closest_point(Vec3(Real(2.9), 0, 0));
  test::expect_vec_near(sp.point, Vec3(3, 0, 0), tol);
  EXPECT_NEAR(sp.signed_distance, Real(-0.1), tol);
  // Just off the minor plane: continuous with the point on it.
  const SurfacePoint on = el.closest_point(Vec3(1, Real(0.5), 0));
  const SurfacePoint off = el.closest_point(Vec3(1, Real(0.5), std::numeric_limits<Real>::min()));
  EXPECT_NEAR(on.signed_distance, off.signed_distance, tol);
  test::expect_vec_near(glm::abs(on.point), glm::abs(off.point), tol);
  // Exactly on the surface: the tips.
  for (const Vec3& p : {Vec3(3, 0, 0), Vec3(0, -2, 0), Vec3(0, 0, 1)}) {
    sp = el.closest_point(p);
    EXPECT_EQ(sp.signed_distance, Real(0));
    test::expect_vec_near(sp.point, p, tol);
  }
  for (const Vec3& p : {Vec3(0), Vec3(5, 0, 0), Vec3(1, 0, 0), Vec3(Real(2.9), 0, 0), Vec3(1, Real(0.5), 0),
                        Vec3(0, 0, Real(0.5)), Vec3(0, Real(1.5), 0), Vec3(0, 3, 0), Vec3(0, 0, -3), Vec3(3, 0, 0)}) {
    check_closest(el, ref, p);
  }
}

TEST(Ellipsoid, ClosestPointOfSphereIsRadial) {
  test::Random rng(4006);
  const Ellipsoid el = make(Vec3(2));
  for (int i = 0; i < 500; ++i) {
    const Vec3 q = rng.vec3(Real(-4), Real(4));
    const SurfacePoint sp = el.closest_point(q);
    const Real len = glm::length(q);
    if (len < Real(1e-3)) continue;
    test::expect_vec_near(sp.point, q * (Real(2) / len), tol_at(4));
    EXPECT_NEAR(sp.signed_distance, len - Real(2), tol_at(4));
  }
}

TEST(Ellipsoid, ClosestPointOfExtremeRatiosIsBoundedAndFinite) {
  // Ratios up to 1e30 (beyond float's squared range) and points far away or on the axes:
  // the bisection stays bounded and every answer is finite.
  const Real tiny = std::numeric_limits<Real>::denorm_min();
  const Real big = kMaxCoordinate;
  const Real small = kMaxCoordinate * Real(1e-30);
  for (const Vec3& radii : {Vec3(big, Real(1), small), Vec3(small, small, big), Vec3(Real(1e3), Real(1e-3), Real(1)),
                            Vec3(kMaxCoordinate, Real(1), Real(1))}) {
    const Ellipsoid el = make(radii);
    for (const Vec3& q : {Vec3(0), Vec3(1, 1, 1), Vec3(tiny, tiny, tiny), Vec3(0, 0, 1), Vec3(1, 0, 0),
                          Vec3(kMaxCoordinate, kMaxCoordinate, kMaxCoordinate), Vec3(0, kMaxCoordinate, 0),
                          Vec3(-kMaxCoordinate, 0, tiny), Vec3(Real(1e-10), Real(1e-10), 0)}) {
      const SurfacePoint sp = el.closest_point(q);
      EXPECT_TRUE(test::all_finite(sp.point) && test::all_finite(sp.normal) && std::isfinite(sp.signed_distance))
          << q.x << " " << q.y << " " << q.z;
      EXPECT_NEAR(glm::length(sp.normal), Real(1), Real(1e2) * kEpsilon);
      if (sp.signed_distance < Real(0)) {
        EXPECT_TRUE(el.contains(q));
      }
      if (sp.signed_distance > Real(0)) {
        EXPECT_FALSE(el.contains(q));
      }
      // The point is on the surface to the precision available at its scale.
      EXPECT_LE(std::abs(glm::length(to_d(sp.point) / to_d(radii)) - 1.0), 1e-3)
          << "radii " << radii.x << " " << radii.y << " " << radii.z << " query " << q.x << " " << q.y << " " << q.z
          << " point " << sp.point.x << " " << sp.point.y << " " << sp.point.z << " sd " << sp.signed_distance;
    }
  }
}

TEST(Ellipsoid, ClosestPointPlacedFarFromOrigin) {
  test::Random rng(4007);
  const Vec3 radii(Real(0.5), Real(2), Real(1));
  const Ellipsoid el = make(radii);
  const RefSurface ref = ellipsoid_surface(radii);
  for (int i = 0; i < 100; ++i) {
    const Transform pose{rng.vec3(Real(-1e4), Real(1e4)), rng.rotation()};
    const Vec3 local = random_query(rng, ref, radii, i);
    const Vec3 q = pose.apply(local);
    const SurfacePoint sp = closest_point(el, pose, q);
    const Real tol = tol_at(4e4);
    const DPose dp(pose);
    const DVec3 qd = dp.apply(to_d(local));
    const auto best = ref.minimize([&](const DVec3& s) { return glm::length(dp.apply(s) - qd); });
    EXPECT_LE(std::abs(sp.signed_distance), best.first + tol);
    EXPECT_NEAR(glm::length(q - sp.point), std::abs(sp.signed_distance), tol);
    EXPECT_LE(std::abs(surface_offset(radii, to_d(pose.inverse_apply(sp.point)))), tol);
  }
}

TEST(Ellipsoid, RaycastMatchesMarching) {
  test::Random rng(4008);
  int hits = 0;
  int misses = 0;
  for (const Vec3& radii : sweep_radii()) {
    const Ellipsoid el = make(radii);
    const RefSurface ref = ellipsoid_surface(radii);
    const double size = max_radius(radii);
    const Real tol = tol_at(8 * size);
    const auto f = [&radii](const DVec3& p) { return implicit(radii, p); };
    const auto inside = [&el](const Vec3& p) { return el.contains(p); };
    for (int i = 0; i < 250; ++i) {
      const Vec3 e = Real(2) * radii;
      const Vec3 o = rng.in_box(-e, e);
      const Vec3 target = rng.in_box(-e, e) * Real(0.5);
      Vec3 dir = target - o;
      if (i % 7 == 0) {
        dir = Vec3(0);
        dir[i % 3] = o[i % 3] > 0 ? -radii[i % 3] : radii[i % 3];  // along an axis
      }
      if (!(glm::length(dir) > Real(0))) continue;
      const Real max_t = rng.uniform(Real(0.2), Real(3));
      const Ray ray{o, dir};
      const auto hit = el.raycast(ray, max_t);
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
      if (hit->t == Real(0) && el.contains(o)) {
        test::expect_vec_near(hit->normal, -dir / glm::length(dir), Real(1e2) * kEpsilon);
        continue;
      }
      // On the surface, nothing deep inside before it, and as early as the bisected entry.
      EXPECT_LE(std::abs(surface_offset(radii, to_d(hit->point))), tol) << "ray " << i;
      EXPECT_FALSE(m.deep && m.t_deep < hit->t - t_tol) << "ray " << i;
      if (m.entered) {
        EXPECT_NEAR(hit->t, m.t_bisect, t_tol) << "ray " << i;
      }
      // The normal faces the ray and is the supporting plane at the hit.
      const DVec3 n = to_d(hit->normal);
      EXPECT_LE(glm::dot(n, to_d(dir)), 0.0 + tol);
      const double support_n = ref.maximize([&n](const DVec3& s) { return glm::dot(s, n); });
      EXPECT_LE(support_n, glm::dot(to_d(hit->point), n) + tol) << "ray " << i;
    }
  }
  EXPECT_GT(hits, 500);
  EXPECT_GT(misses, 300);
}

TEST(Ellipsoid, RaycastNamedCases) {
  const Ellipsoid el = make(Vec3(3, 2, 1));
  const Real tol = tol_at(8);
  // Along x onto the tip, direction of length 2: t in units of |direction|.
  auto hit = el.raycast(Ray{Vec3(-7, 0, 0), Vec3(2, 0, 0)}, Real(10));
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->t, Real(2), tol);
  test::expect_vec_near(hit->point, Vec3(-3, 0, 0), tol);
  test::expect_vec_near(hit->normal, Vec3(-1, 0, 0), tol);
  // Down z at x = 1.5: hits z = sqrt(1 - 1/4) = sqrt(3)/2; normal ~ (x/9, 0, z/1).
  hit = el.raycast(Ray{Vec3(Real(1.5), 0, 5), Vec3(0, 0, -1)}, Real(10));
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->t, Real(5) - std::sqrt(Real(3)) / 2, tol);
  const Vec3 n = glm::normalize(Vec3(Real(1.5) / 9, 0, std::sqrt(Real(3)) / 2));
  test::expect_vec_near(hit->normal, n, tol);
  // Tangent at the top (z = 1): touches or misses; a ray just above misses.
  EXPECT_FALSE(el.raycast(Ray{Vec3(-5, 0, Real(1.001)), Vec3(1, 0, 0)}, Real(100)));
  // Too short, and pointing away.
  EXPECT_FALSE(el.raycast(Ray{Vec3(-7, 0, 0), Vec3(1, 0, 0)}, Real(3.9)));
  EXPECT_FALSE(el.raycast(Ray{Vec3(-7, 0, 0), Vec3(-1, 0, 0)}, Real(100)));
  // Origin inside: t = 0 with normal -direction / |direction|.
  hit = el.raycast(Ray{Vec3(0, Real(0.5), 0), Vec3(0, 3, 4)}, Real(10));
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->t, Real(0));
  test::expect_vec_near(hit->normal, Vec3(0, Real(-0.6), Real(-0.8)), tol);
  // Zero direction: hits only from inside.
  EXPECT_TRUE(el.raycast(Ray{Vec3(0, 0, Real(0.5)), Vec3(0)}, Real(1)));
  EXPECT_FALSE(el.raycast(Ray{Vec3(0, 0, Real(1.5)), Vec3(0)}, Real(1)));
  // A needle 1000:1: a ray across its thin middle.
  const Ellipsoid needle = make(Vec3(Real(1e3), Real(1), Real(1)));
  hit = needle.raycast(Ray{Vec3(0, -5, 0), Vec3(0, 1, 0)}, Real(10));
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->t, Real(4), tol_at(1e3));
  test::expect_vec_near(hit->normal, Vec3(0, -1, 0), tol_at(1));
  // Placed far from the origin.
  const Transform pose{Vec3(Real(1e4), Real(-2e4), Real(5e3)), glm::angleAxis(kPi / 2, Vec3(0, 0, 1))};
  hit = raycast(el, pose, Ray{pose.position + Vec3(0, -10, 0), Vec3(0, 1, 0)}, Real(20));
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->t, Real(7), tol_at(4e4));
  test::expect_vec_near(hit->normal, Vec3(0, -1, 0), tol_at(1e2));
}

// Reference: the second moments of the unit ball, integral of x^2 = 4 pi / 15, scaled by
// the radii (x = a u: integral of x^2 over the ellipsoid = a^3 b c 4 pi / 15), then
// I = tr(C) E - C.
TEST(Ellipsoid, MassPropertiesMatchScaledBallMoments) {
  for (const Vec3& radii : sweep_radii()) {
    const DVec3 r = to_d(radii);
    const double density = 0.75;
    const double jac = r.x * r.y * r.z;
    const double volume = 4.0 * kPiD / 3.0 * jac;
    const DVec3 c = density * 4.0 * kPiD / 15.0 * jac * r * r;  // diagonal second moments
    const MassProperties got = make(radii).mass_properties(Real(0.75));
    EXPECT_NEAR(got.volume, volume, tol_at(volume));
    EXPECT_NEAR(got.mass, density * volume, tol_at(density * volume));
    EXPECT_EQ(got.centroid, Vec3(0));
    const double trace = c.x + c.y + c.z;
    const double scale = trace;
    for (int a = 0; a < 3; ++a) {
      for (int b = 0; b < 3; ++b) {
        const double want = a == b ? trace - c[a] : 0.0;
        EXPECT_NEAR(got.inertia[a][b], want, tol_at(scale)) << a << " " << b;
      }
    }
  }
  EXPECT_NEAR(make(Vec3(1)).mass_properties().mass, Real(4) * kPi / Real(3), tol_at(4));
}

TEST(Ellipsoid, MassPropertiesMatchGridIntegration) {
  for (const Vec3& radii : {Vec3(1, 2, 3), Vec3(Real(0.5), Real(0.5), 2), Vec3(3, 1, Real(0.3))}) {
    const Ellipsoid el = make(radii);
    const auto inside = [&radii](const Vec3& p) { return implicit(radii, to_d(p)) <= 0; };
    const MassProperties grid = test::integrate_mass_on_grid(inside, el.local_aabb(), 120, Real(3));
    test::expect_mass_near(el.mass_properties(Real(3)), grid, Real(0.01), Real(0.01) * max_radius(radii));
  }
}

TEST(Ellipsoid, NeverNaN) {
  const Real huge = std::numeric_limits<Real>::max() / Real(8);
  const Real tiny = std::numeric_limits<Real>::denorm_min();
  for (const Vec3& radii : {Vec3(1, 2, 3), Vec3(Real(1e-3), Real(1e3), 1), Vec3(kMaxCoordinate, Real(1e-20), 1)}) {
    const Ellipsoid el = make(radii);
    for (const Vec3& p :
         {Vec3(0), Vec3(tiny, 0, 0), Vec3(0, 0, tiny), Vec3(tiny, -tiny, tiny), Vec3(kMaxCoordinate, 0, 0),
          Vec3(0, 0, -kMaxCoordinate), Vec3(kMaxCoordinate, kMaxCoordinate, kMaxCoordinate)}) {
      const SurfacePoint sp = el.closest_point(p);
      EXPECT_TRUE(test::all_finite(sp.point) && test::all_finite(sp.normal) && std::isfinite(sp.signed_distance));
      EXPECT_NEAR(glm::length(sp.normal), Real(1), Real(1e2) * kEpsilon);
      (void)el.contains(p);
      EXPECT_TRUE(test::all_finite(el.support(p)));
      EXPECT_TRUE(test::all_finite(el.support(p * (huge / std::max(Real(1), test::max_abs(p))))));
      const auto hit = el.raycast(Ray{p, Vec3(1, 2, 3)}, Real(10));
      if (hit) {
        EXPECT_TRUE(test::all_finite(hit->point) && test::all_finite(hit->normal));
      }
    }
    const Aabb box = el.world_aabb(Transform{Vec3(0), glm::angleAxis(Real(0.3), glm::normalize(Vec3(1, 2, 3)))});
    EXPECT_TRUE(box.is_valid() && test::all_finite(box.min) && test::all_finite(box.max));
  }
}

TEST(Ellipsoid, NonFiniteQueriesHaveDefinedAnswers) {
  test::ScopedNoFpTraps no_traps;
  const Ellipsoid s = make(Vec3(1, 2, 3));
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

}  // namespace test_ellipsoid
}  // namespace proxima
