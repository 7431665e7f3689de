// Point: every member checked against distances to the origin computed in double in the
// test (closest point, contains, the ray's nearest approach) and the one-sample brute force
// of support and boxes.
#include <gtest/gtest.h>

#include <proxima/core/tolerance.hpp>
#include <proxima/shapes/placed.hpp>
#include <proxima/shapes/point.hpp>

#include <cmath>

#include "shapes/shape_test_util.hpp"
#include "support/random.hpp"

namespace proxima {
namespace test_point {

using test::precision_tolerance;

const Point kPoint = Point::create().value();

// Distance from the origin to the ray origin + t d, t in [0, max_t], in double.
double ray_distance_to_origin(const Ray& ray, Real max_t, double& t_closest) {
  const double o[3] = {ray.origin.x, ray.origin.y, ray.origin.z};
  const double d[3] = {ray.direction.x, ray.direction.y, ray.direction.z};
  const double dd = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
  double t = dd > 0.0 ? -(o[0] * d[0] + o[1] * d[1] + o[2] * d[2]) / dd : 0.0;
  t = std::min(std::max(t, 0.0), static_cast<double>(max_t));
  t_closest = t;
  double s = 0.0;
  for (int i = 0; i < 3; ++i) s += (o[i] + t * d[i]) * (o[i] + t * d[i]);
  return std::sqrt(s);
}

TEST(Point, CreateAndTrivialMembers) {
  ASSERT_TRUE(Point::create().ok());
  EXPECT_EQ(Point::kType, ShapeType::Point);
  EXPECT_EQ(kPoint.core_radius(), Real(0));
  test::Random rng(401);
  for (int i = 0; i < 100; ++i) {
    const Vec3 d = rng.vec3(Real(-5), Real(5));
    EXPECT_EQ(kPoint.support(d), Vec3(0));
    EXPECT_EQ(kPoint.core_support(d), Vec3(0));
  }
  EXPECT_EQ(kPoint.support(Vec3(0)), Vec3(0));
}

TEST(Point, Boxes) {
  EXPECT_EQ(kPoint.local_aabb().min, Vec3(0));
  EXPECT_EQ(kPoint.local_aabb().max, Vec3(0));
  test::Random rng(402);
  for (int i = 0; i < 100; ++i) {
    const Transform pose = rng.pose(Real(1e4));
    const Aabb box = kPoint.world_aabb(pose);
    EXPECT_EQ(box.min, pose.position);
    EXPECT_EQ(box.max, pose.position);
    EXPECT_TRUE(box.contains(pose.apply(Vec3(0))));
  }
}

TEST(Point, ContainsOnlyTheOrigin) {
  EXPECT_TRUE(kPoint.contains(Vec3(0)));
  const Real tol = linear_tolerance(Real(0));
  EXPECT_TRUE(kPoint.contains(Vec3(tol * Real(0.5), 0, 0)));
  EXPECT_FALSE(kPoint.contains(Vec3(0, tol * Real(2), 0)));
  test::Random rng(403);
  for (const Real s : test::scales()) {
    for (int i = 0; i < 1000; ++i) {
      const Real length = rng.uniform(Real(0.5), Real(2));
      const Vec3 p = rng.unit_vector() * s * length;
      EXPECT_EQ(kPoint.contains(p), glm::length(p) <= tol);
    }
  }
}

TEST(Point, ClosestPointIsTheOrigin) {
  test::Random rng(404);
  for (const Real s : test::scales()) {
    for (int i = 0; i < 2000; ++i) {
      const Vec3 p = rng.vec3(-s, s);
      const SurfacePoint sp = kPoint.closest_point(p);
      const double ref = std::sqrt(double(p.x) * p.x + double(p.y) * p.y + double(p.z) * p.z);
      EXPECT_EQ(sp.point, Vec3(0));
      EXPECT_NEAR(sp.signed_distance, ref, precision_tolerance(s, Real(4)));
      EXPECT_GE(sp.signed_distance, Real(0));
      EXPECT_NEAR(glm::length(sp.normal), Real(1), precision_tolerance(Real(1), Real(4)));
      test::expect_vec_near(sp.normal * sp.signed_distance, p, precision_tolerance(s, Real(8)));
    }
  }
  // At the origin, denormal and huge offsets: unit normals, no NaN.
  SurfacePoint sp = kPoint.closest_point(Vec3(0));
  EXPECT_EQ(sp.signed_distance, Real(0));
  EXPECT_NEAR(glm::length(sp.normal), Real(1), precision_tolerance(Real(1)));
  const Real tiny = std::numeric_limits<Real>::denorm_min();
  sp = kPoint.closest_point(Vec3(tiny, 0, -tiny));
  EXPECT_NEAR(glm::length(sp.normal), Real(1), precision_tolerance(Real(1), Real(4)));
  EXPECT_GT(sp.signed_distance, Real(0));
  sp = kPoint.closest_point(Vec3(kMaxCoordinate, -kMaxCoordinate, kMaxCoordinate));
  EXPECT_TRUE(test::all_finite(sp.normal) && std::isfinite(sp.signed_distance));
  EXPECT_NEAR(sp.signed_distance, kMaxCoordinate * std::sqrt(Real(3)), kMaxCoordinate * precision_tolerance(Real(1)));
}

TEST(Point, RaycastHitsOnlyRaysThroughThePoint) {
  test::Random rng(405);
  int hits = 0;
  for (const Real s : test::scales()) {
    for (int i = 0; i < 3000; ++i) {
      const Vec3 u = rng.unit_vector();
      const Real speed = rng.uniform(Real(0.5), Real(2)) * s;
      const Real dist = rng.uniform(Real(0.1), Real(3)) * s;
      Ray ray{-u * dist, u * speed};
      if (i % 3 == 1) {
        // Offset sideways by a random amount, mostly far more than the tolerance.
        Vec3 t1;
        Vec3 t2;
        orthonormal_basis(u, t1, t2);
        ray.origin += glm::normalize(t1) * s * rng.uniform(Real(1e-3), Real(1));
      } else if (i % 3 == 2) {
        ray.direction = rng.unit_vector() * speed;  // a random direction from the same origin
      }
      const Real max_t = rng.uniform(Real(0), Real(4)) * s / speed;
      double t_ref = 0.0;
      const double miss = ray_distance_to_origin(ray, max_t, t_ref);
      const auto hit = kPoint.raycast(ray, max_t);
      const Real tol = linear_tolerance(test::max_abs(ray.origin));
      if (miss > 2.0 * tol) {
        EXPECT_FALSE(hit) << "case " << i << " miss distance " << miss;
      } else if (miss < 0.5 * tol) {
        ASSERT_TRUE(hit) << "case " << i;
        ++hits;
        EXPECT_NEAR(hit->t, t_ref, 4.0 * tol / speed + precision_tolerance(Real(t_ref), Real(4)));
        test::expect_vec_near(hit->normal, -glm::normalize(ray.direction), precision_tolerance(Real(1), Real(8)));
        EXPECT_LE(glm::length(hit->point), Real(4) * tol);
      }
    }
  }
  EXPECT_GT(hits, 1000);
}

TEST(Point, RaycastDegenerateCases) {
  // Starting on the point: t = 0.
  auto hit = kPoint.raycast(Ray{Vec3(0), Vec3(1, 0, 0)}, Real(1));
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->t, Real(0));
  test::expect_vec_near(hit->normal, Vec3(-1, 0, 0), Real(0));
  // Zero direction: on the point only.
  hit = kPoint.raycast(Ray{Vec3(0), Vec3(0)}, Real(1));
  ASSERT_TRUE(hit);
  EXPECT_NEAR(glm::length(hit->normal), Real(1), precision_tolerance(Real(1)));
  EXPECT_FALSE(kPoint.raycast(Ray{Vec3(1, 0, 0), Vec3(0)}, Real(1)));
  // Pointing away, too short, negative max_t.
  EXPECT_FALSE(kPoint.raycast(Ray{Vec3(1, 0, 0), Vec3(1, 0, 0)}, Real(10)));
  EXPECT_FALSE(kPoint.raycast(Ray{Vec3(1, 0, 0), Vec3(-1, 0, 0)}, Real(0.5)));
  EXPECT_FALSE(kPoint.raycast(Ray{Vec3(0), Vec3(-1, 0, 0)}, Real(-1)));
  // Unbounded max_t, tiny and huge directions.
  hit = kPoint.raycast(Ray{Vec3(0, 5, 0), Vec3(0, -1, 0)}, test::inf_value());
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->t, Real(5), precision_tolerance(Real(5)));
  const Real tiny = std::numeric_limits<Real>::denorm_min();
  EXPECT_FALSE(kPoint.raycast(Ray{Vec3(0, 5, 0), Vec3(0, -tiny, 0)}, Real(1)));
  hit = kPoint.raycast(Ray{Vec3(0, 5, 0), Vec3(0, -kMaxCoordinate, 0)}, Real(1));
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->t, Real(5) / kMaxCoordinate, Real(5) / kMaxCoordinate * precision_tolerance(Real(1)));
}

