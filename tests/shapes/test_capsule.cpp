// Capsule: every member checked against references the capsule does not compute itself:
// samples of its cylindrical wall and its two hemispherical caps (support, world box,
// closest point), the implicit test x^2 + y^2 + max(|z| - h, 0)^2 <= r^2 (contains, ray
// marching), the closed-form mass properties of the literature and grid integration.
#include <gtest/gtest.h>

#include <proxima/core/tolerance.hpp>
#include <proxima/shapes/capsule.hpp>
#include <proxima/shapes/placed.hpp>

#include <vector>

#include "shapes/shape_test_util.hpp"
#include "support/random.hpp"

namespace proxima {
namespace test_capsule {

using test::precision_tolerance;

Capsule make(Real r, Real h) { return Capsule::create(r, h).value(); }

// Surface samples: `rings` x `per_ring` points on the wall (including the two rims) and
// Fibonacci points on each cap; `resolution` receives their covering radius.
std::vector<Vec3> samples(Real r, Real h, int rings, int per_ring, int cap_points, Real& resolution) {
  std::vector<Vec3> out;
  const double pi = 3.14159265358979323846;
  for (int i = 0; i <= rings; ++i) {
    const Real z = -h + Real(2) * h * static_cast<Real>(i) / static_cast<Real>(rings);
    for (int j = 0; j < per_ring; ++j) {
      const double a = 2.0 * pi * j / per_ring;
      out.emplace_back(r * static_cast<Real>(std::cos(a)), r * static_cast<Real>(std::sin(a)), z);
    }
  }
  for (const Vec3& u : test::fibonacci_sphere(cap_points)) {
    out.push_back(r * u + Vec3(0, 0, u.z >= 0 ? h : -h));
  }
  const Real arc = r * static_cast<Real>(2.0 * pi / per_ring);
  const Real wall = Real(0.5) * std::sqrt(arc * arc + (Real(2) * h / static_cast<Real>(rings)) *
                                                          (Real(2) * h / static_cast<Real>(rings)));
  resolution = std::max(wall, test::fibonacci_resolution(cap_points) * r);
  return out;
}

auto implicit_inside(Real r, Real h) {
  return [r, h](const Vec3& p) {
    const Real dz = std::max(std::abs(p.z) - h, Real(0));
    return p.x * p.x + p.y * p.y + dz * dz <= r * r;
  };
}

TEST(Capsule, CreateValidatesRadiusAndHalfLength) {
  test::expect_positive_field_validated([](Real r) { return Capsule::create(r, 1); }, "radius");
  test::ScopedNoFpTraps no_traps;
  test::expect_error(Capsule::create(1, test::nan_value()), ErrorCode::NotFinite, "half_length");
  test::expect_error(Capsule::create(1, test::inf_value()), ErrorCode::NotFinite, "half_length");
  test::expect_error(Capsule::create(1, Real(-1)), ErrorCode::Negative, "half_length");
  test::expect_error(Capsule::create(1, -std::numeric_limits<Real>::denorm_min()), ErrorCode::Negative, "half_length");
  test::expect_error(Capsule::create(1, kMaxCoordinate * Real(2)), ErrorCode::OutOfRange, "half_length");
  // The radius is checked first.
  test::expect_error(Capsule::create(0, Real(-1)), ErrorCode::NonPositive, "radius");
  EXPECT_TRUE(Capsule::create(1, 0).ok());
}

TEST(Capsule, Accessors) {
  const Capsule c = make(Real(0.5), 2);
  EXPECT_EQ(Capsule::kType, ShapeType::Capsule);
  EXPECT_EQ(c.radius(), Real(0.5));
  EXPECT_EQ(c.half_length(), Real(2));
  EXPECT_EQ(c.core_radius(), Real(0.5));
  EXPECT_EQ(c.top(), Vec3(0, 0, 2));
  EXPECT_EQ(c.bottom(), Vec3(0, 0, -2));
  EXPECT_EQ(c.core_support(Vec3(1, 1, Real(0.1))), Vec3(0, 0, 2));
  EXPECT_EQ(c.core_support(Vec3(1, 1, Real(-0.1))), Vec3(0, 0, -2));
}

TEST(Capsule, SupportMatchesSurfaceSamples) {
  test::Random rng(301);
  for (const Real s : test::scales()) {
    for (const Real hr : {Real(0), Real(0.3), Real(3)}) {
      const Real r = s;
      const Real h = hr * s;
      Real res = Real(0);
      const auto pts = samples(r, h, 20, 256, 8000, res);
      const Capsule c = make(r, h);
      test::check_support_against_samples(c, pts, res * res / (Real(2) * r), precision_tolerance(Real(8) * s), rng,
                                          300);
    }
  }
}

TEST(Capsule, SupportIsCorePlusRadiusAndOnTheSurface) {
  test::Random rng(302);
  const Capsule c = make(Real(0.75), Real(1.5));
  const auto inside = implicit_inside(Real(0.75), Real(1.5));
  for (int i = 0; i < 2000; ++i) {
    const Vec3 d = rng.vec3(Real(-3), Real(3));
    if (glm::length(d) < Real(1e-3)) continue;
    const Vec3 sp = c.support(d);
    test::expect_vec_near(sp, c.core_support(d) + c.core_radius() * glm::normalize(d),
                          precision_tolerance(Real(4), Real(8)));
    // On the surface: inside when pulled in slightly, outside when pushed out.
    EXPECT_TRUE(inside(sp * (Real(1) - Real(1e-3))));
    EXPECT_FALSE(inside(sp * (Real(1) + Real(1e-3))));
  }
  const Vec3 zero = c.support(Vec3(0));
  EXPECT_EQ(zero, Vec3(0, 0, Real(2.25)));
  const Real huge = std::numeric_limits<Real>::max() / Real(2);
  EXPECT_TRUE(test::all_finite(c.support(Vec3(huge, -huge, huge))));
  const Real tiny = std::numeric_limits<Real>::denorm_min();
  EXPECT_TRUE(test::all_finite(c.support(Vec3(tiny, 0, -tiny))));
}

TEST(Capsule, LocalBox) {
  const Capsule c = make(Real(0.5), 2);
  EXPECT_EQ(c.local_aabb().min, Vec3(Real(-0.5), Real(-0.5), Real(-2.5)));
  EXPECT_EQ(c.local_aabb().max, Vec3(Real(0.5), Real(0.5), Real(2.5)));
}

TEST(Capsule, WorldBoxIsTightAtRandomPoses) {
  test::Random rng(303);
  for (const Real s : test::scales()) {
    for (const Real hr : {Real(0), Real(2)}) {
      const Real r = s;
      const Real h = hr * s;
      Real res = Real(0);
      const auto pts = samples(r, h, 8, 256, 20000, res);
      const Real extent = Real(10) * s;
      test::check_world_aabb_against_samples(make(r, h), pts, res, precision_tolerance(extent * Real(2)), rng, 40,
                                             extent);
    }
  }
}

TEST(Capsule, WorldBoxAnalytic) {
  // Lying along world x: the box is [-h - r, h + r] x [-r, r] x [-r, r] around the position.
  const Capsule c = make(1, 3);
  const Transform pose{Vec3(10, 20, 30), glm::angleAxis(kPi / 2, Vec3(0, 1, 0))};
  const Aabb box = c.world_aabb(pose);
  const Real tol = precision_tolerance(Real(40));
  test::expect_vec_near(box.min, Vec3(6, 19, 29), tol);
  test::expect_vec_near(box.max, Vec3(14, 21, 31), tol);
  // Tilted by 45 degrees in the xz plane: half extents h / sqrt(2) + r in x and z.
  const Transform tilt{Vec3(0), glm::angleAxis(kPi / 4, Vec3(0, 1, 0))};
  const Aabb t = c.world_aabb(tilt);
  const Real e = Real(3) / std::sqrt(Real(2)) + 1;
  test::expect_vec_near(t.max, Vec3(e, 1, e), precision_tolerance(Real(8)));
  // Far from the origin.
  const Transform far{Vec3(Real(1e4), Real(-2e4), Real(5e3)), kIdentityQuat};
  test::expect_vec_near(c.world_aabb(far).max, Vec3(Real(1e4) + 1, Real(-2e4) + 1, Real(5e3) + 4),
                        precision_tolerance(Real(2e4)));
}

TEST(Capsule, ContainsMatchesImplicitFunction) {
  test::Random rng(304);
  for (const Real s : test::scales()) {
    for (const Real hr : {Real(0), Real(1.5)}) {
      const Real r = s;
      const Real h = hr * s;
      const Capsule c = make(r, h);
      const auto inside = implicit_inside(r, h);
      int in = 0;
      for (int i = 0; i < 20000; ++i) {
        const Vec3 p = rng.vec3(Real(-1.3), Real(1.3)) * Vec3(r, r, h + r);
        EXPECT_EQ(c.contains(p), inside(p));
        in += inside(p) ? 1 : 0;
      }
      EXPECT_GT(in, 4000);
      EXPECT_TRUE(c.contains(Vec3(0, 0, h + r)));
      EXPECT_TRUE(c.contains(Vec3(r, 0, h)));
      EXPECT_TRUE(c.contains(Vec3(0, -r, 0)));
      EXPECT_FALSE(c.contains(Vec3(0, 0, (h + r) * Real(1.001))));
    }
  }
}

TEST(Capsule, ClosestPointMatchesBruteForce) {
  test::Random rng(305);
  for (const Real s : test::scales()) {
    for (const Real hr : {Real(0), Real(0.5), Real(2)}) {
      const Real r = s;
      const Real h = hr * s;
      Real res = Real(0);
      const auto pts = samples(r, h, 60, 200, 12000, res);
      const Aabb region{-Vec3(2 * r, 2 * r, 2 * (h + r)), Vec3(2 * r, 2 * r, 2 * (h + r))};
      test::check_closest_point_solid(make(r, h), pts, res, precision_tolerance(Real(8) * (r + h)),
                                      implicit_inside(r, h), region, rng, 300);
    }
  }
}

TEST(Capsule, ClosestPointAnalyticAndDegenerate) {
  const Capsule c = make(1, 2);
  const Real tol = precision_tolerance(Real(8));
  // Beside the wall, above a cap, inside near the wall, inside near a cap.
  SurfacePoint sp = c.closest_point(Vec3(3, 0, 1));
  test::expect_vec_near(sp.point, Vec3(1, 0, 1), tol);
  test::expect_vec_near(sp.normal, Vec3(1, 0, 0), tol);
  EXPECT_NEAR(sp.signed_distance, Real(2), tol);
  sp = c.closest_point(Vec3(0, 0, 7));
  test::expect_vec_near(sp.point, Vec3(0, 0, 3), tol);
  EXPECT_NEAR(sp.signed_distance, Real(4), tol);
  sp = c.closest_point(Vec3(0, Real(-0.5), Real(-1)));
  test::expect_vec_near(sp.point, Vec3(0, -1, -1), tol);
  test::expect_vec_near(sp.normal, Vec3(0, -1, 0), tol);
  EXPECT_NEAR(sp.signed_distance, Real(-0.5), tol);
  sp = c.closest_point(Vec3(0, Real(0.1), Real(2.8)));
  EXPECT_NEAR(sp.signed_distance, std::sqrt(Real(0.01) + Real(0.64)) - 1, tol);
  // On the axis (centre, inside the core, at a core end): the wall is nearest, at -r.
  for (const Vec3& q : {Vec3(0), Vec3(0, 0, Real(1.5)), Vec3(0, 0, 2), Vec3(0, 0, -2)}) {
    sp = c.closest_point(q);
    EXPECT_EQ(sp.signed_distance, Real(-1));
    EXPECT_NEAR(glm::length(sp.normal), Real(1), tol);
    EXPECT_NEAR(glm::length(sp.point - q), Real(1), tol);
    EXPECT_NEAR(sp.normal.z, Real(0), tol);
  }
  // A sphere-like capsule (h = 0) at its centre.
  const Capsule ball = make(2, 0);
  sp = ball.closest_point(Vec3(0));
  EXPECT_EQ(sp.signed_distance, Real(-2));
  EXPECT_NEAR(glm::length(sp.point), Real(2), tol);
  // On the surface.
  sp = c.closest_point(Vec3(0, 1, Real(-0.3)));
  EXPECT_NEAR(sp.signed_distance, Real(0), tol);
}

TEST(Capsule, RaycastMatchesMarching) {
  test::Random rng(306);
  for (const Real s : test::scales()) {
    for (const Real hr : {Real(0), Real(0.5), Real(2)}) {
      const Real r = s;
      const Real h = hr * s;
      const Aabb region{Vec3(Real(-2) * (r + h)), Vec3(Real(2) * (r + h))};
      test::check_raycast_solid(make(r, h), implicit_inside(r, h), region,
                                precision_tolerance(Real(16) * (r + h), Real(256)), rng, 1500);
    }
  }
}

TEST(Capsule, RaycastAnalyticCases) {
  const Capsule c = make(1, 2);
  const Real tol = precision_tolerance(Real(8), Real(16));
  // Into the wall, into a cap along the axis, t in units of |direction|.
  auto hit = c.raycast(Ray{Vec3(-5, 0, 1), Vec3(2, 0, 0)}, Real(10));
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->t, Real(2), tol);
  test::expect_vec_near(hit->normal, Vec3(-1, 0, 0), tol);
  hit = c.raycast(Ray{Vec3(0, 0, 10), Vec3(0, 0, -1)}, Real(100));
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->t, Real(7), tol);
  test::expect_vec_near(hit->normal, Vec3(0, 0, 1), tol);
  // Parallel to the axis, through the cap off-centre.
  hit = c.raycast(Ray{Vec3(Real(0.6), 0, -10), Vec3(0, 0, 1)}, Real(100));
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->t, Real(10) - Real(2) - Real(0.8), tol);
  test::expect_vec_near(hit->normal, Vec3(Real(0.6), 0, Real(-0.8)), tol);
  // Parallel to the axis, outside the radius: miss.
  EXPECT_FALSE(c.raycast(Ray{Vec3(Real(1.01), 0, -10), Vec3(0, 0, 1)}, Real(100)));
  // Tangent to the wall: touching hit or miss, never NaN.
  hit = c.raycast(Ray{Vec3(-5, 1, 0), Vec3(1, 0, 0)}, Real(100));
  if (hit) {
    EXPECT_NEAR(hit->t, Real(5), Real(0.01));
  }
  // Inside: t = 0, normal = -direction/|direction|.
  hit = c.raycast(Ray{Vec3(0, 0, Real(2.5)), Vec3(0, 3, 0)}, Real(10));
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->t, Real(0));
  test::expect_vec_near(hit->normal, Vec3(0, -1, 0), tol);
  // Zero direction.
  EXPECT_TRUE(c.raycast(Ray{Vec3(0, 0, 1), Vec3(0)}, Real(1)));
  EXPECT_FALSE(c.raycast(Ray{Vec3(0, 2, 1), Vec3(0)}, Real(1)));
  // A sphere-like capsule.
  hit = make(1, 0).raycast(Ray{Vec3(0, -4, 0), Vec3(0, 1, 0)}, Real(10));
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->t, Real(3), tol);
}

