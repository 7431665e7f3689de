// Sphere: every member checked against references the sphere does not compute itself:
// Fibonacci samples of its surface (support, world box, closest point), the implicit test
// |p| <= r (contains, ray marching), the closed-form and grid-integrated mass properties.
#include <gtest/gtest.h>

#include <proxima/core/tolerance.hpp>
#include <proxima/shapes/placed.hpp>
#include <proxima/shapes/sphere.hpp>

#include <vector>

#include "shapes/shape_test_util.hpp"
#include "support/random.hpp"

namespace proxima {
namespace test_sphere {

using test::precision_tolerance;

Sphere make(Real r) { return Sphere::create(r).value(); }

std::vector<Vec3> samples(Real r, int n) {
  std::vector<Vec3> s = test::fibonacci_sphere(n);
  for (Vec3& p : s) p *= r;
  return s;
}

auto implicit_inside(Real r) {
  return [r](const Vec3& p) { return glm::dot(p, p) <= r * r; };
}

TEST(Sphere, CreateValidatesRadius) {
  test::expect_positive_field_validated([](Real r) { return Sphere::create(r); }, "radius");
  EXPECT_TRUE(Sphere::create(Real(1e-20)).ok());
  EXPECT_TRUE(Sphere::create(kMaxCoordinate).ok());
}

TEST(Sphere, Accessors) {
  const Sphere s = make(Real(2.5));
  EXPECT_EQ(Sphere::kType, ShapeType::Sphere);
  EXPECT_EQ(s.radius(), Real(2.5));
  EXPECT_EQ(s.core_radius(), Real(2.5));
  EXPECT_EQ(s.core_support(Vec3(1, 2, 3)), Vec3(0));
}

TEST(Sphere, SupportMatchesSurfaceSamples) {
  test::Random rng(101);
  const int n = 6000;
  for (const Real r : test::scales()) {
    const Sphere s = make(r);
    const auto pts = samples(r, n);
    const Real res = test::fibonacci_resolution(n) * r;
    test::check_support_against_samples(s, pts, res * res / (Real(2) * r), precision_tolerance(r), rng, 500);
  }
}

TEST(Sphere, SupportIsCorePlusRadius) {
  test::Random rng(102);
  const Sphere s = make(Real(3));
  for (int i = 0; i < 1000; ++i) {
    const Vec3 d = rng.vec3(Real(-10), Real(10));
    if (glm::length(d) < Real(1e-3)) continue;
    test::expect_vec_near(s.support(d), s.core_support(d) + s.core_radius() * glm::normalize(d),
                          precision_tolerance(Real(3), Real(8)));
    EXPECT_NEAR(glm::length(s.support(d)), Real(3), precision_tolerance(Real(3), Real(8)));
  }
}

TEST(Sphere, SupportOfDegenerateDirections) {
  const Sphere s = make(Real(2));
  const Vec3 z = s.support(Vec3(0));
  EXPECT_TRUE(test::all_finite(z));
  EXPECT_NEAR(glm::length(z), Real(2), precision_tolerance(Real(2)));
  const Real tiny = std::numeric_limits<Real>::denorm_min();
  EXPECT_TRUE(test::all_finite(s.support(Vec3(tiny, 0, 0))));
  const Real huge = std::numeric_limits<Real>::max() / Real(4);
  EXPECT_TRUE(test::all_finite(s.support(Vec3(huge, huge, 0))));
}

TEST(Sphere, LocalAndWorldBoxes) {
  test::Random rng(103);
  const int n = 20000;
  for (const Real r : test::scales()) {
    const Sphere s = make(r);
    const Aabb local = s.local_aabb();
    test::expect_vec_near(local.min, Vec3(-r), Real(0));
    test::expect_vec_near(local.max, Vec3(r), Real(0));
    const auto pts = samples(r, n);
    const Real res = test::fibonacci_resolution(n) * r;
    const Real extent = Real(10) * r;
    test::check_world_aabb_against_samples(s, pts, res, precision_tolerance(extent), rng, 50, extent);
  }
}

TEST(Sphere, WorldBoxFarFromOrigin) {
  const Sphere s = make(Real(0.5));
  const Transform pose{Vec3(Real(1e4), Real(-1e4), Real(3e4)),
                       glm::angleAxis(Real(0.7), glm::normalize(Vec3(1, 2, 3)))};
  const Aabb box = s.world_aabb(pose);
  const Aabb ref = test::transformed_sample_box(samples(Real(0.5), 20000), pose);
  const Real tol = precision_tolerance(Real(3e4), Real(4));
  for (int a = 0; a < 3; ++a) {
    EXPECT_LE(box.min[a], ref.min[a] + tol);
    EXPECT_GE(box.max[a], ref.max[a] - tol);
    EXPECT_NEAR(box.max[a] - box.min[a], Real(1), Real(0.02));
  }
}

TEST(Sphere, ContainsMatchesImplicitFunction) {
  test::Random rng(104);
  for (const Real r : test::scales()) {
    const Sphere s = make(r);
    const auto inside = implicit_inside(r);
    int in = 0;
    for (int i = 0; i < 20000; ++i) {
      const Vec3 p = rng.vec3(-Real(1.5) * r, Real(1.5) * r);
      if (std::abs(glm::length(p) - r) <= precision_tolerance(r, Real(8))) continue;
      EXPECT_EQ(s.contains(p), inside(p));
      in += inside(p) ? 1 : 0;
    }
    EXPECT_GT(in, 2000);
    // The boundary counts as inside.
    EXPECT_TRUE(s.contains(Vec3(r, 0, 0)));
    EXPECT_TRUE(s.contains(Vec3(0, 0, -r)));
    EXPECT_TRUE(s.contains(Vec3(0)));
    EXPECT_FALSE(s.contains(Vec3(0, r * Real(1.001), 0)));
  }
}

TEST(Sphere, ClosestPointMatchesBruteForce) {
  test::Random rng(105);
  const int n = 20000;
  for (const Real r : test::scales()) {
    const Sphere s = make(r);
    const auto pts = samples(r, n);
    const Real res = test::fibonacci_resolution(n) * r;
    const Aabb region{Vec3(Real(-2) * r), Vec3(Real(2) * r)};
    test::check_closest_point_solid(s, pts, res, precision_tolerance(Real(4) * r), implicit_inside(r), region, rng,
                                    600);
  }
}

TEST(Sphere, ClosestPointAnalyticAndDegenerate) {
  const Sphere s = make(Real(2));
  // Outside along an axis.
  SurfacePoint sp = s.closest_point(Vec3(0, 5, 0));
  test::expect_vec_near(sp.point, Vec3(0, 2, 0), precision_tolerance(Real(2)));
  test::expect_vec_near(sp.normal, Vec3(0, 1, 0), precision_tolerance(Real(1)));
  EXPECT_NEAR(sp.signed_distance, Real(3), precision_tolerance(Real(5)));
  // Inside.
  sp = s.closest_point(Vec3(0, 0, Real(-0.5)));
  test::expect_vec_near(sp.point, Vec3(0, 0, -2), precision_tolerance(Real(2)));
  EXPECT_NEAR(sp.signed_distance, Real(-1.5), precision_tolerance(Real(2)));
  // On the surface.
  sp = s.closest_point(Vec3(2, 0, 0));
  EXPECT_NEAR(sp.signed_distance, Real(0), precision_tolerance(Real(2)));
  // The centre: any direction, but a unit normal, a surface point and distance -r.
  sp = s.closest_point(Vec3(0));
  EXPECT_NEAR(glm::length(sp.normal), Real(1), precision_tolerance(Real(1)));
  EXPECT_NEAR(glm::length(sp.point), Real(2), precision_tolerance(Real(2)));
  EXPECT_EQ(sp.signed_distance, Real(-2));
  // Denormal offsets from the centre never produce NaN.
  const Real tiny = std::numeric_limits<Real>::denorm_min();
  sp = s.closest_point(Vec3(tiny, 0, 0));
  EXPECT_TRUE(test::all_finite(sp.point) && test::all_finite(sp.normal));
}

TEST(Sphere, RaycastMatchesMarching) {
  test::Random rng(106);
  for (const Real r : test::scales()) {
    const Sphere s = make(r);
    const Aabb region{Vec3(Real(-2) * r), Vec3(Real(2) * r)};
    // The march resolves t to its step; the ray code must agree to the precision of Real.
    test::check_raycast_solid(s, implicit_inside(r), region, precision_tolerance(Real(8) * r, Real(256)), rng, 2000);
  }
}

TEST(Sphere, RaycastAnalyticCases) {
  const Sphere s = make(Real(1));
  const Real tol = precision_tolerance(Real(4), Real(16));
  // Head-on, direction of length 2: t in units of |direction|.
  auto hit = s.raycast(Ray{Vec3(-5, 0, 0), Vec3(2, 0, 0)}, Real(10));
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->t, Real(2), tol);
  test::expect_vec_near(hit->point, Vec3(-1, 0, 0), tol);
  test::expect_vec_near(hit->normal, Vec3(-1, 0, 0), tol);
  // Too short.
  EXPECT_FALSE(s.raycast(Ray{Vec3(-5, 0, 0), Vec3(2, 0, 0)}, Real(1.9)));
  // Pointing away.
  EXPECT_FALSE(s.raycast(Ray{Vec3(-5, 0, 0), Vec3(-1, 0, 0)}, Real(100)));
  // Origin inside: t = 0, normal = -direction / |direction|.
  hit = s.raycast(Ray{Vec3(Real(0.2), 0, 0), Vec3(0, 0, 3)}, Real(10));
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->t, Real(0));
  test::expect_vec_near(hit->normal, Vec3(0, 0, -1), tol);
  // Zero direction: hits only from inside.
  hit = s.raycast(Ray{Vec3(Real(0.5), 0, 0), Vec3(0)}, Real(10));
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->t, Real(0));
  EXPECT_TRUE(test::all_finite(hit->normal));
  EXPECT_FALSE(s.raycast(Ray{Vec3(5, 0, 0), Vec3(0)}, Real(10)));
  // Tangent ray: either a touching hit at t = 5 on the surface or a miss, never NaN.
  hit = s.raycast(Ray{Vec3(-5, 1, 0), Vec3(1, 0, 0)}, Real(10));
  if (hit) {
    EXPECT_NEAR(hit->t, Real(5), Real(0.01));
    EXPECT_NEAR(glm::length(hit->point), Real(1), tol);
  }
  // Unbounded max_t.
  hit = s.raycast(Ray{Vec3(0, 0, 10), Vec3(0, 0, -1)}, std::numeric_limits<Real>::max());
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->t, Real(9), tol);
  hit = s.raycast(Ray{Vec3(0, 0, 10), Vec3(0, 0, -1)}, test::inf_value());
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->t, Real(9), tol);
}

