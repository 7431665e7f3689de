// Point queries of closest_points.hpp: point-point, point-line, point-segment,
// point-triangle, point-AABB, point-OBB.
//
// References: analytic answers for hand-built cases; for random sweeps, long double
// golden-section searches over the primitive's parameters (with an exact inner clamp where
// the inner problem is 1-D) and dense sampling, none of which shares code with the library.
#include <gtest/gtest.h>

#include <proxima/core/tolerance.hpp>
#include <proxima/geometry/closest_points.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

#include "geometry/long_double_reference.hpp"
#include "support/random.hpp"

namespace proxima::geometry {
namespace test_closest_point {

using test::LD, test::LVec, test::ld, test::dist2, test::tol_at, test::max_abs, test::golden_min,
    test::ref_dist2_point_segment;

// Triangle a + u (b - a) + v (c - a), u, v >= 0, u + v <= 1: golden search over u of the
// exact distance to the segment {v in [0, 1 - u]}.
LD ref_dist2_point_triangle(const LVec& p, const LVec& a, const LVec& b, const LVec& c) {
  const LVec ab = b - a;
  const LVec ac = c - a;
  auto g = [&](LD u) {
    const LVec s0 = a + u * ab;
    return ref_dist2_point_segment(p, s0, s0 + (LD(1) - u) * ac);
  };
  return golden_min(g, LD(0), LD(1), 110);
}

void expect_vec_near(const Vec3& a, const Vec3& b, Real tol) {
  EXPECT_NEAR(a.x, b.x, tol);
  EXPECT_NEAR(a.y, b.y, tol);
  EXPECT_NEAR(a.z, b.z, tol);
}

// ---------------------------------------------------------------- point-point, line

TEST(ClosestPoint, PointPointAnalytic) {
  EXPECT_EQ(distance_squared_point_point(Vec3(1, 2, 3), Vec3(1, 2, 3)), Real(0));
  EXPECT_NEAR(distance_squared_point_point(Vec3(0, 0, 0), Vec3(1, 2, 2)), Real(9), tol_at(9));
  EXPECT_NEAR(distance_squared_point_point(Vec3(1e4, 1e4, 1e4), Vec3(1e4 + 3, 1e4, 1e4 + 4)), Real(25),
              Real(25) * Real(1e-2));
}

TEST(ClosestPoint, PointPointHugeAndTinyNeverOverflowToNaN) {
  const Real big = std::numeric_limits<Real>::max() / Real(4);
  const Real d = distance_squared_point_point(Vec3(big, 0, 0), Vec3(-big, 0, 0));
  EXPECT_FALSE(std::isnan(d));
  EXPECT_TRUE(std::isinf(d));     // (big)^2 is beyond the range: reported as infinity
  const Real tiny = Real(1e-15);  // below the rescaling threshold, squares still normal
  const Real dt = distance_squared_point_point(Vec3(tiny, 0, 0), Vec3(0, tiny, 0));
  EXPECT_NEAR(dt / (tiny * tiny), Real(2), Real(1e-5));
}

TEST(ClosestPoint, PointLineAnalytic) {
  const SegmentPoint r = closest_point_line(Vec3(3, 5, 0), Vec3(0, 0, 0), Vec3(2, 0, 0));
  expect_vec_near(r.point, Vec3(3, 0, 0), tol_at(5));
  EXPECT_NEAR(r.t, Real(1.5), tol_at(2));
  const SegmentPoint behind = closest_point_line(Vec3(-4, 1, 1), Vec3(1, 0, 0), Vec3(0, 0, 0.5));
  expect_vec_near(behind.point, Vec3(1, 0, 1), tol_at(5));
  EXPECT_NEAR(behind.t, Real(2), tol_at(5));
}

TEST(ClosestPoint, PointLineZeroDirectionIsTheAnchor) {
  const SegmentPoint r = closest_point_line(Vec3(3, 5, 0), Vec3(1, 2, 3), Vec3(0, 0, 0));
  EXPECT_EQ(r.point, Vec3(1, 2, 3));
  EXPECT_EQ(r.t, Real(0));
}

TEST(ClosestPoint, PointLineTinyDirectionStaysFinite) {
  // |d|^2 underflows in float: the line is still a line, not a point.
  const Vec3 d(Real(1e-25), Real(0), Real(0));
  const SegmentPoint r = closest_point_line(Vec3(7, 1, 0), Vec3(0, 0, 0), d);
  expect_vec_near(r.point, Vec3(7, 0, 0), tol_at(7));
  EXPECT_TRUE(std::isfinite(r.t));
  EXPECT_GT(r.t, Real(0));
}

TEST(ClosestPoint, PointLineRandomMatchesOrthogonality) {
  test::Random rng(101);
  for (int i = 0; i < 2000; ++i) {
    const Vec3 a = rng.vec3(-10, 10);
    const Vec3 d = rng.vec3(-3, 3);
    const Vec3 p = rng.vec3(-10, 10);
    const SegmentPoint r = closest_point_line(p, a, d);
    // Reference: the foot of the perpendicular, computed in long double.
    const LVec dl = ld(d);
    const LD t = glm::dot(ld(p) - ld(a), dl) / glm::dot(dl, dl);
    const LVec foot = ld(a) + t * dl;
    const Real scale = max_abs({a, p, d * r.t});
    EXPECT_LE(std::sqrt(dist2(ld(r.point), foot)), tol_at(scale)) << i;
    EXPECT_NEAR(r.t, Real(t), tol_at(scale) / std::sqrt(length_squared(d))) << i;
  }
}

// ---------------------------------------------------------------- point-segment

TEST(ClosestPoint, PointSegmentRegions) {
  const Vec3 a(1, 1, 1);
  const Vec3 b(3, 1, 1);
  const SegmentPoint before = closest_point_segment(Vec3(0, 5, 1), a, b);
  EXPECT_EQ(before.point, a);
  EXPECT_EQ(before.t, Real(0));
  const SegmentPoint after = closest_point_segment(Vec3(4, -2, 7), a, b);
  EXPECT_EQ(after.point, b);
  EXPECT_EQ(after.t, Real(1));
  const SegmentPoint mid = closest_point_segment(Vec3(2.5, 3, -1), a, b);
  expect_vec_near(mid.point, Vec3(2.5, 1, 1), tol_at(3));
  EXPECT_NEAR(mid.t, Real(0.75), tol_at(1));
  const SegmentPoint on = closest_point_segment(Vec3(2, 1, 1), a, b);
  expect_vec_near(on.point, Vec3(2, 1, 1), tol_at(3));
}

TEST(ClosestPoint, PointSegmentZeroLength) {
  const Vec3 a(2, -1, 4);
  const SegmentPoint r = closest_point_segment(Vec3(5, 5, 5), a, a);
  EXPECT_EQ(r.point, a);
  EXPECT_EQ(r.t, Real(0));
}

TEST(ClosestPoint, PointSegmentHugeCoordinates) {
  const Real big = std::numeric_limits<Real>::max() / Real(8);
  const SegmentPoint r = closest_point_segment(Vec3(0, big, 0), Vec3(-big, 0, 0), Vec3(big, 0, 0));
  EXPECT_TRUE(is_finite(r.point));
  EXPECT_NEAR(r.t, Real(0.5), Real(1e-5));
  EXPECT_LE(std::abs(r.point.x), big * Real(1e-5));
}

// Random segments at several scales and offsets against a golden-section search.
TEST(ClosestPoint, PointSegmentRandomAgainstGoldenSearch) {
  test::Random rng(102);
  const Real scales[] = {Real(1), Real(1e-4), Real(1e4)};
  for (int i = 0; i < 3000; ++i) {
    const Real s = scales[i % 3];
    const Vec3 offset = (i % 7 == 0) ? Vec3(Real(1e4)) : Vec3(Real(0));
    const Vec3 a = offset + s * rng.vec3(-1, 1);
    const Vec3 b = (i % 11 == 0) ? a : offset + s * rng.vec3(-1, 1);
    const Vec3 p = offset + s * rng.vec3(-2, 2);
    const SegmentPoint r = closest_point_segment(p, a, b);
    ASSERT_GE(r.t, Real(0));
    ASSERT_LE(r.t, Real(1));
    const LVec la = ld(a);
    const LVec lb = ld(b);
    const LVec lp = ld(p);
    const LD ref = std::sqrt(golden_min([&](LD t) { return dist2(lp, la + t * (lb - la)); }, 0, 1, 100));
    const Real tol = tol_at(max_abs({a, b, p}));
    const LD got = std::sqrt(dist2(lp, ld(r.point)));
    EXPECT_LE(got, ref + tol) << i;
    EXPECT_GE(got, ref - tol) << i;
    // The point is the point of the segment at parameter t.
    EXPECT_LE(std::sqrt(dist2(ld(r.point), la + LD(r.t) * (lb - la))), tol) << i;
  }
}

// ---------------------------------------------------------------- point-triangle

struct RegionCase {
  Vec3 p;
  Vec3 expected;
  TriangleFeature feature;
};

TEST(ClosestPoint, PointTriangleEveryVoronoiRegion) {
  const Vec3 a(0, 0, 0);
  const Vec3 b(2, 0, 0);
  const Vec3 c(0, 2, 0);
  const RegionCase cases[] = {
      {Vec3(-1, -1, 1), a, TriangleFeature::VertexA},
      {Vec3(3, -1, -2), b, TriangleFeature::VertexB},
      {Vec3(-1, 3, 0.5), c, TriangleFeature::VertexC},
      {Vec3(1, -2, 3), Vec3(1, 0, 0), TriangleFeature::EdgeAB},
      {Vec3(2, 2, 0), Vec3(1, 1, 0), TriangleFeature::EdgeBC},
      {Vec3(-3, 1.5, -1), Vec3(0, 1.5, 0), TriangleFeature::EdgeCA},
      {Vec3(0.5, 0.5, 4), Vec3(0.5, 0.5, 0), TriangleFeature::Face},
      {Vec3(0.5, 0.25, -4), Vec3(0.5, 0.25, 0), TriangleFeature::Face},
  };
  for (const RegionCase& rc : cases) {
    const TrianglePoint r = closest_point_triangle(rc.p, a, b, c);
    expect_vec_near(r.point, rc.expected, tol_at(4));
    EXPECT_EQ(r.feature, rc.feature);
    const Vec3 from_bary = r.barycentric.x * a + r.barycentric.y * b + r.barycentric.z * c;
    expect_vec_near(from_bary, r.point, tol_at(4));
    EXPECT_NEAR(r.barycentric.x + r.barycentric.y + r.barycentric.z, Real(1), tol_at(1));
  }
}

TEST(ClosestPoint, PointTriangleBarycentricOfFacePoint) {
  const Vec3 a(1, 0, 0);
  const Vec3 b(0, 1, 0);
  const Vec3 c(0, 0, 1);
  const TrianglePoint r = closest_point_triangle(Vec3(1, 1, 1), a, b, c);
  EXPECT_EQ(r.feature, TriangleFeature::Face);
  expect_vec_near(r.barycentric, Vec3(Real(1) / 3), tol_at(1));
  expect_vec_near(r.point, Vec3(Real(1) / 3), tol_at(1));
}

TEST(ClosestPoint, PointTriangleCollinearFallsBackToEdges) {
  // c between a and b: the triangle is the segment ab.
  const Vec3 a(0, 0, 0);
  const Vec3 b(4, 0, 0);
  const Vec3 c(1, 0, 0);
  const TrianglePoint r = closest_point_triangle(Vec3(3, 2, 0), a, b, c);
  expect_vec_near(r.point, Vec3(3, 0, 0), tol_at(4));
  EXPECT_TRUE(r.feature == TriangleFeature::EdgeAB || r.feature == TriangleFeature::EdgeBC);
  const TrianglePoint beyond = closest_point_triangle(Vec3(6, 1, 0), a, b, c);
  EXPECT_EQ(beyond.point, b);
  EXPECT_EQ(beyond.feature, TriangleFeature::VertexB);
  EXPECT_EQ(beyond.barycentric, Vec3(0, 1, 0));
}

TEST(ClosestPoint, PointTriangleTwoCoincidentVertices) {
  const Vec3 a(1, 1, 1);
  const Vec3 c(3, 1, 1);
  const TrianglePoint r = closest_point_triangle(Vec3(2, 5, 1), a, a, c);
  expect_vec_near(r.point, Vec3(2, 1, 1), tol_at(5));
  const Vec3 from_bary = r.barycentric.x * a + r.barycentric.y * a + r.barycentric.z * c;
  expect_vec_near(from_bary, r.point, tol_at(5));
}

TEST(ClosestPoint, PointTriangleAllVerticesCoincide) {
  const Vec3 a(-2, 3, 1);
  const TrianglePoint r = closest_point_triangle(Vec3(0, 0, 0), a, a, a);
  EXPECT_EQ(r.point, a);
  EXPECT_EQ(r.feature, TriangleFeature::VertexA);
  EXPECT_EQ(r.barycentric, Vec3(1, 0, 0));
}

TEST(ClosestPoint, PointTrianglePointOnTheTriangle) {
  const Vec3 a(0, 0, 0);
  const Vec3 b(1, 0, 0);
  const Vec3 c(0, 1, 0);
  const Vec3 inside(0.25, 0.25, 0);
  const TrianglePoint r = closest_point_triangle(inside, a, b, c);
  expect_vec_near(r.point, inside, tol_at(1));
  EXPECT_EQ(r.feature, TriangleFeature::Face);
  const TrianglePoint on_edge = closest_point_triangle(Vec3(0.5, 0, 0), a, b, c);
  expect_vec_near(on_edge.point, Vec3(0.5, 0, 0), tol_at(1));
  EXPECT_EQ(closest_point_triangle(b, a, b, c).point, b);
}

TEST(ClosestPoint, PointTriangleHugeCoordinatesStayFinite) {
  const Real big = Real(1e30);
  const TrianglePoint r =
      closest_point_triangle(Vec3(big / 4, big / 4, big), Vec3(0, 0, 0), Vec3(big, 0, 0), Vec3(0, big, 0));
  EXPECT_TRUE(is_finite(r.point));
  EXPECT_EQ(r.feature, TriangleFeature::Face);
  EXPECT_NEAR(r.point.x / big, Real(0.25), Real(1e-5));
  EXPECT_NEAR(r.point.z / big, Real(0), Real(1e-5));
}

TEST(ClosestPoint, PointTriangleTinyTriangleIsNotTreatedAsDegenerate) {
  const Real s = Real(1e-12);
  const TrianglePoint r = closest_point_triangle(Vec3(s / 4, s / 4, s), Vec3(0, 0, 0), Vec3(s, 0, 0), Vec3(0, s, 0));
  EXPECT_EQ(r.feature, TriangleFeature::Face);
  EXPECT_NEAR(r.point.x / s, Real(0.25), Real(1e-5));
  EXPECT_NEAR(r.point.z / s, Real(0), Real(1e-5));
}

// Checks one point-triangle answer: a point of the triangle (its barycentric coordinates
// valid and matching), the feature consistent with them, and not farther than the
// reference. Returns the distance error (got - reference).
LD check_point_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c, LD ref, Real tol, int i) {
  const TrianglePoint r = closest_point_triangle(p, a, b, c);
  const Vec3 w = r.barycentric;
  EXPECT_GE(w.x, Real(0)) << i;
  EXPECT_GE(w.y, Real(0)) << i;
  EXPECT_GE(w.z, Real(0)) << i;
  EXPECT_NEAR(w.x + w.y + w.z, Real(1), Real(8) * kEpsilon) << i;
  const LVec from_bary = LD(w.x) * ld(a) + LD(w.y) * ld(b) + LD(w.z) * ld(c);
  EXPECT_LE(std::sqrt(dist2(from_bary, ld(r.point))), tol) << i;
  switch (r.feature) {
    case TriangleFeature::VertexA: EXPECT_EQ(r.point, a) << i; break;
    case TriangleFeature::VertexB: EXPECT_EQ(r.point, b) << i; break;
    case TriangleFeature::VertexC: EXPECT_EQ(r.point, c) << i; break;
    case TriangleFeature::EdgeAB: EXPECT_EQ(w.z, Real(0)) << i; break;
    case TriangleFeature::EdgeBC: EXPECT_EQ(w.x, Real(0)) << i; break;
    case TriangleFeature::EdgeCA: EXPECT_EQ(w.y, Real(0)) << i; break;
    case TriangleFeature::Face: break;
  }
  const LD got = std::sqrt(dist2(ld(p), ld(r.point)));
  EXPECT_LE(got, ref + tol) << i << " p=" << p.x << "," << p.y << "," << p.z;
  return got - ref;
}

TEST(ClosestPoint, PointTriangleRandomAgainstGoldenSearch) {
  test::Random rng(103);
  const Real scales[] = {Real(1), Real(1e-4), Real(1e4)};
  LD worst = 0;
  for (int i = 0; i < 3000; ++i) {
    const Real s = scales[i % 3];
    const Vec3 offset = (i % 5 == 0) ? Vec3(Real(1e4), Real(-1e4), Real(1e4)) * (s / Real(1)) : Vec3(Real(0));
    const Vec3 a = offset + s * rng.vec3(-1, 1);
    const Vec3 b = offset + s * rng.vec3(-1, 1);
    const Vec3 c = offset + s * rng.vec3(-1, 1);
    const Vec3 p = offset + s * rng.vec3(-2, 2);
    const LD ref = std::sqrt(ref_dist2_point_triangle(ld(p), ld(a), ld(b), ld(c)));
    const Real tol = tol_at(max_abs({a, b, c, p}));
    worst = std::max(worst, check_point_triangle(p, a, b, c, ref, tol, i) / tol);
    // Never nearer than the true distance: the answer is a point of the triangle, and the
    // reference is within its search accuracy of the minimum.
  }
  EXPECT_LE(worst, LD(1));
}

// Points near the plane, near edges and vertices (where the region tests decide), and
// slivers of every thinness down to exactly collinear.
TEST(ClosestPoint, PointTriangleNearBoundariesAndSlivers) {
  test::Random rng(104);
  for (int i = 0; i < 3000; ++i) {
    const Vec3 a = rng.vec3(-1, 1);
    const Vec3 b = rng.vec3(-1, 1);
    Vec3 c = rng.vec3(-1, 1);
    const int kind = i % 4;
    if (kind == 1) {
      // sliver: c near the line ab (height 10^-k)
      const Real h = std::pow(Real(10), -Real(rng.integer(1, sizeof(Real) == 4 ? 8 : 16)));
      const Vec3 off = rng.unit_vector();
      c = a + rng.uniform(Real(-0.5), Real(1.5)) * (b - a) + h * off;
    } else if (kind == 2) {
      c = a + rng.uniform(Real(-0.5), Real(1.5)) * (b - a);  // collinear (up to rounding)
    }
    Vec3 p = rng.vec3(-2, 2);
    if (kind == 3) {
      // on or just off the triangle, near a random point of its boundary
      const Real u = rng.uniform(0, 1);
      const Vec3 edge_point = (i % 3 == 0) ? a + u * (b - a) : (i % 3 == 1) ? b + u * (c - b) : c + u * (a - c);
      const Real shrink = std::pow(Real(10), -Real(rng.integer(0, 4)));
      p = edge_point + Real(1e-3) * rng.in_ball(1) * shrink;
    }
    const LD ref = std::sqrt(ref_dist2_point_triangle(ld(p), ld(a), ld(b), ld(c)));
    check_point_triangle(p, a, b, c, ref, tol_at(max_abs({a, b, c, p})), i);
  }
}

// ---------------------------------------------------------------- point-box

TEST(ClosestPoint, PointAabbAnalytic) {
  const Aabb box{Vec3(-1, -2, -3), Vec3(1, 2, 3)};
  EXPECT_EQ(closest_point_aabb(Vec3(0.5, -1, 2), box), Vec3(0.5, -1, 2));
  EXPECT_EQ(closest_point_aabb(Vec3(5, 0, 0), box), Vec3(1, 0, 0));
  EXPECT_EQ(closest_point_aabb(Vec3(-5, 7, 1), box), Vec3(-1, 2, 1));
  EXPECT_EQ(closest_point_aabb(Vec3(9, 9, -9), box), Vec3(1, 2, -3));
  EXPECT_EQ(closest_point_aabb(Vec3(1, 2, 3), box), Vec3(1, 2, 3));
}

TEST(ClosestPoint, PointAabbFlatBox) {
  const Aabb flat{Vec3(0, 0, 1), Vec3(2, 2, 1)};
  EXPECT_EQ(closest_point_aabb(Vec3(1, 1, 5), flat), Vec3(1, 1, 1));
  EXPECT_EQ(closest_point_aabb(Vec3(3, -1, -5), flat), Vec3(2, 0, 1));
}

TEST(ClosestPoint, PointAabbEmptyBoxIsFinite) {
  const Vec3 q = closest_point_aabb(Vec3(1, 2, 3), Aabb::empty());
  EXPECT_TRUE(is_finite(q));
}

// Dense sampling of the box: nothing sampled is nearer than the answer, and the answer is
// in the box.
TEST(ClosestPoint, PointAabbRandomAgainstSampling) {
  test::Random rng(105);
  for (int i = 0; i < 300; ++i) {
    const Vec3 c = rng.vec3(-5, 5);
    const Vec3 h = rng.vec3(0, 2);
    const Aabb box = Aabb::from_center_half_extents(c, h);
    const Vec3 p = rng.vec3(-8, 8);
    const Vec3 q = closest_point_aabb(p, box);
    EXPECT_TRUE(box.contains(q));
    const Real got = std::sqrt(length_squared(p - q));
    constexpr int kN = 12;
    Real sampled = kRealMax;
    for (int x = 0; x <= kN; ++x) {
      for (int y = 0; y <= kN; ++y) {
        for (int z = 0; z <= kN; ++z) {
          const Vec3 s = box.min + Vec3(Real(x), Real(y), Real(z)) / Real(kN) * (box.max - box.min);
          sampled = std::min(sampled, std::sqrt(length_squared(p - s)));
        }
      }
    }
    EXPECT_LE(got, sampled + tol_at(10)) << i;
    // and within the sampling step of it
    EXPECT_GE(got, sampled - glm::length(box.max - box.min) / Real(kN)) << i;
  }
}

TEST(ClosestPoint, PointObbAnalytic) {
  // Box rotated 90 degrees about z: local x is world y.
  const Mat3 axes(Vec3(0, 1, 0), Vec3(-1, 0, 0), Vec3(0, 0, 1));
  const Vec3 center(10, 0, 0);
  const Vec3 h(2, 1, 0.5);
  expect_vec_near(closest_point_obb(Vec3(10, 5, 0), center, axes, h), Vec3(10, 2, 0), tol_at(10));
  expect_vec_near(closest_point_obb(Vec3(15, 0, 3), center, axes, h), Vec3(11, 0, 0.5), tol_at(15));
  const Vec3 inside(10.5, -1.5, 0.25);
  EXPECT_EQ(closest_point_obb(inside, center, axes, h), inside);
}

TEST(ClosestPoint, PointObbFarFromOriginKeepsInsidePointsExact) {
  const Mat3 axes(glm::mat3_cast(glm::angleAxis(Real(0.3), glm::normalize(Vec3(1, 2, 3)))));
  const Vec3 center(1e4, -1e4, 1e4);
  const Vec3 p = center + Vec3(0.1, 0.2, -0.1);
  EXPECT_EQ(closest_point_obb(p, center, axes, Vec3(1, 1, 1)), p);
}

// Reference: transform to the box frame in long double, clamp, transform back.
TEST(ClosestPoint, PointObbRandomAgainstLocalFrameClamp) {
  test::Random rng(106);
  for (int i = 0; i < 3000; ++i) {
    const Quat q = rng.rotation();
    const Mat3 axes = glm::mat3_cast(q);
    const Vec3 center = rng.vec3(-10, 10);
    const Vec3 h = rng.vec3(0, 3);
    const Vec3 p = rng.vec3(-15, 15);
    const Vec3 got = closest_point_obb(p, center, axes, h);
    LVec ref = ld(center);
    for (int k = 0; k < 3; ++k) {
      const LVec axis = ld(axes[k]);
      const LD along = std::clamp(glm::dot(ld(p) - ld(center), axis), -LD(h[k]), LD(h[k]));
      ref += along * axis;
    }
    EXPECT_LE(std::sqrt(dist2(ld(got), ref)), tol_at(30)) << i;
  }
}

// ---------------------------------------------------------------- NaN input

// NaN (or infinite) coordinates are invalid input: every query still returns, with NaN in
// its answer instead of a plausible-looking distance (triangles_intersect: false).
TEST(ClosestPoint, NanInputPropagates) {
  test::ScopedNoFpTraps no_traps;
  const Real nan = std::numeric_limits<Real>::quiet_NaN();
  const Vec3 bad(Real(0), nan, Real(0));
  const Vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  EXPECT_TRUE(std::isnan(distance_squared_point_point(bad, a)));
  EXPECT_FALSE(is_finite(closest_point_line(bad, a, b).point));
  EXPECT_FALSE(is_finite(closest_point_segment(bad, a, b).point));
  EXPECT_FALSE(is_finite(closest_point_segment(a, bad, b).point));
  EXPECT_FALSE(is_finite(closest_point_triangle(bad, a, b, c).point));
  EXPECT_FALSE(is_finite(closest_point_triangle(a, b, bad, c).point));
  EXPECT_FALSE(is_finite(closest_point_aabb(bad, Aabb{a, b})));
  EXPECT_FALSE(is_finite(closest_point_obb(bad, a, Mat3(Real(1)), Vec3(1))));
  EXPECT_TRUE(std::isnan(closest_points_line_line(bad, b, a, c).distance_squared));
  const Vec3 inf(std::numeric_limits<Real>::infinity(), Real(0), Real(0));
  EXPECT_TRUE(std::isnan(closest_points_segment_segment(a, inf, b, c).distance_squared));
  EXPECT_TRUE(std::isnan(closest_point_segment(inf, a, b).t));
  for (int k = 0; k < 4; ++k) {
    Vec3 v[4] = {a, b, c, Vec3(1, 1, 1)};
    v[k] = bad;
    EXPECT_TRUE(std::isnan(closest_points_segment_segment(v[0], v[1], v[2], v[3]).distance_squared)) << k;
  }
  for (int k = 0; k < 5; ++k) {
    Vec3 v[5] = {Vec3(0.2, 0.2, -1), Vec3(0.2, 0.2, 1), a, b, c};
    v[k] = bad;
    EXPECT_TRUE(std::isnan(closest_points_segment_triangle(v[0], v[1], v[2], v[3], v[4]).distance_squared)) << k;
  }
  for (int k = 0; k < 6; ++k) {
    Vec3 v[6] = {a, b, c, Vec3(0.2, 0.2, -1), Vec3(0.2, 0.2, 1), Vec3(2, 2, 0)};
    v[k] = bad;
    EXPECT_TRUE(std::isnan(closest_points_triangle_triangle(v[0], v[1], v[2], v[3], v[4], v[5]).distance_squared)) << k;
    EXPECT_FALSE(triangles_intersect(v[0], v[1], v[2], v[3], v[4], v[5])) << k;
  }
}

}  // namespace test_closest_point
}  // namespace proxima::geometry