TEST(Capsule, PlacedQueriesMatchLocalOnes) {
  test::Random rng(307);
  const Capsule c = make(Real(0.5), Real(1.5));
  for (int i = 0; i < 500; ++i) {
    const Transform pose = rng.pose(Real(20));
    const Vec3 local_q = rng.vec3(Real(-3), Real(3));
    const Vec3 q = pose.apply(local_q);
    const Real tol = precision_tolerance(Real(40), Real(32));
    const SurfacePoint w = closest_point(c, pose, q);
    const SurfacePoint l = c.closest_point(local_q);
    EXPECT_NEAR(w.signed_distance, l.signed_distance, tol);
    test::expect_vec_near(w.point, pose.apply(l.point), tol);
    test::expect_vec_near(w.normal, pose.apply_vector(l.normal), tol);
    const Vec3 d = rng.unit_vector();
    const Vec3 ws = support(c, pose, d);
    // The world support maximises d over the world surface: compare with the two rims.
    const Vec3 axis = pose.apply_vector(Vec3(0, 0, Real(1.5)));
    const Real best = glm::dot(pose.position, d) + std::abs(glm::dot(axis, d)) + Real(0.5);
    EXPECT_NEAR(glm::dot(ws, d), best, tol);
  }
}

TEST(Capsule, MassPropertiesAnalyticAndIntegrated) {
  for (const Real s : {Real(0.01), Real(1), Real(20)}) {
    for (const Real hr : {Real(0), Real(0.5), Real(3)}) {
      const Real r = s;
      const Real h = hr * s;
      const Real density = Real(1.3);
      const Capsule c = make(r, h);
      const MassProperties m = c.mass_properties(density);
      // Reference in double: cylinder of height H = 2h plus two hemispheres of mass mh,
      // I_xx = mc (H^2 / 12 + r^2 / 4) + 2 mh (2 r^2 / 5 + H^2 / 4 + 3 H r / 8),
      // I_zz = mc r^2 / 2 + 2 mh (2 r^2 / 5).
      const double pi = 3.14159265358979323846;
      const double rd = r;
      const double big_h = 2.0 * static_cast<double>(h);
      const double mc = density * pi * rd * rd * big_h;
      const double mh = density * 2.0 / 3.0 * pi * rd * rd * rd;
      const double ixx = mc * (big_h * big_h / 12.0 + rd * rd / 4.0) +
                         2.0 * mh * (2.0 * rd * rd / 5.0 + big_h * big_h / 4.0 + 3.0 * big_h * rd / 8.0);
      const double izz = mc * rd * rd / 2.0 + 2.0 * mh * (2.0 * rd * rd / 5.0);
      const double mass = mc + 2.0 * mh;
      const Real rel = precision_tolerance(Real(1), Real(32));
      EXPECT_NEAR(m.mass, mass, rel * mass);
      EXPECT_NEAR(m.volume, mass / density, rel * mass / density);
      EXPECT_EQ(m.centroid, Vec3(0));
      EXPECT_NEAR(m.inertia[0][0], ixx, rel * ixx);
      EXPECT_NEAR(m.inertia[1][1], ixx, rel * ixx);
      EXPECT_NEAR(m.inertia[2][2], izz, rel * ixx);
      EXPECT_EQ(m.inertia[0][1], Real(0));
      EXPECT_EQ(m.inertia[1][2], Real(0));
      EXPECT_EQ(m.inertia[0][2], Real(0));
      const MassProperties grid = test::integrate_mass_on_grid(implicit_inside(r, h), c.local_aabb(), 96, density);
      test::expect_mass_near(m, grid, Real(0.01), Real(0.01) * (r + h));
    }
  }
}

TEST(Capsule, NonFiniteQueryInputHasDefinedAnswers) {
  test::exercise_queries_with_non_finite_input(make(Real(0.5), Real(1.5)));
}

}  // namespace test_capsule
}  // namespace proxima
