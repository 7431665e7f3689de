// Segment-segment and line-line closest points.
//
// References: analytic answers; for random sweeps a long double golden-section search over
// the first segment's parameter of the exact distance to the second segment (the distance
// to a segment is convex along a segment), and for a smaller sweep a fully nested
// golden-section search over both parameters. Sweeps cover general position, nearly
// parallel (angles down to 1e-7 rad), exactly parallel, collinear, intersecting and
// zero-length segments, at scales 1e-4, 1 and 1e4 and 1e4 away from the origin.
#include <gtest/gtest.h>

#include <proxima/core/tolerance.hpp>
#include <proxima/geometry/closest_points.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

#include "geometry/long_double_reference.hpp"
#include "support/random.hpp"

namespace proxima::geometry {
namespace test_segment_segment {

using test::LD, test::LVec, test::ld, test::dist2, test::tol_at, test::max_abs, test::golden_min,
    test::ref_dist2_point_segment;

// Golden search over s of the exact distance from p0 + s (p1 - p0) to segment q0q1.
LD ref_distance(const Vec3& p0, const Vec3& p1, const Vec3& q0, const Vec3& q1) {
  const LVec a = ld(p0);
  const LVec d = ld(p1) - a;
  const LVec c0 = ld(q0);
  const LVec c1 = ld(q1);
  return std::sqrt(golden_min([&](LD s) { return ref_dist2_point_segment(a + s * d, c0, c1); }, 0, 1, 110));
}

// Nested golden search over both parameters.
LD ref_distance_nested(const Vec3& p0, const Vec3& p1, const Vec3& q0, const Vec3& q1) {
  const LVec a = ld(p0);
  const LVec d = ld(p1) - a;
  const LVec c = ld(q0);
  const LVec e = ld(q1) - c;
  auto inner = [&](LD s) {
    const LVec x = a + s * d;
    return golden_min([&](LD t) { return dist2(x, c + t * e); }, 0, 1, 70);
  };
  return std::sqrt(golden_min(inner, 0, 1, 70));
}

// Distance of x to segment ab in long double.
LD off_segment(const Vec3& x, const Vec3& a, const Vec3& b) {
  return std::sqrt(ref_dist2_point_segment(ld(x), ld(a), ld(b)));
}

// One answer checked: parameters in range, witnesses on their segments at their
// parameters, distance_squared matching them, and distance not above the reference.
LD check(const Vec3& p0, const Vec3& p1, const Vec3& q0, const Vec3& q1, LD ref, const char* what, int i) {
  const SegmentPair r = closest_points_segment_segment(p0, p1, q0, q1);
  const Real tol = tol_at(max_abs({p0, p1, q0, q1}));
  EXPECT_GE(r.s, Real(0)) << what << i;
  EXPECT_LE(r.s, Real(1)) << what << i;
  EXPECT_GE(r.t, Real(0)) << what << i;
  EXPECT_LE(r.t, Real(1)) << what << i;
  EXPECT_LE(std::sqrt(dist2(ld(r.on_a), ld(p0) + LD(r.s) * (ld(p1) - ld(p0)))), tol) << what << i;
  EXPECT_LE(std::sqrt(dist2(ld(r.on_b), ld(q0) + LD(r.t) * (ld(q1) - ld(q0)))), tol) << what << i;
  EXPECT_LE(off_segment(r.on_a, p0, p1), tol) << what << i;
  EXPECT_LE(off_segment(r.on_b, q0, q1), tol) << what << i;
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

// ---------------------------------------------------------------- line-line

TEST(LineLine, SkewLinesAnalytic) {
  // x axis and the line through (0, 0, 2) along y: closest points at the origin and (0,0,2).
  const SegmentPair r = closest_points_line_line(Vec3(5, 0, 0), Vec3(2, 0, 0), Vec3(0, 3, 2), Vec3(0, -1, 0));
  expect_vec_near(r.on_a, Vec3(0, 0, 0), tol_at(5));
  expect_vec_near(r.on_b, Vec3(0, 0, 2), tol_at(5));
  EXPECT_NEAR(r.s, Real(-2.5), tol_at(5));
  EXPECT_NEAR(r.t, Real(3), tol_at(5));
  EXPECT_NEAR(r.distance_squared, Real(4), tol_at(5));
}

TEST(LineLine, ParallelLinesUseSZero) {
  const SegmentPair r = closest_points_line_line(Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 0, 3), Vec3(-2, -2, 0));
  EXPECT_EQ(r.s, Real(0));
  expect_vec_near(r.on_a, Vec3(1, 0, 0), tol_at(3));
  expect_vec_near(r.on_b, Vec3(0.5, 0.5, 3), tol_at(3));
  EXPECT_NEAR(r.distance_squared, Real(9.5), tol_at(10));
}

TEST(LineLine, ZeroDirections) {
  const SegmentPair both = closest_points_line_line(Vec3(1, 2, 3), Vec3(0), Vec3(4, 5, 6), Vec3(0));
  EXPECT_EQ(both.on_a, Vec3(1, 2, 3));
  EXPECT_EQ(both.on_b, Vec3(4, 5, 6));
  const SegmentPair first = closest_points_line_line(Vec3(1, 1, 0), Vec3(0), Vec3(0, 0, 0), Vec3(2, 0, 0));
  EXPECT_EQ(first.s, Real(0));
  EXPECT_NEAR(first.t, Real(0.5), tol_at(2));
  const SegmentPair second = closest_points_line_line(Vec3(0, 0, 0), Vec3(0, 0, 4), Vec3(3, 0, 2), Vec3(0));
  EXPECT_EQ(second.t, Real(0));
  EXPECT_NEAR(second.s, Real(0.5), tol_at(4));
}

TEST(LineLine, RandomSatisfyNormalEquations) {
  test::Random rng(201);
  for (int i = 0; i < 2000; ++i) {
    const Vec3 p0 = rng.vec3(-5, 5);
    const Vec3 d0 = rng.vec3(-2, 2);
    const Vec3 p1 = rng.vec3(-5, 5);
    const Vec3 d1 = rng.vec3(-2, 2);
    const SegmentPair r = closest_points_line_line(p0, d0, p1, d1);
    // Reference: 2x2 normal equations solved in long double.
    const LVec a = ld(d0);
    const LVec b = ld(d1);
    const LVec w = ld(p0) - ld(p1);
    const LD aa = glm::dot(a, a), ab = glm::dot(a, b), bb = glm::dot(b, b);
    const LD det = aa * bb - ab * ab;
    if (det < LD(1e-6) * aa * bb) continue;  // nearly parallel: closest points ill-defined
    const LD s = (ab * glm::dot(b, w) - bb * glm::dot(a, w)) / det;
    const LD t = (aa * glm::dot(b, w) - ab * glm::dot(a, w)) / det;
    const Real scale = max_abs({p0, p1, d0 * r.s, d1 * r.t});
    const Real tol = Real(1e3) * tol_at(scale);  // well-conditioned lines only
    EXPECT_LE(std::sqrt(dist2(ld(r.on_a), ld(p0) + s * a)), tol) << i;
    EXPECT_LE(std::sqrt(dist2(ld(r.on_b), ld(p1) + t * b)), tol) << i;
  }
}

TEST(LineLine, HugeCoordinatesStayFinite) {
  const Real big = Real(1e30);
  const SegmentPair r =
      closest_points_line_line(Vec3(big, 0, 0), Vec3(1, 0, 0), Vec3(0, big, big), Vec3(0, Real(1e-20), 0));
  EXPECT_TRUE(is_finite(r.on_a));
  EXPECT_TRUE(is_finite(r.on_b));
  EXPECT_TRUE(std::isfinite(r.s));
  EXPECT_TRUE(std::isfinite(r.t));
  EXPECT_NEAR(r.on_a.x / big, Real(0), Real(1e-5));
  EXPECT_NEAR(r.on_b.z / big, Real(1), Real(1e-5));
}

// ---------------------------------------------------------------- segment-segment, named

TEST(SegmentSegment, CrossingSegments) {
  const SegmentPair r = closest_points_segment_segment(Vec3(-1, 0, 0), Vec3(1, 0, 0), Vec3(0, -1, 0), Vec3(0, 1, 0));
  EXPECT_NEAR(r.distance_squared, Real(0), tol_at(1));
  EXPECT_NEAR(r.s, Real(0.5), tol_at(1));
  EXPECT_NEAR(r.t, Real(0.5), tol_at(1));
}

TEST(SegmentSegment, SkewInteriorPair) {
  const SegmentPair r = closest_points_segment_segment(Vec3(-1, 0, 0), Vec3(1, 0, 0), Vec3(0, -1, 1), Vec3(0, 1, 1));
  EXPECT_NEAR(r.distance_squared, Real(1), tol_at(1));
  expect_vec_near(r.on_a, Vec3(0, 0, 0), tol_at(1));
  expect_vec_near(r.on_b, Vec3(0, 0, 1), tol_at(1));
}

TEST(SegmentSegment, EndpointToInterior) {
  // q0 hovers over the middle of p; the lines' closest points lie beyond q's end.
  const SegmentPair r = closest_points_segment_segment(Vec3(0, 0, 0), Vec3(4, 0, 0), Vec3(1, 0, 2), Vec3(1, 3, 5));
  EXPECT_EQ(r.t, Real(0));
  EXPECT_EQ(r.on_b, Vec3(1, 0, 2));
  expect_vec_near(r.on_a, Vec3(1, 0, 0), tol_at(5));
  EXPECT_NEAR(r.distance_squared, Real(4), tol_at(5));
}

TEST(SegmentSegment, EndpointToEndpoint) {
  const SegmentPair r = closest_points_segment_segment(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(2, 1, 0), Vec3(3, 5, 0));
  EXPECT_EQ(r.on_a, Vec3(1, 0, 0));
  EXPECT_EQ(r.on_b, Vec3(2, 1, 0));
  EXPECT_EQ(r.s, Real(1));
  EXPECT_EQ(r.t, Real(0));
  EXPECT_NEAR(r.distance_squared, Real(2), tol_at(5));
}

TEST(SegmentSegment, TouchingAtEndpoint) {
  const SegmentPair r = closest_points_segment_segment(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 1));
  EXPECT_EQ(r.distance_squared, Real(0));
  EXPECT_EQ(r.on_a, Vec3(1, 0, 0));
  EXPECT_EQ(r.on_b, Vec3(1, 0, 0));
}

TEST(SegmentSegment, TShapeTouching) {
  const SegmentPair r =
      closest_points_segment_segment(Vec3(-1, 0, 0), Vec3(1, 0, 0), Vec3(0.25, 0, 0), Vec3(0.25, 2, 0));
  EXPECT_NEAR(r.distance_squared, Real(0), tol_at(2));
  expect_vec_near(r.on_a, Vec3(0.25, 0, 0), tol_at(2));
}

TEST(SegmentSegment, ParallelOverlappingReturnsMidpointOfOverlap) {
  // p covers x in [0, 4], q covers x in [1, 6] one unit above: overlap [1, 4], midpoint 2.5.
  const SegmentPair r = closest_points_segment_segment(Vec3(0, 0, 0), Vec3(4, 0, 0), Vec3(6, 1, 0), Vec3(1, 1, 0));
  EXPECT_NEAR(r.distance_squared, Real(1), tol_at(6));
  expect_vec_near(r.on_a, Vec3(2.5, 0, 0), tol_at(6));
  expect_vec_near(r.on_b, Vec3(2.5, 1, 0), tol_at(6));
  EXPECT_NEAR(r.s, Real(0.625), tol_at(1));
  EXPECT_NEAR(r.t, Real(0.7), tol_at(1));
}

TEST(SegmentSegment, ParallelContainedReturnsMidpointOfInner) {
  const SegmentPair r = closest_points_segment_segment(Vec3(1, 0, 0), Vec3(2, 0, 0), Vec3(0, 0, 3), Vec3(10, 0, 3));
  expect_vec_near(r.on_a, Vec3(1.5, 0, 0), tol_at(10));
  expect_vec_near(r.on_b, Vec3(1.5, 0, 3), tol_at(10));
}

TEST(SegmentSegment, ParallelDisjointUsesNearestEnds) {
  const SegmentPair r = closest_points_segment_segment(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(3, 2, 0), Vec3(5, 2, 0));
  EXPECT_EQ(r.on_a, Vec3(1, 0, 0));
  EXPECT_EQ(r.on_b, Vec3(3, 2, 0));
  EXPECT_NEAR(r.distance_squared, Real(8), tol_at(8));
}

TEST(SegmentSegment, CollinearOverlapping) {
  const SegmentPair r = closest_points_segment_segment(Vec3(0, 0, 0), Vec3(2, 2, 2), Vec3(1, 1, 1), Vec3(5, 5, 5));
  EXPECT_NEAR(r.distance_squared, Real(0), tol_at(5));
  expect_vec_near(r.on_a, Vec3(1.5, 1.5, 1.5), tol_at(5));
}

TEST(SegmentSegment, CollinearDisjoint) {
  const SegmentPair r = closest_points_segment_segment(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(3, 0, 0), Vec3(2, 0, 0));
  EXPECT_EQ(r.on_a, Vec3(1, 0, 0));
  EXPECT_EQ(r.on_b, Vec3(2, 0, 0));
  EXPECT_EQ(r.t, Real(1));
}

TEST(SegmentSegment, AntiParallelOverlapping) {
  const SegmentPair r = closest_points_segment_segment(Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(3, 0, 1), Vec3(1, 0, 1));
  EXPECT_NEAR(r.distance_squared, Real(1), tol_at(3));
  expect_vec_near(r.on_a, Vec3(1.5, 0, 0), tol_at(3));
}

TEST(SegmentSegment, FirstZeroLength) {
  const SegmentPair r = closest_points_segment_segment(Vec3(1, 1, 0), Vec3(1, 1, 0), Vec3(0, 0, 0), Vec3(4, 0, 0));
  EXPECT_EQ(r.s, Real(0));
  EXPECT_EQ(r.on_a, Vec3(1, 1, 0));
  expect_vec_near(r.on_b, Vec3(1, 0, 0), tol_at(4));
  EXPECT_NEAR(r.t, Real(0.25), tol_at(1));
}

TEST(SegmentSegment, SecondZeroLength) {
  const SegmentPair r = closest_points_segment_segment(Vec3(0, 0, 0), Vec3(0, 4, 0), Vec3(2, 3, 0), Vec3(2, 3, 0));
  EXPECT_EQ(r.t, Real(0));
  EXPECT_EQ(r.on_b, Vec3(2, 3, 0));
  expect_vec_near(r.on_a, Vec3(0, 3, 0), tol_at(4));
}

TEST(SegmentSegment, BothZeroLength) {
  const SegmentPair r = closest_points_segment_segment(Vec3(1, 2, 3), Vec3(1, 2, 3), Vec3(4, 6, 3), Vec3(4, 6, 3));
  EXPECT_EQ(r.on_a, Vec3(1, 2, 3));
  EXPECT_EQ(r.on_b, Vec3(4, 6, 3));
  EXPECT_NEAR(r.distance_squared, Real(25), tol_at(25));
}

TEST(SegmentSegment, IdenticalSegments) {
  const Vec3 a(1, -2, 3);
  const Vec3 b(4, 0, -1);
  const SegmentPair r = closest_points_segment_segment(a, b, a, b);
  EXPECT_NEAR(r.distance_squared, Real(0), tol_at(4));
  expect_vec_near(r.on_a, (a + b) * Real(0.5), tol_at(4));
}

TEST(SegmentSegment, NearlyParallelCrossingNearAnEnd) {
  // Angle 1e-5: the lines cross at x = 9.9 (inside both).
  const Real k = Real(1e-5);
  const Vec3 p0(0, 0, 0), p1(10, 0, 0);
  const Vec3 q0(0, Real(-9.9) * k, 0), q1(10, Real(0.1) * k, 0);
  const SegmentPair r = closest_points_segment_segment(p0, p1, q0, q1);
  EXPECT_LE(std::sqrt(r.distance_squared), tol_at(10));
  EXPECT_LE(off_segment(r.on_a, p0, p1), tol_at(10));
  EXPECT_LE(off_segment(r.on_b, q0, q1), tol_at(10));
}

TEST(SegmentSegment, FarFromOrigin) {
  const Vec3 o(1e4, -1e4, 1e4);
  const SegmentPair r =
      closest_points_segment_segment(o + Vec3(-1, 0, 0), o + Vec3(1, 0, 0), o + Vec3(0, -1, 1), o + Vec3(0, 1, 1));
  EXPECT_NEAR(std::sqrt(r.distance_squared), Real(1), tol_at(1e4));
  expect_vec_near(r.on_a, o, tol_at(1e4));
}

TEST(SegmentSegment, TinyScale) {
  const Real s = Real(1e-4);
  const SegmentPair r = closest_points_segment_segment(Vec3(-s, 0, 0), Vec3(s, 0, 0), Vec3(0, -s, s), Vec3(0, s, s));
  EXPECT_NEAR(std::sqrt(r.distance_squared), s, tol_at(s));
}

TEST(SegmentSegment, HugeCoordinatesStayFinite) {
  const Real big = std::numeric_limits<Real>::max() / Real(16);
  const SegmentPair r =
      closest_points_segment_segment(Vec3(-big, 0, 0), Vec3(big, 0, 0), Vec3(0, -big, big), Vec3(0, big, big));
  EXPECT_TRUE(is_finite(r.on_a));
  EXPECT_TRUE(is_finite(r.on_b));
  EXPECT_NEAR(r.s, Real(0.5), Real(1e-5));
  EXPECT_NEAR(r.t, Real(0.5), Real(1e-5));
  EXPECT_FALSE(std::isnan(r.distance_squared));
}

TEST(SegmentSegment, SymmetricUnderSwap) {
  test::Random rng(202);
  for (int i = 0; i < 1000; ++i) {
    const Vec3 p0 = rng.vec3(-1, 1), p1 = rng.vec3(-1, 1), q0 = rng.vec3(-1, 1), q1 = rng.vec3(-1, 1);
    const SegmentPair ab = closest_points_segment_segment(p0, p1, q0, q1);
    const SegmentPair ba = closest_points_segment_segment(q0, q1, p0, p1);
    EXPECT_NEAR(std::sqrt(ab.distance_squared), std::sqrt(ba.distance_squared), tol_at(1)) << i;
  }
}

// ---------------------------------------------------------------- segment-segment, sweeps

TEST(SegmentSegment, RandomGeneralPositionAgainstGoldenSearch) {
  test::Random rng(203);
  const Real scales[] = {Real(1), Real(1e-4), Real(1e4)};
  LD worst = -1;
  for (int i = 0; i < 3000; ++i) {
    const Real s = scales[i % 3];
    const Vec3 o = (i % 4 == 0) ? Vec3(Real(1e4), Real(1e4), Real(-1e4)) : Vec3(Real(0));
    const Vec3 p0 = o + s * rng.vec3(-1, 1), p1 = o + s * rng.vec3(-1, 1);
    const Vec3 q0 = o + s * rng.vec3(-1, 1), q1 = o + s * rng.vec3(-1, 1);
    worst = std::max(worst, check(p0, p1, q0, q1, ref_distance(p0, p1, q0, q1), "general ", i));
  }
  EXPECT_LE(worst, LD(1));
}

TEST(SegmentSegment, RandomAgainstNestedGoldenSearch) {
  test::Random rng(204);
  for (int i = 0; i < 300; ++i) {
    const Vec3 p0 = rng.vec3(-1, 1), p1 = rng.vec3(-1, 1), q0 = rng.vec3(-1, 1), q1 = rng.vec3(-1, 1);
    // The nested search converges to ~1e-14: compare at that accuracy in both precisions.
    const LD ref = ref_distance_nested(p0, p1, q0, q1);
    const SegmentPair r = closest_points_segment_segment(p0, p1, q0, q1);
    EXPECT_LE(std::sqrt(r.distance_squared), ref + std::max(LD(tol_at(1)), LD(1e-12))) << i;
  }
}

TEST(SegmentSegment, RandomNearlyParallel) {
  test::Random rng(205);
  LD worst = -1;
  for (int i = 0; i < 3000; ++i) {
    const Real s = (i % 3 == 0) ? Real(1e-4) : (i % 3 == 1) ? Real(1) : Real(1e4);
    const Vec3 p0 = s * rng.vec3(-1, 1);
    const Vec3 dir = s * rng.vec3(-1, 1);
    const Vec3 p1 = p0 + dir;
    // q: the same direction tilted by 10^-k, possibly reversed and rescaled, offset a
    // little (often less than the tilt can cover, so that the segments cross).
    const Real tilt = std::pow(Real(10), -Real(rng.integer(1, 7)));
    const Vec3 lean = rng.unit_vector();
    const Real sign = rng.uniform(0, 1) < Real(0.5) ? Real(-1) : Real(1);
    const Real stretch = rng.uniform(Real(0.2), Real(2));
    const Vec3 qdir = sign * stretch * (dir + tilt * glm::length(dir) * lean);
    const Real wobble_scale = rng.uniform(0, 2);
    const Vec3 wobble = rng.in_ball(1);
    const Vec3 q0 = p0 + rng.uniform(Real(-1), Real(1)) * dir + tilt * s * wobble * wobble_scale;
    const Vec3 q1 = q0 + qdir;
    worst = std::max(worst, check(p0, p1, q0, q1, ref_distance(p0, p1, q0, q1), "nearly parallel ", i));
  }
  EXPECT_LE(worst, LD(1));
}

TEST(SegmentSegment, RandomExactlyParallelAndCollinear) {
  test::Random rng(206);
  for (int i = 0; i < 2000; ++i) {
    // Integer coordinates (exact in float): q is p's direction times a small integer,
    // shifted by an integer offset (zero offset across: collinear).
    auto ivec = [&](int lo, int hi) {
      const int z = rng.integer(lo, hi);
      const int y = rng.integer(lo, hi);
      const int x = rng.integer(lo, hi);
      return Vec3(Real(x), Real(y), Real(z));
    };
    const Vec3 p0 = ivec(-50, 50);
    const Vec3 d = ivec(-5, 5);
    const Vec3 p1 = p0 + d;
    const Vec3 shift = (i % 2 == 0) ? Real(rng.integer(-3, 3)) * d : ivec(-3, 3);
    const Vec3 q0 = p0 + shift + Real(rng.integer(-2, 2)) * d;
    const Vec3 q1 = q0 + Real(rng.integer(-3, 3)) * d;
    const LD ref = ref_distance(p0, p1, q0, q1);
    check(p0, p1, q0, q1, ref, "parallel ", i);
    // With a real overlap, the answer is the midpoint of the overlap on the first.
    const SegmentPair r = closest_points_segment_segment(p0, p1, q0, q1);
    const LD a = glm::dot(ld(d), ld(d));
    if (a == 0 || q0 == q1) continue;
    const LD sq0 = glm::dot(ld(q0) - ld(p0), ld(d)) / a;
    const LD sq1 = glm::dot(ld(q1) - ld(p0), ld(d)) / a;
    const LD lo = std::max(LD(0), std::min(sq0, sq1));
    const LD hi = std::min(LD(1), std::max(sq0, sq1));
    if (hi - lo > LD(1e-3)) {
      EXPECT_NEAR(r.s, Real((lo + hi) / 2), Real(1e-4)) << i;
    }
  }
}

TEST(SegmentSegment, RandomIntersectingAndTouching) {
  test::Random rng(207);
  for (int i = 0; i < 2000; ++i) {
    const Vec3 p0 = rng.vec3(-1, 1), p1 = rng.vec3(-1, 1);
    const Vec3 x = p0 + rng.uniform(0, 1) * (p1 - p0);  // a point of p
    const Vec3 dir = rng.vec3(-1, 1);
    const int kind = i % 3;
    // crossing through x, ending at x (touching), or passing x at 1e-3
    const Vec3 q0 = kind == 1 ? x : x - rng.uniform(Real(0.1), 1) * dir;
    const Vec3 off = kind == 2 ? Real(1e-3) * rng.unit_vector() : Vec3(0);
    const Vec3 q1 = x + rng.uniform(Real(0.1), 1) * dir + off;
    check(p0, p1, q0, q1, ref_distance(p0, p1, q0, q1), "intersecting ", i);
  }
}

TEST(SegmentSegment, RandomZeroLength) {
  test::Random rng(208);
  for (int i = 0; i < 1000; ++i) {
    const Vec3 p0 = rng.vec3(-1, 1);
    const Vec3 p1 = (i % 2 == 0) ? p0 : rng.vec3(-1, 1);
    const Vec3 q0 = rng.vec3(-1, 1);
    const Vec3 q1 = (i % 3 == 0) ? q0 : rng.vec3(-1, 1);
    check(p0, p1, q0, q1, ref_distance(p0, p1, q0, q1), "zero-length ", i);
  }
}

}  // namespace test_segment_segment
}  // namespace proxima::geometry
