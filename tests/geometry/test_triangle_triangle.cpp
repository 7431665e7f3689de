// Triangle-triangle intersection test and closest points.
//
// References: analytic and constructed cases (separated by a plane with a known gap,
// crossing at a chosen interior point, coplanar overlapping or separated by a line,
// touching at a vertex, an edge or a shared feature); for random sweeps the distance is
// checked against a long double reference, the minimum over the six edges of a golden-
// section search along the edge of a long double point-triangle distance (for intersecting
// triangles an edge of one meets the other, so the minimum is 0 exactly then), and
// the intersection test against that distance. Exact CGAL references live in
// test_closest_cgal.cpp.
#include <gtest/gtest.h>

#include <proxima/core/tolerance.hpp>
#include <proxima/geometry/closest_points.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "geometry/long_double_reference.hpp"
#include "support/random.hpp"

namespace proxima::geometry {
namespace test_triangle_triangle {

using test::LD, test::LVec, test::ld, test::dist2, test::tol_at, test::golden_min, test::ref_dist2_point_triangle;

using Tri = std::array<Vec3, 3>;

Real max_abs(const Tri& a, const Tri& b) {
  Real m = Real(0);
  for (int k = 0; k < 3; ++k) {
    for (const Vec3& v : {a[k], b[k]}) m = std::max({m, std::abs(v.x), std::abs(v.y), std::abs(v.z)});
  }
  return m;
}

// The touching band of triangles_intersect at the scale of the pair.
Real touch_tol(const Tri& a, const Tri& b) { return kRelativeTolerance * max_abs(a, b); }

LD ref_dist_point_triangle(const Vec3& p, const Tri& t) {
  return std::sqrt(ref_dist2_point_triangle(ld(p), ld(t[0]), ld(t[1]), ld(t[2])));
}

LD ref_distance(const Tri& a, const Tri& b) {
  LD best = std::numeric_limits<LD>::max();
  for (int side = 0; side < 2; ++side) {
    const Tri& e = side == 0 ? a : b;
    const Tri& t = side == 0 ? b : a;
    const LVec t0 = ld(t[0]), t1 = ld(t[1]), t2 = ld(t[2]);
    for (int k = 0; k < 3; ++k) {
      const LVec p = ld(e[k]);
      const LVec d = ld(e[(k + 1) % 3]) - p;
      best =
          std::min(best, golden_min([&](LD s) { return ref_dist2_point_triangle(p + s * d, t0, t1, t2); }, 0, 1, 80));
    }
  }
  return std::sqrt(best);
}

// Below this the reference distance is 0 up to its long double rounding: the triangles
// intersect.
constexpr LD kRefZero = LD(1e-12);

// Checks one distance answer: witnesses on their triangles, distance_squared matching
// them, not above the reference. Returns (got - ref) / tol.
LD check_distance(const Tri& a, const Tri& b, LD ref, const char* what, int i) {
  const ClosestPair r = closest_points_triangle_triangle(a[0], a[1], a[2], b[0], b[1], b[2]);
  const Real tol = tol_at(max_abs(a, b));
  EXPECT_LE(ref_dist_point_triangle(r.on_a, a), tol) << what << i;
  EXPECT_LE(ref_dist_point_triangle(r.on_b, b), tol) << what << i;
  const LD got = std::sqrt(dist2(ld(r.on_a), ld(r.on_b)));
  EXPECT_NEAR(std::sqrt(r.distance_squared), Real(got), tol) << what << i;
  EXPECT_LE(got, ref + tol) << what << i;
  return (got - ref) / tol;
}

bool intersect(const Tri& a, const Tri& b) { return triangles_intersect(a[0], a[1], a[2], b[0], b[1], b[2]); }

// Both argument orders, and every rotation of the vertex order, agree.
void expect_intersect(const Tri& a, const Tri& b, bool expected, const char* what, int i = 0) {
  for (int k = 0; k < 3; ++k) {
    const Tri ra{a[k], a[(k + 1) % 3], a[(k + 2) % 3]};
    const Tri rb{b[(k + 1) % 3], b[k], b[(k + 2) % 3]};  // also flips b's orientation
    EXPECT_EQ(intersect(ra, rb), expected) << what << i << " rotation " << k;
    EXPECT_EQ(intersect(rb, ra), expected) << what << i << " swapped, rotation " << k;
  }
}

const Tri kUnit{Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(0, 2, 0)};

// ---------------------------------------------------------------- intersection, named

TEST(TriangleTriangle, PiercingIntersects) {
  const Tri b{Vec3(0.5, 0.5, -1), Vec3(0.5, 0.5, 1), Vec3(3, 3, 0.5)};
  expect_intersect(kUnit, b, true, "piercing");
}

TEST(TriangleTriangle, SeparatedAbove) {
  const Tri b{Vec3(0, 0, 1), Vec3(1, 0, 2), Vec3(0, 1, 1.5)};
  expect_intersect(kUnit, b, false, "above");
}

TEST(TriangleTriangle, StraddlingPlaneButMissing) {
  // b crosses a's plane, but outside a (beyond the hypotenuse).
  const Tri b{Vec3(2, 2, -1), Vec3(2, 2, 1), Vec3(3, 1, 0)};
  expect_intersect(kUnit, b, false, "straddling");
}

TEST(TriangleTriangle, LinesOverlapButIntervalsDoNot) {
  // Both cross the line y = 0.5 on z = 0, a on x in [0, 1.5], b on x in [2, 3].
  const Tri b{Vec3(2, 0.5, -1), Vec3(3, 0.5, 1), Vec3(3, 0.5, -1)};
  expect_intersect(kUnit, b, false, "disjoint intervals");
}

TEST(TriangleTriangle, VertexTouchingFace) {
  const Tri b{Vec3(0.5, 0.5, 0), Vec3(1, 1, 2), Vec3(0, 1, 2)};
  expect_intersect(kUnit, b, true, "vertex on face");
}

TEST(TriangleTriangle, EdgeTouchingEdge) {
  // b's edge crosses a's edge ab (y = 0) at (1, 0, 0); b lies below, tilted.
  const Tri b{Vec3(1, -1, 0), Vec3(1, 1, 0), Vec3(1, 0, -2)};
  expect_intersect(kUnit, b, true, "edge on edge");
}

TEST(TriangleTriangle, EdgeTouchingFaceFromOneSide) {
  const Tri b{Vec3(0.2, 0.5, 0), Vec3(1.2, 0.5, 0), Vec3(0.7, 0.5, 1)};
  expect_intersect(kUnit, b, true, "edge on face");
}

TEST(TriangleTriangle, SharedVertex) {
  const Tri b{Vec3(2, 0, 0), Vec3(3, 1, 1), Vec3(3, -1, 1)};
  expect_intersect(kUnit, b, true, "shared vertex");
}

TEST(TriangleTriangle, SharedEdge) {
  const Tri b{Vec3(2, 0, 0), Vec3(0, 0, 0), Vec3(1, -1, 1)};
  expect_intersect(kUnit, b, true, "shared edge");
}

TEST(TriangleTriangle, CoplanarOverlapping) {
  const Tri b{Vec3(1, 1, 0), Vec3(3, 1, 0), Vec3(1, 3, 0)};
  expect_intersect(kUnit, b, true, "coplanar overlap");
}

TEST(TriangleTriangle, CoplanarContained) {
  const Tri b{Vec3(0.2, 0.2, 0), Vec3(0.6, 0.2, 0), Vec3(0.2, 0.6, 0)};
  expect_intersect(kUnit, b, true, "contained");
  const Tri big{Vec3(-5, -5, 0), Vec3(10, -5, 0), Vec3(-5, 10, 0)};
  expect_intersect(kUnit, big, true, "containing");
}

TEST(TriangleTriangle, CoplanarSeparated) {
  const Tri b{Vec3(1.5, 1.5, 0), Vec3(3, 1.5, 0), Vec3(1.5, 3, 0)};
  expect_intersect(kUnit, b, false, "coplanar apart");
}

TEST(TriangleTriangle, CoplanarTouchingAtVertex) {
  const Tri b{Vec3(1, 1, 0), Vec3(3, 1, 0), Vec3(3, 3, 0)};  // (1,1) lies on the hypotenuse
  expect_intersect(kUnit, b, true, "coplanar vertex on edge");
}

TEST(TriangleTriangle, CoplanarSharedEdgeOppositeSides) {
  const Tri b{Vec3(2, 0, 0), Vec3(0, 0, 0), Vec3(1, -1, 0)};
  expect_intersect(kUnit, b, true, "coplanar shared edge");
}

TEST(TriangleTriangle, ParallelPlanesApart) {
  const Tri b{Vec3(0, 0, 1e-3), Vec3(2, 0, 1e-3), Vec3(0, 2, 1e-3)};
  expect_intersect(kUnit, b, false, "parallel");
}

TEST(TriangleTriangle, IdenticalTriangles) { expect_intersect(kUnit, kUnit, true, "identical"); }

TEST(TriangleTriangle, DegenerateSegmentPiercing) {
  const Tri seg{Vec3(0.5, 0.5, -1), Vec3(0.5, 0.5, 1), Vec3(0.5, 0.5, 0.25)};  // collinear
  expect_intersect(kUnit, seg, true, "segment through");
  const Tri off{Vec3(3, 3, -1), Vec3(3, 3, 1), Vec3(3, 3, 0)};
  expect_intersect(kUnit, off, false, "segment beside");
}

TEST(TriangleTriangle, DegeneratePointOnFace) {
  const Tri point{Vec3(0.5, 0.5, 0), Vec3(0.5, 0.5, 0), Vec3(0.5, 0.5, 0)};
  expect_intersect(kUnit, point, true, "point on face");
  const Tri above{Vec3(0.5, 0.5, 1), Vec3(0.5, 0.5, 1), Vec3(0.5, 0.5, 1)};
  expect_intersect(kUnit, above, false, "point above");
}

TEST(TriangleTriangle, BothDegenerate) {
  const Tri s1{Vec3(-1, 0, 0), Vec3(1, 0, 0), Vec3(0, 0, 0)};
  const Tri s2{Vec3(0, -1, 0), Vec3(0, 1, 0), Vec3(0, 1, 0)};
  expect_intersect(s1, s2, true, "crossing segments");
  const Tri s3{Vec3(0, -1, 1), Vec3(0, 1, 1), Vec3(0, 0, 1)};
  expect_intersect(s1, s3, false, "skew segments");
}

TEST(TriangleTriangle, FarFromOriginAndScales) {
  for (const Real s : {Real(1e-4), Real(1), Real(1e4)}) {
    for (const Vec3& o : {Vec3(0), Vec3(Real(1e4), Real(-1e4), Real(1e4))}) {
      if (s < Real(1) && o.x != Real(0)) continue;  // 1e-4 details 1e4 away are below float resolution
      auto place = [&](const Tri& t) { return Tri{o + s * t[0], o + s * t[1], o + s * t[2]}; };
      expect_intersect(place(kUnit), place(Tri{Vec3(0.5, 0.5, -1), Vec3(0.5, 0.5, 1), Vec3(3, 3, 0.5)}), true,
                       "far piercing");
      expect_intersect(place(kUnit), place(Tri{Vec3(0, 0, 1), Vec3(1, 0, 2), Vec3(0, 1, 1.5)}), false, "far above");
    }
  }
}

TEST(TriangleTriangle, HugeCoordinatesStayDefined) {
  const Real s = Real(1e30);
  const Tri a{s * kUnit[0], s * kUnit[1], s * kUnit[2]};
  const Tri b{s * Vec3(0.5, 0.5, -1), s * Vec3(0.5, 0.5, 1), s * Vec3(3, 3, 0.5)};
  EXPECT_TRUE(intersect(a, b));
  const ClosestPair r = closest_points_triangle_triangle(a[0], a[1], a[2], b[0], b[1], b[2]);
  EXPECT_EQ(r.distance_squared, Real(0));
  EXPECT_TRUE(is_finite(r.on_a));
  const Tri c{s * Vec3(0, 0, 1), s * Vec3(1, 0, 2), s * Vec3(0, 1, 1.5)};
  const ClosestPair rc = closest_points_triangle_triangle(a[0], a[1], a[2], c[0], c[1], c[2]);
  EXPECT_NEAR(rc.on_b.z / s, Real(1), Real(1e-5));
  EXPECT_TRUE(std::isinf(rc.distance_squared) || rc.distance_squared > Real(0));
}

// ---------------------------------------------------------------- distance, named

TEST(TriangleTriangle, DistancePiercingIsZeroAtCommonPoint) {
  const Tri b{Vec3(0.5, 0.5, -1), Vec3(0.5, 0.5, 1), Vec3(3, 3, 0.5)};
  const ClosestPair r = closest_points_triangle_triangle(kUnit[0], kUnit[1], kUnit[2], b[0], b[1], b[2]);
  EXPECT_EQ(r.distance_squared, Real(0));
  EXPECT_EQ(r.on_a, r.on_b);
  EXPECT_LE(ref_dist_point_triangle(r.on_a, kUnit), tol_at(3));
  EXPECT_LE(ref_dist_point_triangle(r.on_a, b), tol_at(3));
}

TEST(TriangleTriangle, DistanceVertexFace) {
  const Tri b{Vec3(0.5, 0.5, 1), Vec3(1, 1, 3), Vec3(0, 1, 3)};
  const ClosestPair r = closest_points_triangle_triangle(kUnit[0], kUnit[1], kUnit[2], b[0], b[1], b[2]);
  EXPECT_NEAR(r.distance_squared, Real(1), tol_at(3));
  EXPECT_EQ(r.on_b, b[0]);
  EXPECT_NEAR(r.on_a.x, Real(0.5), tol_at(3));
  EXPECT_NEAR(r.on_a.y, Real(0.5), tol_at(3));
}

TEST(TriangleTriangle, DistanceEdgeEdge) {
  // b's edge at x = 1, y = -1 runs from z = 0.5 down to z = -0.5: nearest to a's edge y = 0
  // at (1, 0, 0), one unit away.
  const Tri b{Vec3(1, -1, 0.5), Vec3(1, -1, -0.5), Vec3(1, -3, 0)};
  const ClosestPair r = closest_points_triangle_triangle(kUnit[0], kUnit[1], kUnit[2], b[0], b[1], b[2]);
  EXPECT_NEAR(r.distance_squared, Real(1), tol_at(3));
  EXPECT_NEAR(r.on_a.x, Real(1), tol_at(3));
  EXPECT_NEAR(r.on_a.y, Real(0), tol_at(3));
  EXPECT_NEAR(r.on_b.y, Real(-1), tol_at(3));
}

TEST(TriangleTriangle, DistanceParallelPlanes) {
  const Tri b{Vec3(0.5, 0.5, 2), Vec3(1.5, 0.5, 2), Vec3(0.5, 1.5, 2)};
  const ClosestPair r = closest_points_triangle_triangle(kUnit[0], kUnit[1], kUnit[2], b[0], b[1], b[2]);
  EXPECT_NEAR(r.distance_squared, Real(4), tol_at(4));
  EXPECT_NEAR(r.on_a.z, Real(0), tol_at(4));
  EXPECT_NEAR(r.on_b.z, Real(2), tol_at(4));
}

TEST(TriangleTriangle, DistanceCoplanarApart) {
  const Tri b{Vec3(2, 2, 0), Vec3(4, 2, 0), Vec3(2, 4, 0)};
  const ClosestPair r = closest_points_triangle_triangle(kUnit[0], kUnit[1], kUnit[2], b[0], b[1], b[2]);
  EXPECT_NEAR(r.distance_squared, Real(2), tol_at(4));
  EXPECT_EQ(r.on_b, b[0]);
}

TEST(TriangleTriangle, DistanceCoplanarOverlapping) {
  const Tri b{Vec3(1, 1, 0), Vec3(3, 1, 0), Vec3(1, 3, 0)};
  const ClosestPair r = closest_points_triangle_triangle(kUnit[0], kUnit[1], kUnit[2], b[0], b[1], b[2]);
  EXPECT_LE(std::sqrt(r.distance_squared), tol_at(3));
}

TEST(TriangleTriangle, DistanceDegenerateTriangles) {
  const Tri seg{Vec3(0.5, 0.5, 1), Vec3(0.5, 0.5, 3), Vec3(0.5, 0.5, 2)};
  const ClosestPair r = closest_points_triangle_triangle(kUnit[0], kUnit[1], kUnit[2], seg[0], seg[1], seg[2]);
  EXPECT_NEAR(r.distance_squared, Real(1), tol_at(3));
  const Tri point{Vec3(3, 3, 0), Vec3(3, 3, 0), Vec3(3, 3, 0)};
  const ClosestPair rp = closest_points_triangle_triangle(point[0], point[1], point[2], kUnit[0], kUnit[1], kUnit[2]);
  EXPECT_NEAR(rp.distance_squared, Real(8), tol_at(8));
  EXPECT_EQ(rp.on_a, point[0]);
  const ClosestPair rpp = closest_points_triangle_triangle(point[0], point[1], point[2], point[0], point[1], point[2]);
  EXPECT_EQ(rpp.distance_squared, Real(0));
}

// ---------------------------------------------------------------- sweeps

Tri random_triangle(test::Random& rng, const Vec3& o, Real s) {
  return {o + s * rng.vec3(-1, 1), o + s * rng.vec3(-1, 1), o + s * rng.vec3(-1, 1)};
}

TEST(TriangleTriangle, RandomDistanceAgainstReference) {
  test::Random rng(401);
  const Real scales[] = {Real(1), Real(1e-4), Real(1e4)};
  LD worst = -1;
  int intersecting = 0;
  for (int i = 0; i < 2400; ++i) {
    const Real s = scales[i % 3];
    const Vec3 o = (i % 4 == 0) ? Vec3(Real(1e4), Real(1e4), Real(-1e4)) : Vec3(Real(0));
    const Tri a = random_triangle(rng, o, s);
    const Tri b = random_triangle(rng, o + s * rng.vec3(-1, 1), s);
    const LD ref = ref_distance(a, b);
    worst = std::max(worst, check_distance(a, b, ref, "random ", i));
    intersecting += ref < kRefZero ? 1 : 0;
    // The intersection test agrees with the distance (away from the touching band).
    const Real band = Real(4) * touch_tol(a, b);
    if (ref > band) {
      EXPECT_FALSE(intersect(a, b)) << i;
    }
    if (intersect(a, b)) {
      const ClosestPair r = closest_points_triangle_triangle(a[0], a[1], a[2], b[0], b[1], b[2]);
      EXPECT_LE(std::sqrt(r.distance_squared), band) << i;
    }
  }
  EXPECT_LE(worst, LD(1));
  EXPECT_GT(intersecting, 200);  // the sweep exercises both outcomes
}

// Crossing at a chosen interior point of a: intersect, distance 0 at a common point.
TEST(TriangleTriangle, RandomConstructedCrossing) {
  test::Random rng(402);
  for (int i = 0; i < 2000; ++i) {
    const Real s = (i % 2 == 0) ? Real(1) : Real(1e-4);
    const Tri a = random_triangle(rng, Vec3(0), s);
    const Vec3 n = glm::cross(a[1] - a[0], a[2] - a[0]);
    if (length_squared(n) < Real(1e-2) * s * s * s * s) continue;  // keep a well shaped
    Real u = rng.uniform(Real(0.1), Real(0.8)), v = rng.uniform(Real(0.1), Real(0.8));
    if (u + v > Real(0.9)) {
      u *= Real(0.5);
      v *= Real(0.5);
    }
    const Vec3 x = a[0] + u * (a[1] - a[0]) + v * (a[2] - a[0]);
    // b's edge crosses a's plane at x at more than ~10 degrees.
    Vec3 dir = rng.unit_vector();
    const Vec3 un = glm::normalize(n);
    if (std::abs(glm::dot(dir, un)) < Real(0.2)) dir = glm::normalize(dir + un);
    const Tri b{x - s * rng.uniform(Real(0.2), 1) * dir, x + s * rng.uniform(Real(0.2), 1) * dir,
                x + s * rng.vec3(-2, 2)};
    expect_intersect(a, b, true, "crossing ", i);
    const ClosestPair r = closest_points_triangle_triangle(a[0], a[1], a[2], b[0], b[1], b[2]);
    const Real tol = tol_at(max_abs(a, b));
    EXPECT_LE(std::sqrt(r.distance_squared), tol) << i;
    EXPECT_LE(ref_dist_point_triangle(r.on_a, a), tol) << i;
    EXPECT_LE(ref_dist_point_triangle(r.on_b, b), tol) << i;
  }
}

// b on the far side of a plane that a lies behind, with a known gap: no intersection, and
// the distance is at least the gap.
TEST(TriangleTriangle, RandomConstructedSeparated) {
  test::Random rng(403);
  for (int i = 0; i < 2000; ++i) {
    const Vec3 n = rng.unit_vector();
    const Real gap = std::pow(Real(10), -Real(rng.integer(0, 3)));
    auto behind = [&](Real lo, Real hi) {
      const Vec3 v = rng.vec3(-1, 1);
      return v - glm::dot(v, n) * n + rng.uniform(lo, hi) * n;
    };
    const Tri a{behind(-1, 0), behind(-1, 0), behind(-1, 0)};
    Tri b{behind(0, 1), behind(0, 1), behind(0, 1)};
    for (Vec3& v : b) v += gap * n;
    expect_intersect(a, b, false, "separated ", i);
    const ClosestPair r = closest_points_triangle_triangle(a[0], a[1], a[2], b[0], b[1], b[2]);
    EXPECT_GE(std::sqrt(r.distance_squared), gap - tol_at(3)) << i;
    check_distance(a, b, ref_distance(a, b), "separated ", i);
  }
}

TEST(TriangleTriangle, RandomCoplanar) {
  test::Random rng(404);
  int hits = 0;
  for (int i = 0; i < 2000; ++i) {
    // Both triangles in the plane z = 0 (exactly coplanar); half of the pairs are then
    // moved by a random rigid transform (coplanar up to rounding).
    // A point of the plane z = 0, each coordinate uniform in [-1, 1); y is drawn first.
    auto planar = [&] {
      const Real y = rng.uniform(-1, 1);
      const Real x = rng.uniform(-1, 1);
      return Vec2(x, y);
    };
    auto lift = [](const Vec2& p) { return Vec3(p.x, p.y, 0); };
    Tri a{lift(planar()), lift(planar()), lift(planar())};
    const Real shift_y = rng.uniform(-2, 2);
    const Real shift_x = rng.uniform(-2, 2);
    const Vec2 shift(shift_x, shift_y);
    Tri b{lift(planar() + shift), lift(planar() + shift), lift(planar() + shift)};
    if (i % 2 == 1) {
      const Transform pose = rng.pose(Real(2));
      for (Vec3& v : a) v = pose.apply(v);
      for (Vec3& v : b) v = pose.apply(v);
    }
    const LD ref = ref_distance(a, b);
    check_distance(a, b, ref, "coplanar ", i);
    const Real band = Real(4) * touch_tol(a, b);
    if (ref > band) {
      EXPECT_FALSE(intersect(a, b)) << i;
    } else if (ref < kRefZero) {
      // Overlapping by a margin: the overlap survives shrinking b towards its centroid.
      const Vec3 g = (b[0] + b[1] + b[2]) / Real(3);
      const Tri shrunk{g + Real(0.99) * (b[0] - g), g + Real(0.99) * (b[1] - g), g + Real(0.99) * (b[2] - g)};
      if (ref_distance(a, shrunk) < kRefZero) {
        EXPECT_TRUE(intersect(a, b)) << i;
        ++hits;
      }
    }
  }
  EXPECT_GT(hits, 100);
}

TEST(TriangleTriangle, RandomTouching) {
  test::Random rng(405);
  for (int i = 0; i < 1500; ++i) {
    const Tri a = random_triangle(rng, Vec3(0), 1);
    const Vec3 n = glm::cross(a[1] - a[0], a[2] - a[0]);
    if (length_squared(n) < Real(1e-2)) continue;
    const Vec3 un = glm::normalize(n);
    Tri b;
    if (i % 3 == 0) {
      // a vertex of b on a's face, b on one side
      Real u = rng.uniform(0, 1), v = rng.uniform(0, 1);
      if (u + v > 1) {
        u = 1 - u;
        v = 1 - v;
      }
      const Vec3 x = a[0] + u * (a[1] - a[0]) + v * (a[2] - a[0]);
      b = {x, x + rng.vec3(-1, 1) + un, x + rng.vec3(-1, 1) + un};
    } else if (i % 3 == 1) {
      // shared vertex
      b = {a[1], a[1] + rng.vec3(-1, 1), a[1] + rng.vec3(-1, 1)};
    } else {
      // shared edge, b folded about it
      b = {a[0], a[1], Real(0.5) * (a[0] + a[1]) + rng.vec3(-1, 1)};
    }
    expect_intersect(a, b, true, "touching ", i);
    check_distance(a, b, 0, "touching ", i);
  }
}

TEST(TriangleTriangle, RandomDegenerate) {
  test::Random rng(406);
  for (int i = 0; i < 1500; ++i) {
    const Tri a = random_triangle(rng, Vec3(0), 1);
    Tri b = random_triangle(rng, Vec3(0), 1);
    switch (i % 4) {
      case 0: b[2] = b[0] + rng.uniform(-1, 2) * (b[1] - b[0]); break;  // collinear
      case 1: b[2] = b[1]; break;                                       // two coincide
      case 2: b[1] = b[2] = b[0]; break;                                // a point
      default: {                                                        // sliver
        const Vec3 off = rng.unit_vector();
        b[2] = b[0] + rng.uniform(0, 1) * (b[1] - b[0]) + Real(1e-5) * off;
        break;
      }
    }
    const LD ref = ref_distance(a, b);
    check_distance(a, b, ref, "degenerate ", i);
    if (ref > Real(4) * touch_tol(a, b)) {
      EXPECT_FALSE(intersect(a, b)) << i;
    }
  }
}

}  // namespace test_triangle_triangle
}  // namespace proxima::geometry
