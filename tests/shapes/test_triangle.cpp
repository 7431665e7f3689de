// Triangle: every member checked against references the triangle does not compute itself:
// its vertices and a dense barycentric grid (support, world box, closest point, contains),
// and a ray-plane intersection with an inside test by signed areas, both in double
// (ray casts).
#include <gtest/gtest.h>

#include <proxima/core/tolerance.hpp>
#include <proxima/shapes/placed.hpp>
#include <proxima/shapes/triangle.hpp>

#include <array>
#include <optional>
#include <vector>

#include "shapes/shape_test_util.hpp"
#include "support/random.hpp"

namespace proxima {
namespace test_triangle {

using test::precision_tolerance;

Triangle make(const Vec3& a, const Vec3& b, const Vec3& c) { return Triangle::create(a, b, c).value(); }

// Barycentric grid with n subdivisions per edge; covering radius at most longest edge / n.
std::vector<Vec3> samples(const Triangle& t, int n, Real& resolution) {
  std::vector<Vec3> out;
  for (int i = 0; i <= n; ++i) {
    for (int j = 0; j <= n - i; ++j) {
      const Real u = static_cast<Real>(i) / static_cast<Real>(n);
      const Real v = static_cast<Real>(j) / static_cast<Real>(n);
      out.push_back(t.a() + u * (t.b() - t.a()) + v * (t.c() - t.a()));
    }
  }
  const Real longest = std::max({glm::length(t.b() - t.a()), glm::length(t.c() - t.b()), glm::length(t.a() - t.c())});
  resolution = longest / static_cast<Real>(n);
  return out;
}

// A random, not too thin triangle of size ~ scale around `center`.
Triangle random_triangle(test::Random& rng, Real scale, const Vec3& center = Vec3(0)) {
  for (;;) {
    const Vec3 a = center + rng.vec3(-scale, scale);
    const Vec3 b = center + rng.vec3(-scale, scale);
    const Vec3 c = center + rng.vec3(-scale, scale);
    const Real longest = std::max({glm::length(b - a), glm::length(c - b), glm::length(a - c)});
    if (longest > Real(0.3) * scale && glm::length(glm::cross(b - a, c - a)) > Real(0.1) * longest * longest) {
      return make(a, b, c);
    }
  }
}

// Reference ray cast in double: the ray meets the plane at t, then the point must be on
// the inner side of the three edges. `margin` receives the hit point's smallest relative
// distance to an edge line (the test skips near-edge rays) and the ray's |cos| with the
// plane normal.
struct RefHit {
  double t = 0.0;
  double edge_margin = 0.0;
  double cos = 0.0;
};
std::optional<RefHit> reference_raycast(const Ray& ray, Real max_t, const Triangle& tri) {
  using D3 = std::array<double, 3>;
  auto d3 = [](const Vec3& v) { return D3{v.x, v.y, v.z}; };
  auto sub = [](const D3& p, const D3& q) { return D3{p[0] - q[0], p[1] - q[1], p[2] - q[2]}; };
  auto dot = [](const D3& p, const D3& q) { return p[0] * q[0] + p[1] * q[1] + p[2] * q[2]; };
  auto cross = [](const D3& p, const D3& q) {
    return D3{p[1] * q[2] - p[2] * q[1], p[2] * q[0] - p[0] * q[2], p[0] * q[1] - p[1] * q[0]};
  };
  const D3 a = d3(tri.a());
  const D3 b = d3(tri.b());
  const D3 c = d3(tri.c());
  const D3 o = d3(ray.origin);
  const D3 d = d3(ray.direction);
  const D3 n = cross(sub(b, a), sub(c, a));
  const double nn = std::sqrt(dot(n, n));
  const double dd = std::sqrt(dot(d, d));
  const double denom = dot(n, d);
  RefHit r;
  r.cos = std::abs(denom) / (nn * dd);
  if (denom == 0.0) return std::nullopt;
  r.t = dot(n, sub(a, o)) / denom;
  if (r.t < 0.0 || r.t > max_t) return std::nullopt;
  const D3 p{o[0] + r.t * d[0], o[1] + r.t * d[1], o[2] + r.t * d[2]};
  // Signed areas of the sub-triangles, relative to the whole.
  const double w0 = dot(cross(sub(b, p), sub(c, p)), n) / (nn * nn);
  const double w1 = dot(cross(sub(c, p), sub(a, p)), n) / (nn * nn);
  const double w2 = dot(cross(sub(a, p), sub(b, p)), n) / (nn * nn);
  r.edge_margin = std::min({w0, w1, w2});
  if (r.edge_margin < 0.0) {
    r.edge_margin = std::abs(r.edge_margin);
    // Outside: report the margin but no hit.
    return RefHit{-1.0, r.edge_margin, r.cos};
  }
  return r;
}

TEST(Triangle, CreateValidatesVertices) {
  const Vec3 b(1, 0, 0);
  const Vec3 c(0, 1, 0);
  test::expect_vector_field_finite_validated([&](const Vec3& a) { return Triangle::create(a, b, c); }, Vec3(0), "a");
  test::expect_vector_field_finite_validated([&](const Vec3& v) { return Triangle::create(Vec3(0), v, c); }, b, "b");
  test::expect_vector_field_finite_validated([&](const Vec3& v) { return Triangle::create(Vec3(0), b, v); }, c, "c");
  // Collinear, coincident, all equal, nearly collinear (relative to the longest edge).
  test::expect_error(Triangle::create(Vec3(0), Vec3(2, 2, 2), Vec3(1, 1, 1)), ErrorCode::Degenerate, "vertices");
  test::expect_error(Triangle::create(Vec3(0), Vec3(0), Vec3(1, 1, 1)), ErrorCode::Degenerate, "vertices");
  test::expect_error(Triangle::create(Vec3(3), Vec3(3), Vec3(3)), ErrorCode::Degenerate, "vertices");
  const Real thin = kRelativeTolerance * Real(0.25);
  test::expect_error(Triangle::create(Vec3(0), Vec3(1, 0, 0), Vec3(Real(0.5), thin, 0)), ErrorCode::Degenerate,
                     "vertices");
  test::expect_error(Triangle::create(Vec3(0), Vec3(1000, 0, 0), Vec3(500, 1000 * thin, 0)), ErrorCode::Degenerate,
                     "vertices");
  EXPECT_TRUE(Triangle::create(Vec3(0), Vec3(1, 0, 0), Vec3(Real(0.5), kRelativeTolerance * 4, 0)).ok());
  // Tiny and huge triangles are fine.
  EXPECT_TRUE(Triangle::create(Vec3(0), Vec3(Real(1e-12), 0, 0), Vec3(0, Real(1e-12), 0)).ok());
  EXPECT_TRUE(Triangle::create(Vec3(-kMaxCoordinate), Vec3(kMaxCoordinate, -kMaxCoordinate, 0),
                               Vec3(0, kMaxCoordinate, kMaxCoordinate))
                  .ok());
}

TEST(Triangle, AccessorsNormalAndArea) {
  const Triangle t = make(Vec3(1, 0, 0), Vec3(0, 2, 0), Vec3(0, 0, 3));
  EXPECT_EQ(Triangle::kType, ShapeType::Triangle);
  EXPECT_EQ(t.a(), Vec3(1, 0, 0));
  EXPECT_EQ(t.b(), Vec3(0, 2, 0));
  EXPECT_EQ(t.c(), Vec3(0, 0, 3));
  EXPECT_EQ(t.vertex(0), t.a());
  EXPECT_EQ(t.vertex(1), t.b());
  EXPECT_EQ(t.vertex(2), t.c());
  EXPECT_EQ(t.core_radius(), Real(0));
  EXPECT_EQ(t.tolerance(), linear_tolerance(Real(3)));
  // (b - a) x (c - a) = (6, 3, 2), |.| = 7.
  test::expect_vec_near(t.normal(), Vec3(6, 3, 2) / Real(7), precision_tolerance(Real(1), Real(4)));
  EXPECT_NEAR(t.area(), Real(3.5), precision_tolerance(Real(4)));
  test::Random rng(701);
  for (const Real s : test::scales()) {
    for (int i = 0; i < 200; ++i) {
      const Triangle r = random_triangle(rng, s);
      const Vec3 e0 = r.b() - r.a();
      const Vec3 e1 = r.c() - r.a();
      // Heron's formula in double.
      const double la = glm::length(r.b() - r.c());
      const double lb = glm::length(r.c() - r.a());
      const double lc = glm::length(r.a() - r.b());
      const double p = 0.5 * (la + lb + lc);
      const double heron = std::sqrt(std::max(0.0, p * (p - la) * (p - lb) * (p - lc)));
      EXPECT_NEAR(r.area(), heron, 1e-3 * heron);
      EXPECT_NEAR(glm::length(r.normal()), Real(1), precision_tolerance(Real(1), Real(4)));
      EXPECT_NEAR(glm::dot(r.normal(), e0) / glm::length(e0), Real(0), precision_tolerance(Real(1), Real(16)));
      EXPECT_NEAR(glm::dot(r.normal(), e1) / glm::length(e1), Real(0), precision_tolerance(Real(1), Real(16)));
      EXPECT_GT(glm::dot(r.normal(), glm::cross(e0, e1)), Real(0));
    }
  }
}

TEST(Triangle, SupportIsTheBestVertex) {
  test::Random rng(702);
  for (const Real s : test::scales()) {
    for (int k = 0; k < 20; ++k) {
      const Triangle t = random_triangle(rng, s);
      Real res = Real(0);
      const auto pts = samples(t, 20, res);
      test::check_support_against_samples(t, pts, Real(0), precision_tolerance(Real(4) * s), rng, 100);
      for (int i = 0; i < 100; ++i) {
        const Vec3 d = rng.unit_vector();
        const Vec3 sp = t.support(d);
        EXPECT_TRUE(sp == t.a() || sp == t.b() || sp == t.c());
        EXPECT_EQ(t.core_support(d), sp);
      }
    }
  }
  const Triangle t = make(Vec3(0), Vec3(1, 0, 0), Vec3(0, 1, 0));
  EXPECT_EQ(t.support(Vec3(0)), t.a());
  EXPECT_EQ(t.support(Vec3(0, 0, 1)), t.a());  // all tie: the first
}

TEST(Triangle, Boxes) {
  const Triangle t = make(Vec3(1, -2, 3), Vec3(-4, 5, 0), Vec3(2, 2, 2));
  EXPECT_EQ(t.local_aabb().min, Vec3(-4, -2, 0));
  EXPECT_EQ(t.local_aabb().max, Vec3(2, 5, 3));
  test::Random rng(703);
  for (const Real s : test::scales()) {
    const Triangle r = random_triangle(rng, s);
    Real res = Real(0);
    const auto pts = samples(r, 10, res);
    // The vertices are samples: exact.
    test::check_world_aabb_against_samples(r, pts, Real(0), precision_tolerance(Real(20) * s), rng, 100, Real(10) * s);
  }
}

TEST(Triangle, ContainsPointsOnItOnly) {
  test::Random rng(704);
  for (const Real s : test::scales()) {
    for (int k = 0; k < 20; ++k) {
      const Triangle t = random_triangle(rng, s, rng.vec3(-s, s));
      for (int i = 0; i < 100; ++i) {
        Real u = rng.uniform(Real(0), Real(1));
        Real v = rng.uniform(Real(0), Real(1));
        if (u + v > Real(1)) {
          u = Real(1) - u;
          v = Real(1) - v;
        }
        const Vec3 on = t.a() + u * (t.b() - t.a()) + v * (t.c() - t.a());
        EXPECT_TRUE(t.contains(on));
        EXPECT_TRUE(t.contains(on + t.normal() * t.tolerance() * Real(0.25)));
        EXPECT_FALSE(t.contains(on + t.normal() * t.tolerance() * Real(4)));
        EXPECT_FALSE(t.contains(on - t.normal() * (s * Real(0.01) + t.tolerance() * Real(4))));
      }
      for (int i = 0; i < 3; ++i) EXPECT_TRUE(t.contains(t.vertex(i)));
      // Beyond a vertex, away from the centroid.
      const Vec3 centroid = (t.a() + t.b() + t.c()) / Real(3);
      EXPECT_FALSE(t.contains(t.a() + glm::normalize(t.a() - centroid) * t.tolerance() * Real(4)));
    }
  }
}

TEST(Triangle, ClosestPointMatchesBruteForce) {
  test::Random rng(705);
  for (const Real s : test::scales()) {
    for (int k = 0; k < 10; ++k) {
      const Triangle t = random_triangle(rng, s);
      Real res = Real(0);
      const auto pts = samples(t, 150, res);
      const Real tol = precision_tolerance(Real(8) * s);
      for (int i = 0; i < 60; ++i) {
        const Vec3 q = rng.vec3(Real(-2) * s, Real(2) * s);
        const SurfacePoint sp = t.closest_point(q);
        const Real brute = test::nearest_sample_distance(pts, q);
        EXPECT_GE(sp.signed_distance, Real(0));
        EXPECT_LE(sp.signed_distance, brute + tol);
        EXPECT_GE(sp.signed_distance, brute - res - tol);
        EXPECT_NEAR(glm::length(q - sp.point), sp.signed_distance, tol);
        EXPECT_TRUE(t.contains(sp.point));
        EXPECT_NEAR(glm::length(sp.normal), Real(1), precision_tolerance(Real(1), Real(8)));
        if (sp.signed_distance > t.tolerance()) {
          test::expect_vec_near(sp.normal, (q - sp.point) / sp.signed_distance,
                                tol / sp.signed_distance + precision_tolerance(Real(1), Real(8)));
        }
      }
    }
  }
}

TEST(Triangle, ClosestPointOnTheTriangleAndDegenerate) {
  const Triangle t = make(Vec3(0), Vec3(2, 0, 0), Vec3(0, 2, 0));
  const Real tol = precision_tolerance(Real(4));
  // Above the face, below it, beside an edge, beyond a vertex.
  SurfacePoint sp = t.closest_point(Vec3(Real(0.5), Real(0.5), 3));
  test::expect_vec_near(sp.point, Vec3(Real(0.5), Real(0.5), 0), tol);
  test::expect_vec_near(sp.normal, Vec3(0, 0, 1), tol);
  EXPECT_NEAR(sp.signed_distance, Real(3), tol);
  sp = t.closest_point(Vec3(Real(0.5), Real(0.5), -3));
  test::expect_vec_near(sp.normal, Vec3(0, 0, -1), tol);
  EXPECT_NEAR(sp.signed_distance, Real(3), tol);
  sp = t.closest_point(Vec3(Real(1), Real(-2), 0));
  test::expect_vec_near(sp.point, Vec3(1, 0, 0), tol);
  test::expect_vec_near(sp.normal, Vec3(0, -1, 0), tol);
  sp = t.closest_point(Vec3(Real(5), Real(-1), 0));
  test::expect_vec_near(sp.point, Vec3(2, 0, 0), tol);
  // On the face, on an edge, at a vertex: distance 0 and the face normal.
  for (const Vec3& q : {Vec3(Real(0.5), Real(0.5), 0), Vec3(1, 1, 0), Vec3(1, 0, 0), Vec3(0), Vec3(0, 2, 0)}) {
    sp = t.closest_point(q);
    EXPECT_EQ(sp.signed_distance, Real(0));
    test::expect_vec_near(sp.normal, Vec3(0, 0, 1), tol);
    test::expect_vec_near(sp.point, q, tol);
  }
  // Within the tolerance below the face: the normal turns to the query's side.
  sp = t.closest_point(Vec3(Real(0.5), Real(0.5), -t.tolerance() * Real(0.5)));
  test::expect_vec_near(sp.normal, Vec3(0, 0, -1), tol);
  const Real tiny = std::numeric_limits<Real>::denorm_min();
  sp = t.closest_point(Vec3(Real(0.5), Real(0.5), tiny));
  EXPECT_TRUE(test::all_finite(sp.normal));
}

TEST(Triangle, RaycastMatchesReference) {
  test::Random rng(706);
  int hits = 0;
  int misses = 0;
  for (const Real s : test::scales()) {
    for (int k = 0; k < 20; ++k) {
      const Triangle t = random_triangle(rng, s);
      for (int i = 0; i < 150; ++i) {
        const Vec3 o = rng.vec3(Real(-3) * s, Real(3) * s);
        Vec3 dir = rng.unit_vector();
        if (i % 2 == 0) {
          // Aim at a point of the triangle's plane near it (barycentric in [-0.2, 1.2]).
          const Real u = rng.uniform(Real(-0.2), Real(1));
          const Real v = rng.uniform(Real(-0.2), Real(1.2) - u);
          const Vec3 target = t.a() + u * (t.b() - t.a()) + v * (t.c() - t.a());
          if (glm::length(target - o) > Real(0)) dir = glm::normalize(target - o);
        }
        const Real speed = rng.uniform(Real(0.5), Real(2));
        const Ray ray{o, dir * speed};
        const Real max_t = rng.uniform(Real(0), Real(8) * s / speed);
        const auto ref = reference_raycast(ray, max_t, t);
        if (ref && (ref->edge_margin < 1e-4 || ref->cos < 1e-3)) continue;  // ambiguous, near an edge
        if (ref && ref->t >= 0.0 && std::abs(ref->t - max_t) * speed < 1e-4 * s) continue;
        const auto hit = t.raycast(ray, max_t);
        if (ref && ref->t >= 0.0) {
          ++hits;
          ASSERT_TRUE(hit) << "scale " << s << " case " << i;
          const Real tol = precision_tolerance(Real(8) * s, Real(64)) / static_cast<Real>(ref->cos);
          EXPECT_NEAR(hit->t, ref->t, tol / speed);
          test::expect_vec_near(hit->point, ray.at(hit->t), precision_tolerance(Real(8) * s));
          EXPECT_NEAR(std::abs(glm::dot(hit->normal, t.normal())), Real(1), precision_tolerance(Real(1), Real(16)));
          EXPECT_LT(glm::dot(hit->normal, dir), Real(0));  // faces the ray
        } else {
          ++misses;
          EXPECT_FALSE(hit) << "scale " << s << " case " << i;
        }
      }
    }
  }
  EXPECT_GT(hits, 1000);
  EXPECT_GT(misses, 1000);
}

TEST(Triangle, RaycastDegenerateCases) {
  const Triangle t = make(Vec3(0), Vec3(2, 0, 0), Vec3(0, 2, 0));
  const Real tol = precision_tolerance(Real(8), Real(16));
  // From either side: the normal faces the ray.
  auto hit = t.raycast(Ray{Vec3(Real(0.5), Real(0.5), 4), Vec3(0, 0, -2)}, Real(10));
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->t, Real(2), tol);
  test::expect_vec_near(hit->normal, Vec3(0, 0, 1), tol);
  hit = t.raycast(Ray{Vec3(Real(0.5), Real(0.5), -4), Vec3(0, 0, 1)}, Real(10));
  ASSERT_TRUE(hit);
  test::expect_vec_near(hit->normal, Vec3(0, 0, -1), tol);
  // In the plane, zero direction, away, too short: defined answers, never NaN.
  (void)t.raycast(Ray{Vec3(-1, Real(0.5), 0), Vec3(1, 0, 0)}, Real(10));
  (void)t.raycast(Ray{Vec3(Real(0.5), Real(0.5), 0), Vec3(0)}, Real(10));
  EXPECT_FALSE(t.raycast(Ray{Vec3(Real(0.5), Real(0.5), 1), Vec3(0)}, Real(10)));
  EXPECT_FALSE(t.raycast(Ray{Vec3(Real(0.5), Real(0.5), 4), Vec3(0, 0, 1)}, Real(10)));
  EXPECT_FALSE(t.raycast(Ray{Vec3(Real(0.5), Real(0.5), 4), Vec3(0, 0, -1)}, Real(3.9)));
  // Unbounded max_t.
  hit = t.raycast(Ray{Vec3(Real(0.5), Real(0.5), 4), Vec3(0, 0, -1)}, std::numeric_limits<Real>::max());
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->t, Real(4), tol);
}