TEST(Point, MassPropertiesAreZero) {
  const MassProperties m = kPoint.mass_properties(Real(1000));
  EXPECT_EQ(m.volume, Real(0));
  EXPECT_EQ(m.mass, Real(0));
  EXPECT_EQ(m.centroid, Vec3(0));
  EXPECT_EQ(m.inertia, Mat3(Real(0)));
  EXPECT_EQ(kPoint.mass_properties(test::inf_value()).mass, Real(0));
}

TEST(Point, PlacedQueries) {
  test::Random rng(406);
  for (int i = 0; i < 200; ++i) {
    const Transform pose = rng.pose(Real(50));
    const Vec3 q = rng.vec3(Real(-50), Real(50));
    const SurfacePoint sp = closest_point(kPoint, pose, q);
    EXPECT_NEAR(sp.signed_distance, glm::length(q - pose.position), precision_tolerance(Real(200), Real(8)));
    test::expect_vec_near(sp.point, pose.position, precision_tolerance(Real(50), Real(8)));
    test::expect_vec_near(support(kPoint, pose, rng.unit_vector()), pose.position, precision_tolerance(Real(50)));
  }
}

TEST(Point, NonFiniteQueryInputHasDefinedAnswers) { test::exercise_queries_with_non_finite_input(kPoint); }

}  // namespace test_point
}  // namespace proxima
