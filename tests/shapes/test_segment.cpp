// Segment: every member checked against references the segment does not compute itself:
// dense samples along it (support, world box, closest point, contains), distances between
// the ray and those samples computed in double (ray casts), and rays built to pass through
// a chosen point of the segment.
#include <gtest/gtest.h>

#include <proxima/core/tolerance.hpp>
#include <proxima/shapes/placed.hpp>
#include <proxima/shapes/segment.hpp>

#include <vector>

#include "shapes/shape_test_util.hpp"
#include "support/random.hpp"

namespace proxima {
namespace test_segment {

using test::precision_tolerance;

Segment make(const Vec3& a, const Vec3& b) { return Segment::create(a, b).value(); }

// n + 1 evenly spaced points from a to b; covering radius |b - a| / (2 n).
std::vector<Vec3> samples(const Vec3& a, const Vec3& b, int n) {
  std::vector<Vec3> out;
  for (int i = 0; i <= n; ++i) {
    const Real t = static_cast<Real>(i) / static_cast<Real>(n);
    out.push_back(a + t * (b - a));
  }
  return out;
}

// A random segment of length ~ scale near `center`.
Segment random_segment(test::Random& rng, Real scale, const Vec3& center = Vec3(0)) {
  for (;;) {
    const Vec3 a = center + rng.vec3(-scale, scale);
    const Vec3 b = center + rng.vec3(-scale, scale);
    if (glm::length(b - a) > Real(0.2) * scale) return make(a, b);
  }
}

// Distance (double) from the ray to the nearest of the segment samples.
double ray_sample_distance(const Ray& ray, Real max_t, const std::vector<Vec3>& pts) {
  const double o[3] = {ray.origin.x, ray.origin.y, ray.origin.z};
  const double d[3] = {ray.direction.x, ray.direction.y, ray.direction.z};
  const double dd = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
  double best = 1e300;
  for (const Vec3& p : pts) {
    const double r[3] = {p.x - o[0], p.y - o[1], p.z - o[2]};
    double t = dd > 0.0 ? (r[0] * d[0] + r[1] * d[1] + r[2] * d[2]) / dd : 0.0;
    t = std::min(std::max(t, 0.0), static_cast<double>(max_t));
    double s = 0.0;
    for (int i = 0; i < 3; ++i) s += (r[i] - t * d[i]) * (r[i] - t * d[i]);
    best = std::min(best, std::sqrt(s));
  }
  return best;
}

TEST(Segment, CreateValidatesEndPoints) {
  test::expect_vector_field_finite_validated([](const Vec3& a) { return Segment::create(a, Vec3(1, 2, 3)); }, Vec3(0),
                                             "a");
  test::expect_vector_field_finite_validated([](const Vec3& b) { return Segment::create(Vec3(1, 2, 3), b); }, Vec3(0),
                                             "b");
  test::expect_error(Segment::create(Vec3(1, 2, 3), Vec3(1, 2, 3)), ErrorCode::Degenerate, "b");
  test::expect_error(Segment::create(Vec3(0), Vec3(0)), ErrorCode::Degenerate, "b");
  // Coinciding within the relative tolerance of the coordinates.
  const Real big = Real(1000);
  test::expect_error(Segment::create(Vec3(big, 0, 0), Vec3(big + kRelativeTolerance * big * Real(0.5), 0, 0)),
                     ErrorCode::Degenerate, "b");
  EXPECT_TRUE(Segment::create(Vec3(big, 0, 0), Vec3(big + kRelativeTolerance * big * Real(4), 0, 0)).ok());
  // Tiny segments near the origin are fine.
  EXPECT_TRUE(Segment::create(Vec3(0), Vec3(Real(1e-10), 0, 0)).ok());
  // a is checked before b.
  test::ScopedNoFpTraps no_traps;
  test::expect_error(Segment::create(Vec3(test::nan_value()), Vec3(test::nan_value())), ErrorCode::NotFinite, "a.x");
}

TEST(Segment, Accessors) {
  const Segment s = make(Vec3(1, 2, 3), Vec3(4, 6, 3));
  EXPECT_EQ(Segment::kType, ShapeType::Segment);
  EXPECT_EQ(s.a(), Vec3(1, 2, 3));
  EXPECT_EQ(s.b(), Vec3(4, 6, 3));
  EXPECT_NEAR(s.length(), Real(5), precision_tolerance(Real(5)));
  EXPECT_EQ(s.core_radius(), Real(0));
  EXPECT_EQ(s.tolerance(), linear_tolerance(Real(6)));
}

TEST(Segment, SupportMatchesSamples) {
  test::Random rng(501);
  for (const Real sc : test::scales()) {
    for (int k = 0; k < 20; ++k) {
      const Segment s = random_segment(rng, sc);
      // The end points are samples: no sampling gap.
      test::check_support_against_samples(s, samples(s.a(), s.b(), 50), Real(0), precision_tolerance(sc), rng, 100);
    }
  }
  const Segment s = make(Vec3(0), Vec3(1, 0, 0));
  EXPECT_EQ(s.support(Vec3(0)), s.a());
  EXPECT_EQ(s.support(Vec3(0, 1, 0)), s.a());  // a tie keeps a
  EXPECT_EQ(s.core_support(Vec3(1, 1, 0)), s.b());
}

TEST(Segment, Boxes) {
  const Segment s = make(Vec3(1, -2, 3), Vec3(-4, 5, 3));
  EXPECT_EQ(s.local_aabb().min, Vec3(-4, -2, 3));
  EXPECT_EQ(s.local_aabb().max, Vec3(1, 5, 3));
  test::Random rng(502);
  for (const Real sc : test::scales()) {
    const Segment r = random_segment(rng, sc);
    test::check_world_aabb_against_samples(r, samples(r.a(), r.b(), 20), Real(0), precision_tolerance(Real(20) * sc),
                                           rng, 100, Real(10) * sc);
  }
}

TEST(Segment, ContainsPointsOnItOnly) {
  test::Random rng(503);
  for (const Real sc : test::scales()) {
    for (int k = 0; k < 20; ++k) {
      const Segment s = random_segment(rng, sc, rng.vec3(-sc, sc));
      const Vec3 dir = glm::normalize(s.b() - s.a());
      Vec3 t1;
      Vec3 t2;
      orthonormal_basis(dir, t1, t2);
      for (int i = 0; i < 100; ++i) {
        const Real t = rng.uniform(Real(0), Real(1));
        const Vec3 on = s.a() + t * (s.b() - s.a());
        EXPECT_TRUE(s.contains(on));
        const Real v = rng.uniform(Real(-1), Real(1));
        const Real u = rng.uniform(Real(-1), Real(1));
        const Vec3 side = glm::normalize(t1 * u + t2 * v);
        EXPECT_TRUE(s.contains(on + side * s.tolerance() * Real(0.25)));
        EXPECT_FALSE(s.contains(on + side * s.tolerance() * Real(4)));
        EXPECT_FALSE(s.contains(on + side * (sc * Real(0.01) + s.tolerance() * Real(4))));
      }
      EXPECT_TRUE(s.contains(s.a()));
      EXPECT_TRUE(s.contains(s.b()));
      EXPECT_FALSE(s.contains(s.b() + dir * s.tolerance() * Real(4)));
      EXPECT_FALSE(s.contains(s.a() - dir * s.tolerance() * Real(4)));
    }
  }
}

TEST(Segment, ClosestPointMatchesBruteForce) {
  test::Random rng(504);
  for (const Real sc : test::scales()) {
    for (int k = 0; k < 10; ++k) {
      const Segment s = random_segment(rng, sc);
      const int n = 4000;
      const auto pts = samples(s.a(), s.b(), n);
      const Real res = s.length() / static_cast<Real>(2 * n);
      const Real tol = precision_tolerance(Real(8) * sc);
      for (int i = 0; i < 100; ++i) {
        const Vec3 q = rng.vec3(Real(-2) * sc, Real(2) * sc);
        const SurfacePoint sp = s.closest_point(q);
        const Real brute = test::nearest_sample_distance(pts, q);
        EXPECT_GE(sp.signed_distance, Real(0));
        EXPECT_LE(sp.signed_distance, brute + tol);
        EXPECT_GE(sp.signed_distance, brute - res - tol);
        EXPECT_NEAR(glm::length(q - sp.point), sp.signed_distance, tol);
        EXPECT_LE(test::nearest_sample_distance(pts, sp.point), res + tol);
        EXPECT_NEAR(glm::length(sp.normal), Real(1), precision_tolerance(Real(1), Real(8)));
        if (sp.signed_distance > Real(100) * tol) {
          test::expect_vec_near(sp.normal, (q - sp.point) / sp.signed_distance,
                                tol / sp.signed_distance + precision_tolerance(Real(1), Real(8)));
        }
      }
    }
  }
}

TEST(Segment, ClosestPointOnTheSegmentAndDegenerate) {
  const Segment s = make(Vec3(-1, 0, 0), Vec3(1, 0, 0));
  const Real tol = precision_tolerance(Real(4));
  // Beside the middle, beyond an end.
  SurfacePoint sp = s.closest_point(Vec3(Real(0.3), 2, 0));
  test::expect_vec_near(sp.point, Vec3(Real(0.3), 0, 0), tol);
  test::expect_vec_near(sp.normal, Vec3(0, 1, 0), tol);
  EXPECT_NEAR(sp.signed_distance, Real(2), tol);
  sp = s.closest_point(Vec3(4, 0, 4));
  test::expect_vec_near(sp.point, Vec3(1, 0, 0), tol);
  EXPECT_NEAR(sp.signed_distance, Real(5), tol);
  // On the segment (interior, end points): distance 0, a unit normal orthogonal to it.
  for (const Vec3& q : {Vec3(Real(0.25), 0, 0), Vec3(-1, 0, 0), Vec3(1, 0, 0), Vec3(0)}) {
    sp = s.closest_point(q);
    EXPECT_EQ(sp.signed_distance, Real(0));
    EXPECT_NEAR(glm::length(sp.normal), Real(1), tol);
    EXPECT_NEAR(sp.normal.x, Real(0), tol);
  }
  // Denormally off the segment: still finite.
  const Real tiny = std::numeric_limits<Real>::denorm_min();
  sp = s.closest_point(Vec3(Real(0.5), tiny, 0));
  EXPECT_TRUE(test::all_finite(sp.normal));
  EXPECT_NEAR(glm::length(sp.normal), Real(1), tol);
}

TEST(Segment, RaycastThroughChosenPoints) {
  test::Random rng(505);
  int hits = 0;
  for (const Real sc : test::scales()) {
    for (int k = 0; k < 20; ++k) {
      const Segment s = random_segment(rng, sc);
      const Vec3 w = glm::normalize(s.b() - s.a());
      for (int i = 0; i < 100; ++i) {
        const Real t_on = rng.uniform(Real(0), Real(1));
        const Vec3 target = s.a() + t_on * (s.b() - s.a());
        Vec3 u = rng.unit_vector();
        const Real sin_angle = glm::length(glm::cross(u, w));
        if (sin_angle < Real(0.2)) continue;  // shallow rays are checked separately
        const Real dist = rng.uniform(Real(0.1), Real(3)) * sc;
        const Real speed = rng.uniform(Real(0.5), Real(2));
        const Ray ray{target - u * dist, u * speed};
        const auto hit = s.raycast(ray, Real(4) * sc / speed);
        ASSERT_TRUE(hit) << "scale " << sc << " case " << i;
        ++hits;
        const Real tol = std::max(s.tolerance(), linear_tolerance(test::max_abs(ray.origin)));
        EXPECT_NEAR(hit->t, dist / speed, Real(4) * tol / sin_angle / speed + precision_tolerance(sc));
        test::expect_vec_near(hit->point, ray.at(hit->t), precision_tolerance(Real(4) * sc));
        // The normal is unit, orthogonal to the segment and faces the ray; a segment that
        // fits within the tolerance of the ray's line is met head-on (normal -u).
        EXPECT_NEAR(glm::length(hit->normal), Real(1), precision_tolerance(Real(1), Real(16)));
        EXPECT_LT(glm::dot(hit->normal, u), Real(0));
        if (s.length() * sin_angle > Real(4) * tol) {
          EXPECT_NEAR(glm::dot(hit->normal, w), Real(0), precision_tolerance(Real(1), Real(64)));
        } else if (s.length() * sin_angle < Real(0.5) * tol) {
          test::expect_vec_near(hit->normal, -u, precision_tolerance(Real(1), Real(16)));
        }
        // Too short a ray misses (when it stops clearly farther than the tolerance).
        if (dist * Real(0.1) * sin_angle > Real(4) * tol) {
          EXPECT_FALSE(s.raycast(ray, dist / speed * Real(0.9)));
        }
      }
    }
  }
  EXPECT_GT(hits, 3000);
}

TEST(Segment, RandomRaysMissUnlessTheyPassWithinTolerance) {
  test::Random rng(506);
  for (const Real sc : test::scales()) {
    for (int k = 0; k < 10; ++k) {
      const Segment s = random_segment(rng, sc);
      const int n = 2000;
      const auto pts = samples(s.a(), s.b(), n);
      const Real res = s.length() / static_cast<Real>(2 * n);
      for (int i = 0; i < 100; ++i) {
        const Ray ray{rng.vec3(Real(-3) * sc, Real(3) * sc), rng.vector_of_length(Real(0.5), Real(2))};
        const Real max_t = Real(6) * sc;
        const double miss = ray_sample_distance(ray, max_t, pts);
        const Real tol = std::max(s.tolerance(), linear_tolerance(test::max_abs(ray.origin)));
        const auto hit = s.raycast(ray, max_t);
        if (miss > 2.0 * tol + res) {
          EXPECT_FALSE(hit) << "scale " << sc << " case " << i << " distance " << miss;
        }
        if (hit) {
          EXPECT_LE(s.closest_point(hit->point).signed_distance, Real(2) * tol);
        }
      }
    }
  }
}

TEST(Segment, RaycastAlongTheSegment) {
  const Segment s = make(Vec3(1, 1, 1), Vec3(3, 1, 1));
  const Real tol = precision_tolerance(Real(8), Real(16));
  // From before a, along the line: enters at a.
  auto hit = s.raycast(Ray{Vec3(-1, 1, 1), Vec3(2, 0, 0)}, Real(10));
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->t, Real(1), tol);
  test::expect_vec_near(hit->point, Vec3(1, 1, 1), tol);
  test::expect_vec_near(hit->normal, Vec3(-1, 0, 0), tol);
  // From beyond b, backwards: enters at b.
  hit = s.raycast(Ray{Vec3(7, 1, 1), Vec3(-1, 0, 0)}, Real(10));
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->t, Real(4), tol);
  // Starting inside the segment: t = 0.
  hit = s.raycast(Ray{Vec3(2, 1, 1), Vec3(1, 0, 0)}, Real(10));
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->t, Real(0));
  // Along the line but pointing away, or stopping short.
  EXPECT_FALSE(s.raycast(Ray{Vec3(-1, 1, 1), Vec3(-1, 0, 0)}, Real(10)));
  EXPECT_FALSE(s.raycast(Ray{Vec3(-1, 1, 1), Vec3(1, 0, 0)}, Real(1.9)));
  // Parallel, offset by much more than the tolerance.
  EXPECT_FALSE(s.raycast(Ray{Vec3(-1, Real(1.001), 1), Vec3(1, 0, 0)}, Real(10)));
  // Zero direction, on and off the segment.
  hit = s.raycast(Ray{Vec3(Real(1.5), 1, 1), Vec3(0)}, Real(1));
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->t, Real(0));
  EXPECT_NEAR(glm::length(hit->normal), Real(1), tol);
  EXPECT_FALSE(s.raycast(Ray{Vec3(Real(1.5), 2, 1), Vec3(0)}, Real(1)));
  // Unbounded max_t, huge direction.
  hit = s.raycast(Ray{Vec3(2, -5, 1), Vec3(0, 1, 0)}, test::inf_value());
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->t, Real(6), tol);
  hit = s.raycast(Ray{Vec3(2, -5, 1), Vec3(0, kMaxCoordinate, 0)}, Real(1));
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->t * kMaxCoordinate, Real(6), tol);
  EXPECT_FALSE(s.raycast(Ray{Vec3(2, -5, 1), Vec3(0, 1, 0)}, Real(-1)));
}

