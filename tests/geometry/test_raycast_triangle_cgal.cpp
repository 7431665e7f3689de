// ray_triangle against CGAL's exact kernel (Epeck): do_intersect and the exact
// intersection point, on seeded random triangles and rays (segments and unbounded rays)
// at unit, huge, tiny and far-from-origin scales, plus rays exactly through vertices and
// edge points (axis-aligned, where the watertight test is exact as well).
//
// Floating point and exact arithmetic may legitimately disagree within rounding of the
// boundary, so random cases closer than a margin to an edge, to either end of the
// segment, or to parallel with the plane are counted and skipped; all others must agree.
#include <gtest/gtest.h>

#include <proxima/core/tolerance.hpp>
#include <proxima/geometry/raycast.hpp>

#if PROXIMA_HAVE_CGAL
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/intersections.h>
#endif

#include <array>
#include <cmath>
#include <limits>
#include <string>

#include "support/random.hpp"

namespace proxima::geometry {
namespace test_raycast_triangle_cgal {

#if PROXIMA_HAVE_CGAL

using K = CGAL::Exact_predicates_exact_constructions_kernel;
using D3 = glm::dvec3;

K::Point_3 exact(const Vec3& v) { return {double(v.x), double(v.y), double(v.z)}; }
K::Vector_3 exact_vector(const Vec3& v) { return {double(v.x), double(v.y), double(v.z)}; }

/// Exact answer: does the ray (segment for finite max_t) meet the closed triangle, and at
/// which parameter (when the meeting is one point).
struct ExactAnswer {
  bool hit = false;
  bool single_point = false;
  double t = 0;
};

ExactAnswer exact_cast(const Ray& ray, Real max_t, const Vec3& a, const Vec3& b, const Vec3& c) {
  const K::Triangle_3 tri(exact(a), exact(b), exact(c));
  const K::Point_3 o = exact(ray.origin);
  const K::Vector_3 d = exact_vector(ray.direction);
  ExactAnswer r;
  // CGAL::exact first: to_double of a lazy number reads its interval approximation only.
  auto param = [&](const K::Point_3& p) { return CGAL::to_double(CGAL::exact(((p - o) * d) / (d * d))); };
  auto read = [&](const auto& result) {
    if (!result) return;
    r.hit = true;
    if (const K::Point_3* p = boost::get<K::Point_3>(&*result)) {  // CGAL 5: boost::variant
      r.single_point = true;
      r.t = param(*p);
    }
  };
  if (std::isinf(max_t)) {
    const K::Ray_3 line(o, d);
    r.hit = CGAL::do_intersect(tri, line);
    if (r.hit) read(CGAL::intersection(tri, line));
  } else {
    const K::Segment_3 seg(o, o + d * K::FT(double(max_t)));
    r.hit = CGAL::do_intersect(tri, seg);
    if (r.hit) read(CGAL::intersection(tri, seg));
  }
  return r;
}

struct Setting {
  Real scale;
  Vec3 offset;
};

// Built at run time (see test_raycast_bruteforce.cpp: static aggregates holding inexact
// constants are miscompiled by GCC 12 with CGAL's -frounding-math).
std::array<Setting, 4> settings() {
  return {{{Real(1), Vec3(0)},
           {Real(1e4), Vec3(0)},
           {Real(1e-4), Vec3(0)},
           {Real(1), Vec3(Real(1e4), Real(-1e4), Real(1e4))}}};
}

TEST(RayTriangleCgal, RandomCasesAgreeWithExactArithmetic) {
  for (const Setting& s : settings()) {
    SCOPED_TRACE(::testing::Message() << "scale " << s.scale << " offset " << s.offset.x);
    test::Random rng(61);
    int hits = 0;
    int misses = 0;
    int skipped = 0;
    const int n = 3000;
    for (int i = 0; i < n; ++i) {
      const Vec3 centre = s.offset + s.scale * rng.in_ball(Real(0.5));
      const Vec3 a = centre + s.scale * rng.in_ball(1);
      const Vec3 b = centre + s.scale * rng.in_ball(1);
      const Vec3 c = centre + s.scale * rng.in_ball(1);
      const D3 da(a), db(b), dc(c);
      const D3 cr = glm::cross(db - da, dc - da);
      if (glm::length(cr) < 1e-2 * glm::length(db - da) * glm::length(dc - da)) continue;  // sliver: not this test
      // Aim at a point of the triangle's plane around it (barycentrics from -0.2).
      const Real u = rng.uniform(Real(-0.2), Real(1));
      const Real v = rng.uniform(Real(-0.2), Real(1) - u);
      const Vec3 target = a + u * (b - a) + v * (c - a);
      const Vec3 origin = centre + s.scale * rng.in_ball(Real(3));
      Vec3 dir = target - origin;
      if (!(glm::length(dir) > Real(1e-2) * s.scale)) continue;
      dir *= rng.uniform(Real(0.2), Real(3));
      const Real max_t = rng.integer(0, 2) == 0
                             ? std::numeric_limits<Real>::infinity()
                             : rng.uniform(Real(0.3), Real(2.5)) * glm::length(target - origin) / glm::length(dir);
      const Ray ray{origin, dir};

      // Margins, in double (relative to the triangle's size).
      const D3 nrm = glm::normalize(cr);
      const D3 o(origin), d(dir);
      const double dl = glm::length(d);
      const double margin = 4000 * double(kEpsilon) * double(s.scale);
      const double cosine = std::abs(glm::dot(nrm, d)) / dl;
      const double tp = glm::dot(nrm, da - o) / glm::dot(nrm, d);
      const D3 p = o + tp * d;
      double edge = 1e300;
      const D3 vs[3] = {da, db, dc};
      const double orient = glm::dot(cr, nrm) > 0 ? 1 : -1;
      for (int k = 0; k < 3; ++k) {
        const D3 e = vs[(k + 1) % 3] - vs[k];
        edge = std::min(edge, orient * glm::dot(glm::cross(e, p - vs[k]), nrm) / glm::length(e));
      }
      const bool near_end =
          std::abs(tp) * dl < margin || (!std::isinf(max_t) && std::abs(tp - double(max_t)) * dl < margin);
      if (cosine < 1e-3 || std::abs(edge) < margin / cosine || near_end) {
        ++skipped;
        continue;
      }

      const ExactAnswer want = exact_cast(ray, max_t, a, b, c);
      const auto got = ray_triangle(ray, max_t, a, b, c);
      ASSERT_EQ(got.has_value(), want.hit) << "case " << i;
      if (!got) {
        ++misses;
        continue;
      }
      ++hits;
      ASSERT_TRUE(want.single_point);
      EXPECT_NEAR(double(got->t) * dl, want.t * dl, margin / cosine) << "case " << i;
      EXPECT_NEAR(std::abs(glm::dot(D3(got->normal), nrm)), 1.0, 1e-5) << "case " << i;
      EXPECT_LE(glm::dot(D3(got->normal), d), 0.0) << "case " << i;
    }
    EXPECT_GT(hits, n / 4);
    EXPECT_GT(misses, n / 4);
    EXPECT_LT(skipped, n / 20);
    ::testing::Test::RecordProperty(
        "counts_" + std::to_string(s.scale) + "_" + std::to_string(s.offset.x),
        std::to_string(hits) + " hits, " + std::to_string(misses) + " misses, " + std::to_string(skipped) + " skipped");
  }
}

TEST(RayTriangleCgal, AxisAlignedRaysThroughVerticesAndEdgesHit) {
  test::Random rng(62);
  int checked = 0;
  for (int i = 0; i < 1500; ++i) {
    // Dyadic vertices (multiples of 1/8), exact sums and midpoints.
    auto grid = [&] {
      const int z = rng.integer(-16, 16);
      const int y = rng.integer(-16, 16);
      const int x = rng.integer(-16, 16);
      return Vec3(Real(x), Real(y), Real(z)) * Real(0.125);
    };
    const Vec3 off = rng.integer(0, 1) != 0 ? Vec3(Real(1024), Real(-2048), Real(512)) : Vec3(0);
    const Vec3 a = off + grid(), b = off + grid(), c = off + grid();
    const Vec3 pts[6] = {a, b, c, (a + b) * Real(0.5), (b + c) * Real(0.5), (c + a) * Real(0.5)};
    const Vec3 target = pts[rng.integer(0, 5)];
    Vec3 dir(0);
    dir[rng.integer(0, 2)] = rng.integer(0, 1) != 0 ? Real(1) : Real(-1);
    const Ray ray{target - Real(8) * dir, dir};
    const ExactAnswer want = exact_cast(ray, Real(16), a, b, c);
    const D3 cr = glm::cross(D3(b - a), D3(c - a));
    if (cr == D3(0) || glm::dot(cr, D3(dir)) == 0) {
      // Degenerate triangle or a ray in its plane: never a hit by contract.
      EXPECT_FALSE(ray_triangle(ray, Real(16), a, b, c));
      continue;
    }
    ASSERT_TRUE(want.hit);
    const auto got = ray_triangle(ray, Real(16), a, b, c);
    ASSERT_TRUE(got.has_value()) << "case " << i;
    EXPECT_DOUBLE_EQ(want.t, 8.0);
    EXPECT_NEAR(got->t, Real(8), Real(8) * 64 * kEpsilon);
    ++checked;
  }
  EXPECT_GT(checked, 1000);
}

#else

TEST(RayTriangleCgal, SkippedWithoutCgal) { GTEST_SKIP() << "CGAL not found: the exact comparison is not built"; }

#endif

}  // namespace test_raycast_triangle_cgal
}  // namespace proxima::geometry
