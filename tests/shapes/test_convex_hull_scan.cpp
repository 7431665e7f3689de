// ConvexHull's three support searches against a brute-force maximum written here:
//  - scan_support_index (SSE2 blocks of four in float) returns exactly the index of
//    scalar_support_index (one vertex per step), the first vertex of largest dot product
//    over the shifted vertices, at every size from 4 to 300 vertices;
//  - climb_support_index from random starts reaches the largest dot product (within the
//    rounding of the shifted vertices);
//  - on degenerate hulls: nearly flat slabs, needles, clouds given with every point twice,
//    boxes and prisms (exact ties along the axes and the face normals), and directions
//    lying in a face's plane (perpendicular to its normal: ties along a whole edge or face);
//  - the zero direction gives vertex 0, a NaN direction a valid index.

#include <gtest/gtest.h>

#include <proxima/core/tolerance.hpp>
#include <proxima/shapes/convex_hull.hpp>

#include <cmath>
#include <cstdint>
#include <limits>
#include <span>
#include <string>
#include <vector>

#include "brute_support.hpp"
#include "support/random.hpp"

namespace proxima {
namespace test_convex_hull_scan {

using test::brute_support;

std::vector<Vec3> directions(const ConvexHull& hull, test::Random& rng) {
  std::vector<Vec3> dirs;
  for (int i = 0; i < 150; ++i) dirs.push_back(rng.vector_of_length(Real(0.01), Real(100)));
  for (int a = 0; a < 3; ++a) {
    for (const Real s : {Real(1), Real(-1)}) {
      Vec3 d(Real(0));
      d[a] = s;
      dirs.push_back(d);
    }
  }
  // Face normals (ties over the face) and directions in each face's plane (ties along an
  // edge when the direction is perpendicular to it, or over the face for flat hulls).
  for (std::uint32_t f = 0; f < hull.faces().size() && f < 40; ++f) {
    const Vec3 n = hull.faces()[f].normal;
    dirs.push_back(n);
    const auto loop = hull.face_vertices(f);
    const Vec3 e = hull.vertices()[loop[1]] - hull.vertices()[loop[0]];
    dirs.push_back(glm::cross(n, e));
    dirs.push_back(e);
  }
  return dirs;
}

void check_hull(const ConvexHull& hull, test::Random& rng, const std::string& what) {
  const std::span<const Vec3> v = hull.vertices();
  std::vector<Vec3> shifted(v.begin(), v.end());
  const Vec3 ref = hull.local_aabb().center();
  for (Vec3& p : shifted) p -= ref;
  const auto n = static_cast<std::uint32_t>(v.size());
  std::uint32_t start = 0;
  for (const Vec3& d : directions(hull, rng)) {
    Real best = Real(0);
    const std::uint32_t first = brute_support(shifted, d, best);
    const std::uint32_t scan = hull.scan_support_index(d);
    ASSERT_EQ(scan, hull.scalar_support_index(d)) << what << " d=" << d.x << "," << d.y << "," << d.z;
    ASSERT_EQ(scan, first) << what << " d=" << d.x << "," << d.y << "," << d.z;
    const std::uint32_t climb = hull.climb_support_index(d, start);
    ASSERT_LT(climb, n) << what;
    const Real tol = Real(8) * kEpsilon * hull.scale() * glm::length(d);
    EXPECT_NEAR(glm::dot(shifted[climb], d), best, tol) << what;
    start = static_cast<std::uint32_t>(rng.integer(0, static_cast<int>(n) - 1));
    // support_index is one of the two, by size.
    EXPECT_NEAR(glm::dot(shifted[hull.support_index(d, start)], d), best, tol) << what;
  }
  EXPECT_EQ(hull.scan_support_index(Vec3(Real(0))), 0u) << what;
  {
    test::ScopedNoFpTraps no_traps;  // comparisons with NaN raise FE_INVALID
    const Real nan = std::numeric_limits<Real>::quiet_NaN();
    EXPECT_EQ(hull.scan_support_index(Vec3(nan, nan, nan)), 0u) << what;
    EXPECT_EQ(hull.scalar_support_index(Vec3(nan, nan, nan)), 0u) << what;
    EXPECT_LT(hull.climb_support_index(Vec3(nan, Real(1), Real(0)), 0), n) << what;
  }
}

ConvexHull make(const std::vector<Vec3>& pts, const std::string& what) {
  auto hull = ConvexHull::create(pts);
  EXPECT_TRUE(hull.ok()) << what;
  return hull.value();
}

TEST(ConvexHullScan, RandomCloudsEverySize) {
  test::Random rng(99);
  for (int n = 4; n <= 300; n += (n < 40 ? 1 : 13)) {
    std::vector<Vec3> pts;
    for (int i = 0; i < n; ++i) pts.push_back(rng.vector_of_length(Real(0.5), Real(2)));
    // Far from the local origin: the shifted vertices keep the hull's resolution.
    const Vec3 offset = n % 3 == 0 ? Vec3(Real(100), Real(-50), Real(20)) : Vec3(Real(0));
    for (Vec3& p : pts) p += offset;
    check_hull(make(pts, "cloud"), rng, "cloud n=" + std::to_string(n));
  }
}

TEST(ConvexHullScan, FlatNeedleAndDuplicatedClouds) {
  test::Random rng(5);
  for (int n : {6, 9, 17, 40, 130}) {
    std::vector<Vec3> flat, needle, twice;
    for (int i = 0; i < n; ++i) {
      const Vec3 u = rng.unit_vector();
      flat.emplace_back(u.x, u.y, Real(0.002) * u.z);
      needle.emplace_back(Real(0.01) * u.x, Real(0.01) * u.y, Real(5) * u.z);
      twice.push_back(u);
      twice.push_back(u);  // duplicates are dropped by the build; the rest must still agree
    }
    check_hull(make(flat, "flat"), rng, "flat n=" + std::to_string(n));
    check_hull(make(needle, "needle"), rng, "needle n=" + std::to_string(n));
    check_hull(make(twice, "twice"), rng, "twice n=" + std::to_string(n));
  }
}

TEST(ConvexHullScan, BoxesAndPrismsWithExactTies) {
  test::Random rng(11);
  std::vector<Vec3> box;
  for (int i = 0; i < 8; ++i) box.emplace_back(i & 1 ? 1 : -1, i & 2 ? 2 : -2, i & 4 ? 3 : -3);
  check_hull(make(box, "box"), rng, "box");
  for (int k = 3; k <= 90; k += 7) {
    std::vector<Vec3> pts;
    for (int i = 0; i < k; ++i) {
      const Real a = Real(6.283185307179586) * Real(i) / Real(k);
      pts.emplace_back(std::cos(a), std::sin(a), Real(1));
      pts.emplace_back(std::cos(a), std::sin(a), Real(-1));
    }
    check_hull(make(pts, "prism"), rng, "prism k=" + std::to_string(k));
  }
}

}  // namespace test_convex_hull_scan
}  // namespace proxima