TEST(Sphere, PlacedQueriesMatchLocalOnes) {
  test::Random rng(107);
  const Sphere s = make(Real(1.5));
  for (int i = 0; i < 500; ++i) {
    const Transform pose = rng.pose(Real(20));
    // A query outside the sphere, so that the ray to its centre enters through the surface.
    const Vec3 q = pose.position + rng.vector_of_length(Real(1.6), Real(4));
    const Real tol = precision_tolerance(Real(30), Real(32));
    const SurfacePoint w = closest_point(s, pose, q);
    EXPECT_NEAR(w.signed_distance, glm::length(q - pose.position) - Real(1.5), tol);
    EXPECT_NEAR(glm::length(w.point - pose.position), Real(1.5), tol);
    EXPECT_EQ(contains(s, pose, q), glm::length(q - pose.position) <= Real(1.5)) << i;
    const Vec3 d = rng.unit_vector();
    test::expect_vec_near(support(s, pose, d), pose.position + Real(1.5) * d, tol);
    const Ray ray{q, pose.position - q};
    const auto hit = raycast(s, pose, ray, Real(1));
    ASSERT_TRUE(hit);
    EXPECT_NEAR(glm::length(hit->point - pose.position), Real(1.5), tol);
  }
}

TEST(Sphere, MassPropertiesAnalyticAndIntegrated) {
  for (const Real r : {Real(0.01), Real(1), Real(7)}) {
    const Sphere s = make(r);
    const Real density = Real(2.5);
    const MassProperties m = s.mass_properties(density);
    const double pi = 3.14159265358979323846;
    const double vol = 4.0 / 3.0 * pi * r * r * r;
    const double mass = density * vol;
    const double inertia = 0.4 * mass * r * r;
    const Real rel = precision_tolerance(Real(1), Real(16));
    EXPECT_NEAR(m.volume, vol, rel * vol);
    EXPECT_NEAR(m.mass, mass, rel * mass);
    test::expect_vec_near(m.centroid, Vec3(0), Real(0));
    for (int a = 0; a < 3; ++a) {
      for (int b = 0; b < 3; ++b) {
        EXPECT_NEAR(m.inertia[a][b], a == b ? inertia : 0.0, rel * inertia);
      }
    }
    const MassProperties grid = test::integrate_mass_on_grid(implicit_inside(r), s.local_aabb(), 80, density);
    test::expect_mass_near(m, grid, Real(0.01), Real(0.01) * r);
  }
}

TEST(Sphere, DefaultDensityIsOne) {
  const Sphere s = make(Real(1));
  EXPECT_NEAR(s.mass_properties().mass, s.mass_properties().volume, precision_tolerance(Real(4)));
}

TEST(Sphere, NonFiniteQueryInputHasDefinedAnswers) { test::exercise_queries_with_non_finite_input(make(Real(1.5))); }

}  // namespace test_sphere
}  // namespace proxima