TEST(Triangle, FarFromOrigin) {
  const Vec3 c(Real(1e4), Real(1e4), Real(-1e4));
  const Triangle t = make(c, c + Vec3(2, 0, 0), c + Vec3(0, 2, 0));
  const Real tol = precision_tolerance(Real(4e4), Real(16));
  test::expect_vec_near(t.normal(), Vec3(0, 0, 1), tol);
  EXPECT_TRUE(t.contains(c + Vec3(Real(0.5), Real(0.5), 0)));
  EXPECT_FALSE(t.contains(c + Vec3(Real(0.5), Real(0.5), 1)));
  const SurfacePoint sp = t.closest_point(c + Vec3(Real(0.5), Real(0.5), 3));
  EXPECT_NEAR(sp.signed_distance, Real(3), tol);
  const auto hit = t.raycast(Ray{c + Vec3(Real(0.5), Real(0.5), 5), Vec3(0, 0, -1)}, Real(10));
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->t, Real(5), tol);
  const Aabb box = t.world_aabb(Transform{Vec3(Real(-1e4)), kIdentityQuat});
  test::expect_vec_near(box.max, Vec3(2, 2, Real(-2e4)), tol);
}

TEST(Triangle, MassPropertiesAreZeroAtTheCentroid) {
  const Triangle t = make(Vec3(0), Vec3(3, 0, 0), Vec3(0, 6, 3));
  const MassProperties m = t.mass_properties(Real(2));
  EXPECT_EQ(m.volume, Real(0));
  EXPECT_EQ(m.mass, Real(0));
  test::expect_vec_near(m.centroid, Vec3(1, 2, 1), precision_tolerance(Real(4)));
  EXPECT_EQ(m.inertia, Mat3(Real(0)));
}