TEST(Segment, FarFromOrigin) {
  const Vec3 c(Real(1e4), Real(-1e4), Real(1e4));
  const Segment s = make(c, c + Vec3(1, 2, 2));
  const Real tol = precision_tolerance(Real(4e4), Real(4));
  EXPECT_TRUE(s.contains(c + Vec3(Real(0.5), 1, 1)));
  // The tolerance is relative to the coordinates: 0.12 in float at 1e4.
  EXPECT_TRUE(s.contains(c + Vec3(Real(0.5), 1, 1) + Vec3(0, 0, s.tolerance() * Real(0.5))));
  EXPECT_FALSE(s.contains(c + Vec3(Real(0.5), 1, Real(1.5))));
  const SurfacePoint sp = s.closest_point(c + Vec3(0, 0, 3));
  EXPECT_NEAR(sp.signed_distance, std::sqrt(Real(5)), Real(16) * tol);
  const auto hit = s.raycast(Ray{c + Vec3(Real(0.5), 1, -5), Vec3(0, 0, 1)}, Real(10));
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->t, Real(6), Real(16) * tol);
}

TEST(Segment, MassPropertiesAreZeroAtTheMidpoint) {
  const Segment s = make(Vec3(1, 2, 3), Vec3(3, 2, -1));
  const MassProperties m = s.mass_properties(Real(5));
  EXPECT_EQ(m.volume, Real(0));
  EXPECT_EQ(m.mass, Real(0));
  EXPECT_EQ(m.centroid, Vec3(2, 2, 1));
  EXPECT_EQ(m.inertia, Mat3(Real(0)));
}

TEST(Segment, PlacedQueries) {
  test::Random rng(507);
  const Segment s = make(Vec3(-1, 0, 0), Vec3(2, 0, 0));
  for (int i = 0; i < 200; ++i) {
    const Transform pose = rng.pose(Real(20));
    const Vec3 local_q = rng.vec3(Real(-3), Real(3));
    const SurfacePoint w = closest_point(s, pose, pose.apply(local_q));
    const SurfacePoint l = s.closest_point(local_q);
    const Real tol = precision_tolerance(Real(40), Real(16));
    EXPECT_NEAR(w.signed_distance, l.signed_distance, tol);
    test::expect_vec_near(w.point, pose.apply(l.point), tol);
    const Vec3 d = rng.unit_vector();
    const Real best = std::max(glm::dot(pose.apply(s.a()), d), glm::dot(pose.apply(s.b()), d));
    EXPECT_NEAR(glm::dot(support(s, pose, d), d), best, tol);
  }
}

TEST(Segment, NonFiniteQueryInputHasDefinedAnswers) {
  test::exercise_queries_with_non_finite_input(make(Vec3(-1, 0, 0), Vec3(2, 1, 0)));
}

}  // namespace test_segment
}  // namespace proxima
