// Segment-triangle closest points.
//
// References: analytic answers; for random sweeps a long double golden-section search over
// the segment parameter of a long double point-triangle distance that solves the Gram
// normal equations for the plane projection and falls back to the three edges (a method
// unrelated to the library's Voronoi regions and crossing tests); for a smaller sweep a
// nested golden-section search over the segment and the triangle parameters.
#include <gtest/gtest.h>

#include <proxima/core/tolerance.hpp>
#include <proxima/geometry/closest_points.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

#include "geometry/long_double_reference.hpp"
#include "support/random.hpp"

namespace proxima::geometry {
namespace test_segment_triangle {

using test::LD, test::LVec, test::ld, test::dist2, test::tol_at, test::max_abs, test::golden_min,
    test::ref_dist2_point_segment, test::ref_dist2_point_triangle;

LD ref_distance(const Vec3& p, const Vec3& q, const Vec3& a, const Vec3& b, const Vec3& c) {
  const LVec lp = ld(p), d = ld(q) - ld(p), la = ld(a), lb = ld(b), lc = ld(c);
  return std::sqrt(golden_min([&](LD s) { return ref_dist2_point_triangle(lp + s * d, la, lb, lc); }, 0, 1, 110));
}

// Segment parameter s, triangle a + u ab + v ac with u searched and v exact.
LD ref_distance_nested(const Vec3& p, const Vec3& q, const Vec3& a, const Vec3& b, const Vec3& c) {
  const LVec lp = ld(p), d = ld(q) - ld(p), la = ld(a), ab = ld(b) - ld(a), ac = ld(c) - ld(a);
  auto over_triangle = [&](LD s) {
    const LVec x = lp + s * d;
    return golden_min(
        [&](LD u) {
          const LVec s0 = la + u * ab;
          return ref_dist2_point_segment(x, s0, s0 + (LD(1) - u) * ac);
        },
        0, 1, 80);
  };
  return std::sqrt(golden_min(over_triangle, 0, 1, 80));
}

// Checks one answer: witnesses on their primitives, distance_squared matching them, not
// above the reference. Returns (got - ref) / tol.
LD check(const Vec3& p, const Vec3& q, const Vec3& a, const Vec3& b, const Vec3& c, LD ref, const char* what, int i) {
  const ClosestPair r = closest_points_segment_triangle(p, q, a, b, c);
  const Real tol = tol_at(max_abs({p, q, a, b, c}));
  EXPECT_LE(std::sqrt(ref_dist2_point_segment(ld(r.on_a), ld(p), ld(q))), tol) << what << i;
  EXPECT_LE(std::sqrt(ref_dist2_point_triangle(ld(r.on_b), ld(a), ld(b), ld(c))), tol) << what << i;
  const LD got = std::sqrt(dist2(ld(r.on_a), ld(r.on_b)));
  EXPECT_NEAR(std::sqrt(r.distance_squared), Real(got), tol) << what << i;
  EXPECT_LE(got, ref + tol) << what << i;
  return (got - ref) / tol;
}

void expect_vec_near(const Vec3& a, const Vec3& b, Real tol) {
  EXPECT_NEAR(a.x, b.x, tol);
  EXPECT_NEAR(a.y, b.y, tol);
  EXPECT_NEAR(a.z, b.z, tol);
}

const Vec3 kA(0, 0, 0);
const Vec3 kB(4, 0, 0);
const Vec3 kC(0, 4, 0);

// ---------------------------------------------------------------- named cases

TEST(SegmentTriangle, CrossesTheFace) {
  const ClosestPair r = closest_points_segment_triangle(Vec3(1, 1, -2), Vec3(1, 1, 3), kA, kB, kC);
  EXPECT_EQ(r.distance_squared, Real(0));
  expect_vec_near(r.on_a, Vec3(1, 1, 0), tol_at(4));
  EXPECT_EQ(r.on_a, r.on_b);
}

TEST(SegmentTriangle, ObliqueCrossing) {
  const ClosestPair r = closest_points_segment_triangle(Vec3(0, 0, -1), Vec3(2, 2, 1), kA, kB, kC);
  EXPECT_EQ(r.distance_squared, Real(0));
  expect_vec_near(r.on_a, Vec3(1, 1, 0), tol_at(4));
}

TEST(SegmentTriangle, EndpointOnTheFace) {
  const ClosestPair r = closest_points_segment_triangle(Vec3(1, 2, 0), Vec3(3, 5, 7), kA, kB, kC);
  EXPECT_LE(r.distance_squared, tol_at(4) * tol_at(4));
  expect_vec_near(r.on_a, Vec3(1, 2, 0), tol_at(4));
  expect_vec_near(r.on_b, Vec3(1, 2, 0), tol_at(4));
}

TEST(SegmentTriangle, ThroughAnEdge) {
  const ClosestPair r = closest_points_segment_triangle(Vec3(2, 0, -1), Vec3(2, 0, 1), kA, kB, kC);
  EXPECT_LE(r.distance_squared, tol_at(4) * tol_at(4));
  expect_vec_near(r.on_b, Vec3(2, 0, 0), tol_at(4));
}

TEST(SegmentTriangle, ThroughAVertex) {
  const ClosestPair r = closest_points_segment_triangle(Vec3(-1, -1, -1), Vec3(1, 1, 1), kA, kB, kC);
  EXPECT_LE(r.distance_squared, tol_at(4) * tol_at(4));
  expect_vec_near(r.on_b, kA, tol_at(4));
}

TEST(SegmentTriangle, InThePlaneCrossingTheTriangle) {
  const ClosestPair r = closest_points_segment_triangle(Vec3(-1, 1, 0), Vec3(5, 1, 0), kA, kB, kC);
  EXPECT_LE(r.distance_squared, tol_at(5) * tol_at(5));
}

TEST(SegmentTriangle, InThePlaneInsideTheTriangle) {
  const ClosestPair r = closest_points_segment_triangle(Vec3(0.5, 0.5, 0), Vec3(1, 2, 0), kA, kB, kC);
  EXPECT_LE(r.distance_squared, tol_at(4) * tol_at(4));
}

TEST(SegmentTriangle, InThePlaneOutside) {
  const ClosestPair r = closest_points_segment_triangle(Vec3(3, 3, 0), Vec3(5, 3, 0), kA, kB, kC);
  EXPECT_NEAR(std::sqrt(r.distance_squared), Real(std::sqrt(2.0)), tol_at(5));
  expect_vec_near(r.on_a, Vec3(3, 3, 0), tol_at(5));
  expect_vec_near(r.on_b, Vec3(2, 2, 0), tol_at(5));
}

TEST(SegmentTriangle, ParallelAboveTheFace) {
  const ClosestPair r = closest_points_segment_triangle(Vec3(0.5, 0.5, 2), Vec3(1.5, 1, 2), kA, kB, kC);
  EXPECT_NEAR(r.distance_squared, Real(4), tol_at(4));
  EXPECT_NEAR(r.on_b.z, Real(0), tol_at(4));
  EXPECT_NEAR(r.on_a.z, Real(2), tol_at(4));
}

TEST(SegmentTriangle, ParallelPassingOverAnEdge) {
  // Segment at height 1, parallel to the plane, from outside across the edge bc.
  const ClosestPair r = closest_points_segment_triangle(Vec3(5, 5, 1), Vec3(1, 1, 1), kA, kB, kC);
  EXPECT_NEAR(r.distance_squared, Real(1), tol_at(5));
}

TEST(SegmentTriangle, SkewAboveAnEdge) {
  // Segment along y at x = 2, z = -1, ending before the edge ab (y = 0): its end (2, -1, -1)
  // is nearest to the edge point (2, 0, 0).
  const ClosestPair r = closest_points_segment_triangle(Vec3(2, -3, -1), Vec3(2, -1, -1), kA, kB, kC);
  expect_vec_near(r.on_b, Vec3(2, 0, 0), tol_at(4));
  expect_vec_near(r.on_a, Vec3(2, -1, -1), tol_at(4));
  EXPECT_NEAR(r.distance_squared, Real(2), tol_at(4));
}

TEST(SegmentTriangle, EndpointAboveTheFace) {
  const ClosestPair r = closest_points_segment_triangle(Vec3(1, 1, 1), Vec3(1, 2, 5), kA, kB, kC);
  EXPECT_EQ(r.on_a, Vec3(1, 1, 1));
  expect_vec_near(r.on_b, Vec3(1, 1, 0), tol_at(5));
  EXPECT_NEAR(r.distance_squared, Real(1), tol_at(5));
}

TEST(SegmentTriangle, ZeroLengthSegment) {
  const ClosestPair r = closest_points_segment_triangle(Vec3(1, 1, 3), Vec3(1, 1, 3), kA, kB, kC);
  EXPECT_EQ(r.on_a, Vec3(1, 1, 3));
  expect_vec_near(r.on_b, Vec3(1, 1, 0), tol_at(4));
  EXPECT_NEAR(r.distance_squared, Real(9), tol_at(9));
}

TEST(SegmentTriangle, ZeroLengthSegmentOnTheFace) {
  const ClosestPair r = closest_points_segment_triangle(Vec3(1, 1, 0), Vec3(1, 1, 0), kA, kB, kC);
  EXPECT_LE(r.distance_squared, tol_at(4) * tol_at(4));
}

TEST(SegmentTriangle, CollinearTriangle) {
  // The "triangle" is the segment from (0,0,0) to (4,0,0).
  const ClosestPair r =
      closest_points_segment_triangle(Vec3(1, -1, 1), Vec3(1, 1, 1), Vec3(0, 0, 0), Vec3(4, 0, 0), Vec3(2, 0, 0));
  expect_vec_near(r.on_b, Vec3(1, 0, 0), tol_at(4));
  EXPECT_NEAR(r.distance_squared, Real(1), tol_at(4));
}

TEST(SegmentTriangle, CollinearTriangleCrossed) {
  const ClosestPair r =
      closest_points_segment_triangle(Vec3(1, -1, 0), Vec3(1, 1, 0), Vec3(0, 0, 0), Vec3(4, 0, 0), Vec3(2, 0, 0));
  EXPECT_LE(r.distance_squared, tol_at(4) * tol_at(4));
  expect_vec_near(r.on_b, Vec3(1, 0, 0), tol_at(4));
}

TEST(SegmentTriangle, PointTriangle) {
  const Vec3 v(1, 2, 3);
  const ClosestPair r = closest_points_segment_triangle(Vec3(0, 0, 0), Vec3(2, 4, 0), v, v, v);
  EXPECT_EQ(r.on_b, v);
  EXPECT_NEAR(r.distance_squared, Real(9), tol_at(9));
}

TEST(SegmentTriangle, FarFromOrigin) {
  const Vec3 o(1e4, 1e4, -1e4);
  const ClosestPair r = closest_points_segment_triangle(o + Vec3(1, 1, -2), o + Vec3(1, 1, 3), o + kA, o + kB, o + kC);
  EXPECT_EQ(r.distance_squared, Real(0));
  expect_vec_near(r.on_a, o + Vec3(1, 1, 0), tol_at(1e4));
  const ClosestPair above =
      closest_points_segment_triangle(o + Vec3(1, 1, 2), o + Vec3(1, 2, 3), o + kA, o + kB, o + kC);
  EXPECT_NEAR(std::sqrt(above.distance_squared), Real(2), tol_at(1e4));
}

TEST(SegmentTriangle, TinyScale) {
  const Real s = Real(1e-4);
  const ClosestPair r = closest_points_segment_triangle(s * Vec3(1, 1, 2), s * Vec3(1, 2, 3), s * kA, s * kB, s * kC);
  EXPECT_NEAR(std::sqrt(r.distance_squared), Real(2) * s, tol_at(4 * s));
}

TEST(SegmentTriangle, HugeCoordinatesStayFinite) {
  const Real s = Real(1e30);
  const ClosestPair r = closest_points_segment_triangle(s * Vec3(1, 1, 2), s * Vec3(1, 2, 3), s * kA, s * kB, s * kC);
  EXPECT_TRUE(is_finite(r.on_a));
  EXPECT_TRUE(is_finite(r.on_b));
  EXPECT_FALSE(std::isnan(r.distance_squared));
  EXPECT_NEAR(r.on_b.z / s, Real(0), Real(1e-5));
  EXPECT_NEAR(r.on_a.z / s, Real(2), Real(1e-5));
}

// ---------------------------------------------------------------- sweeps

TEST(SegmentTriangle, RandomGeneralPosition) {
  test::Random rng(301);
  const Real scales[] = {Real(1), Real(1e-4), Real(1e4)};
  LD worst = -1;
  for (int i = 0; i < 3000; ++i) {
    const Real s = scales[i % 3];
    const Vec3 o = (i % 4 == 0) ? Vec3(Real(-1e4), Real(1e4), Real(1e4)) : Vec3(Real(0));
    const Vec3 a = o + s * rng.vec3(-1, 1), b = o + s * rng.vec3(-1, 1), c = o + s * rng.vec3(-1, 1);
    const Vec3 p = o + s * rng.vec3(-1.5, 1.5), q = o + s * rng.vec3(-1.5, 1.5);
    worst = std::max(worst, check(p, q, a, b, c, ref_distance(p, q, a, b, c), "general ", i));
  }
  EXPECT_LE(worst, LD(1));
}

TEST(SegmentTriangle, RandomAgainstNestedGoldenSearch) {
  test::Random rng(302);
  for (int i = 0; i < 200; ++i) {
    const Vec3 a = rng.vec3(-1, 1), b = rng.vec3(-1, 1), c = rng.vec3(-1, 1);
    const Vec3 p = rng.vec3(-1.5, 1.5), q = rng.vec3(-1.5, 1.5);
    const LD ref = ref_distance_nested(p, q, a, b, c);
    const ClosestPair r = closest_points_segment_triangle(p, q, a, b, c);
    EXPECT_LE(std::sqrt(r.distance_squared), ref + std::max(LD(tol_at(2)), LD(1e-12))) << i;
  }
}

// Segments through a random point of the triangle: distance 0, the common point on both.
TEST(SegmentTriangle, RandomCrossingAndTouching) {
  test::Random rng(303);
  for (int i = 0; i < 3000; ++i) {
    const Real s = (i % 3 == 0) ? Real(1e-4) : Real(1);
    const Vec3 a = s * rng.vec3(-1, 1), b = s * rng.vec3(-1, 1), c = s * rng.vec3(-1, 1);
    Real u = rng.uniform(0, 1), v = rng.uniform(0, 1);
    if (u + v > 1) {
      u = 1 - u;
      v = 1 - v;
    }
    const int kind = i % 4;
    if (kind == 2) v = 0;  // through an edge
    const Vec3 x = a + u * (b - a) + v * (c - a);
    Vec3 dir = s * rng.unit_vector();
    if (kind == 3) {
      // grazing: nearly in the plane
      const Vec3 n = glm::normalize(glm::cross(b - a, c - a));
      dir = s * glm::normalize(dir - glm::dot(dir, n) * n + Real(1e-3) * n);
    }
    const Vec3 p = kind == 1 ? x : x - rng.uniform(Real(0.1), 1) * dir;  // kind 1: touching at p
    const Vec3 q = x + rng.uniform(Real(0.1), 1) * dir;
    const Real tol = tol_at(max_abs({p, q, a, b, c}));
    const ClosestPair r = closest_points_segment_triangle(p, q, a, b, c);
    EXPECT_LE(std::sqrt(r.distance_squared), Real(8) * tol) << i;
    check(p, q, a, b, c, 0, "crossing ", i);
  }
}

TEST(SegmentTriangle, RandomParallelAndCoplanar) {
  test::Random rng(304);
  for (int i = 0; i < 2000; ++i) {
    const Vec3 a = rng.vec3(-1, 1), b = rng.vec3(-1, 1), c = rng.vec3(-1, 1);
    const Vec3 n = glm::normalize(glm::cross(b - a, c - a));
    // a segment in a plane parallel to the triangle at height h (0: coplanar)
    const Real h = (i % 3 == 0) ? Real(0) : rng.uniform(-1, 1);
    // One draw per statement: the weight of (c - a) first.
    auto in_plane = [&] {
      const Real v = rng.uniform(-1, 2);
      const Real u = rng.uniform(-1, 2);
      return a + u * (b - a) + v * (c - a);
    };
    const Vec3 p0 = in_plane();
    const Vec3 p1 = in_plane();
    const Vec3 p = p0 + h * n, q = p1 + h * n;
    check(p, q, a, b, c, ref_distance(p, q, a, b, c), "parallel ", i);
  }
}

TEST(SegmentTriangle, RandomDegenerate) {
  test::Random rng(305);
  for (int i = 0; i < 2000; ++i) {
    const Vec3 a = rng.vec3(-1, 1);
    const Vec3 b = rng.vec3(-1, 1);
    Vec3 c;
    switch (i % 4) {
      case 0: c = a + rng.uniform(-1, 2) * (b - a); break;  // collinear
      case 1: c = b; break;                                 // two coincide
      case 2: {                                             // sliver
        const Vec3 off = rng.unit_vector();
        c = a + rng.uniform(0, 1) * (b - a) + Real(1e-4) * off;
        break;
      }
      default: c = rng.vec3(-1, 1); break;
    }
    const Vec3 p = rng.vec3(-1.5, 1.5);
    const Vec3 q = (i % 5 == 0) ? p : rng.vec3(-1.5, 1.5);
    check(p, q, a, b, c, ref_distance(p, q, a, b, c), "degenerate ", i);
  }
}

}  // namespace test_segment_triangle
}  // namespace proxima::geometry