TEST(Triangle, PlacedQueries) {
  test::Random rng(707);
  const Triangle t = make(Vec3(-1, 0, 0), Vec3(2, 0, 0), Vec3(0, 1, 1));
  for (int i = 0; i < 200; ++i) {
    const Transform pose = rng.pose(Real(20));
    const Vec3 local_q = rng.vec3(Real(-3), Real(3));
    const SurfacePoint w = closest_point(t, pose, pose.apply(local_q));
    const SurfacePoint l = t.closest_point(local_q);
    const Real tol = precision_tolerance(Real(40), Real(16));
    EXPECT_NEAR(w.signed_distance, l.signed_distance, tol);
    test::expect_vec_near(w.point, pose.apply(l.point), tol);
    const Vec3 d = rng.unit_vector();
    Real best = -kRealMax;
    for (int k = 0; k < 3; ++k) best = std::max(best, glm::dot(pose.apply(t.vertex(k)), d));
    EXPECT_NEAR(glm::dot(support(t, pose, d), d), best, tol);
  }
}

TEST(Triangle, NonFiniteQueryInputHasDefinedAnswers) {
  test::exercise_queries_with_non_finite_input(make(Vec3(-1, 0, 0), Vec3(2, 0, 0), Vec3(0, 1, 1)));
}

}  // namespace test_triangle
}  // namespace proxima
