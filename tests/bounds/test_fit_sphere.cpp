// Bounding-sphere fitting: containment on thousands of clouds, Welzl against a brute-force
// minimum over all 2-, 3- and 4-point support sets, approximations never below minimal,
// named degenerate cases and validation errors.
#include <gtest/gtest.h>

#include <proxima/bounds/fit_sphere.hpp>
#include <proxima/core/tolerance.hpp>

#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include "bounds/test_bounds_support.hpp"
#include "support/random.hpp"

namespace proxima {
namespace test_fit_sphere {

using LD = long double;
struct LVec {
  LD x, y, z;
};
LVec lv(const Vec3& p) { return {LD(p.x), LD(p.y), LD(p.z)}; }
LVec sub(const LVec& a, const LVec& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
LVec add(const LVec& a, const LVec& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
LVec mul(const LVec& a, LD s) { return {a.x * s, a.y * s, a.z * s}; }
LD dot(const LVec& a, const LVec& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
LVec cross(const LVec& a, const LVec& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

// Smallest ball with all of `s` on its boundary (centre in their affine hull); false when
// the points are affinely dependent.
bool circumball(const std::vector<LVec>& s, LVec& c, LD& r2) {
  if (s.size() == 2) {
    c = mul(add(s[0], s[1]), LD(0.5));
    r2 = dot(sub(s[0], c), sub(s[0], c));
    return true;
  }
  if (s.size() == 3) {
    const LVec ab = sub(s[1], s[0]), ac = sub(s[2], s[0]);
    const LVec n = cross(ab, ac);
    const LD n2 = dot(n, n);
    if (!(n2 > LD(1e-30) * dot(ab, ab) * dot(ac, ac))) return false;
    const LVec rel = mul(add(mul(cross(n, ab), dot(ac, ac)), mul(cross(ac, n), dot(ab, ab))), LD(1) / (LD(2) * n2));
    c = add(s[0], rel);
    r2 = dot(rel, rel);
    return true;
  }
  // Four points: 2 (p_i - p0) . x = |p_i - p0|^2, Cramer's rule.
  const LVec a = sub(s[1], s[0]), b = sub(s[2], s[0]), d = sub(s[3], s[0]);
  const LD det = dot(a, cross(b, d));
  const LD scale = std::sqrt(dot(a, a) * dot(b, b) * dot(d, d));
  if (!(std::abs(det) > LD(1e-15) * scale)) return false;
  const LD ra = dot(a, a) / 2, rb = dot(b, b) / 2, rd = dot(d, d) / 2;
  const LVec rel = mul(add(add(mul(cross(b, d), ra), mul(cross(d, a), rb)), mul(cross(a, b), rd)), LD(1) / det);
  c = add(s[0], rel);
  r2 = dot(rel, rel);
  return true;
}

// Brute-force minimum enclosing ball radius over all 2-, 3-, 4-point support sets.
LD brute_force_min_radius(const std::vector<Vec3>& pts) {
  std::vector<LVec> p;
  for (const Vec3& q : pts) p.push_back(lv(q));
  const std::size_t n = p.size();
  LD best = std::numeric_limits<LD>::max();
  auto try_set = [&](const std::vector<LVec>& s) {
    LVec c;
    LD r2;
    if (!circumball(s, c, r2)) return;
    if (r2 >= best * best) return;
    for (const LVec& q : p) {
      if (dot(sub(q, c), sub(q, c)) > r2 * (1 + LD(1e-14)) + LD(1e-40)) return;
    }
    best = std::sqrt(r2);
  };
  if (n == 1) return 0;
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = i + 1; j < n; ++j) {
      try_set({p[i], p[j]});
      for (std::size_t k = j + 1; k < n; ++k) {
        try_set({p[i], p[j], p[k]});
        for (std::size_t l = k + 1; l < n; ++l) try_set({p[i], p[j], p[k], p[l]});
      }
    }
  }
  return best;
}

// Tolerance of a fitted radius: the centre is rounded to Real (a few ulps of the
// coordinates' magnitude) and the radius computed in Real.
Real radius_tol(Real r, Real magnitude) { return Real(8) * kEpsilon * magnitude + Real(64) * kEpsilon * r; }

TEST(FitSphere, EveryFitterContainsEveryPoint) {
  const auto sweep = test::make_cloud_sweep(101, 3000, 60);
  const SphereFit methods[] = {SphereFit::Centroid, SphereFit::AabbCenter, SphereFit::Ritter, SphereFit::Minimal};
  int checked = 0;
  for (const auto& c : sweep) {
    for (SphereFit m : methods) {
      auto s = fit_sphere(c.points, m);
      ASSERT_TRUE(s.ok()) << c.label;
      ASSERT_TRUE(std::isfinite(s->radius) && s->radius >= Real(0)) << c.label;
      for (const Vec3& p : c.points) ASSERT_TRUE(s->contains(p)) << c.label << " method " << static_cast<int>(m);
      ++checked;
    }
  }
  EXPECT_EQ(checked, 12000);
}

TEST(FitSphere, WelzlMatchesBruteForceMinimum) {
  const auto sweep = test::make_cloud_sweep(202, 900, 12);
  int compared = 0;
  for (const auto& c : sweep) {
    const LD ref = brute_force_min_radius(c.points);
    auto s = fit_sphere_minimal(c.points);
    ASSERT_TRUE(s.ok());
    const Real tol = radius_tol(Real(ref), c.magnitude);
    EXPECT_NEAR(double(s->radius), double(ref), double(tol)) << c.label;
    ++compared;
  }
  EXPECT_EQ(compared, 900);
}

TEST(FitSphere, ApproximationsAreNeverBelowMinimal) {
  const auto sweep = test::make_cloud_sweep(303, 2000, 80);
  int ritter_within_20pct = 0;
  for (const auto& c : sweep) {
    const Real r_min = fit_sphere_minimal(c.points)->radius;
    const Real tol = radius_tol(r_min, c.magnitude);
    const Real r_c = fit_sphere_centroid(c.points)->radius;
    const Real r_a = fit_sphere_aabb_center(c.points)->radius;
    const Real r_r = fit_sphere_ritter(c.points)->radius;
    EXPECT_GE(r_c, r_min - tol) << c.label;
    EXPECT_GE(r_a, r_min - tol) << c.label;
    EXPECT_GE(r_r, r_min - tol) << c.label;
    if (r_r <= Real(1.2) * r_min + tol) ++ritter_within_20pct;
  }
  // Ritter is usually within a few percent of minimal.
  EXPECT_GE(ritter_within_20pct, 1900);
}

TEST(FitSphere, MinimalIsDeterministic) {
  test::Random rng(7);
  const auto pts = test::make_cloud(rng, test::CloudKind::Gaussian, 500, Real(3), Vec3(Real(1), Real(2), Real(3)));
  const BoundingSphere a = *fit_sphere_minimal(pts);
  const BoundingSphere b = *fit_sphere_minimal(pts);
  EXPECT_EQ(a.center, b.center);
  EXPECT_EQ(a.radius, b.radius);
}

TEST(FitSphere, NamedCases) {
  const Real tol = Real(64) * kEpsilon;
  // Regular tetrahedron: circumradius sqrt(3) for corners (+-1,+-1,+-1) with even sign count.
  const std::vector<Vec3> tet{{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}};
  auto s = fit_sphere_minimal(tet);
  EXPECT_NEAR(s->radius, std::sqrt(Real(3)), tol * 4);
  EXPECT_NEAR(glm::length(s->center), Real(0), tol * 4);
  // Cube corners: half diagonal; an extra interior point changes nothing.
  std::vector<Vec3> cube;
  for (int k = 0; k < 8; ++k) cube.push_back(Vec3(k & 1 ? 2 : 0, k & 2 ? 2 : 0, k & 4 ? 2 : 0));
  cube.push_back(Vec3(1, 1, 1));
  EXPECT_NEAR(fit_sphere_minimal(cube)->radius, std::sqrt(Real(3)), tol * 4);
  // Equilateral triangle (a coplanar support set): circumradius 1.
  const std::vector<Vec3> tri{{1, 0, 5}, {-0.5, std::sqrt(Real(3)) / 2, 5}, {-0.5, -std::sqrt(Real(3)) / 2, 5}};
  EXPECT_NEAR(fit_sphere_minimal(tri)->radius, Real(1), tol * 4);
  // Obtuse triangle: the longest edge's diameter ball.
  const std::vector<Vec3> obtuse{{-1, 0, 0}, {1, 0, 0}, {0, Real(0.1), 0}};
  EXPECT_NEAR(fit_sphere_minimal(obtuse)->radius, Real(1), tol * 4);
  // Collinear points: half the span.
  const std::vector<Vec3> line{{0, 0, 0}, {1, 1, 1}, {3, 3, 3}, {2, 2, 2}, {-1, -1, -1}};
  EXPECT_NEAR(fit_sphere_minimal(line)->radius, Real(2) * std::sqrt(Real(3)), tol * 8);
  // Four cocircular coplanar points (a square): degenerate 4-point support set.
  const std::vector<Vec3> square{{1, 0, 0}, {0, 1, 0}, {-1, 0, 0}, {0, -1, 0}};
  EXPECT_NEAR(fit_sphere_minimal(square)->radius, Real(1), tol * 4);
  // Duplicates and a single point.
  const std::vector<Vec3> dup{{1, 2, 3}, {1, 2, 3}, {1, 2, 3}};
  EXPECT_EQ(fit_sphere_minimal(dup)->radius, Real(0));
  EXPECT_EQ(fit_sphere_minimal(dup)->center, Vec3(1, 2, 3));
  // Points on a sphere: radius ~1 (all on the surface).
  test::Random rng(9);
  std::vector<Vec3> sph;
  for (int i = 0; i < 2000; ++i) sph.push_back(rng.unit_vector() * Real(10) + Vec3(100, 0, 0));
  auto big = fit_sphere_minimal(sph);
  EXPECT_LE(big->radius, Real(10) * (1 + tol * 10));
  EXPECT_GE(big->radius, Real(9.9));
  for (const Vec3& p : sph) EXPECT_TRUE(big->contains(p));
}

TEST(FitSphere, ValidationErrorsNameTheField) {
  test::ScopedNoFpTraps no_traps;
  const Real nan = std::numeric_limits<Real>::quiet_NaN();
  const Real inf = std::numeric_limits<Real>::infinity();
  const std::vector<Vec3> empty;
  for (SphereFit m : {SphereFit::Centroid, SphereFit::AabbCenter, SphereFit::Ritter, SphereFit::Minimal}) {
    auto e = fit_sphere(empty, m);
    ASSERT_FALSE(e.ok());
    EXPECT_EQ(e.error().code, ErrorCode::TooFew);
    EXPECT_EQ(e.error().field, "points");
    std::vector<Vec3> bad{{0, 0, 0}, {1, 1, 1}, {2, 2, 2}, {0, nan, 0}};
    auto f = fit_sphere(bad, m);
    ASSERT_FALSE(f.ok());
    EXPECT_EQ(f.error().code, ErrorCode::NotFinite);
    EXPECT_EQ(f.error().field, "points[3].y");
    bad[3] = Vec3(0, 0, -inf);
    EXPECT_EQ(fit_sphere(bad, m).error().field, "points[3].z");
    bad[3] = Vec3(Real(2) * kMaxCoordinate, 0, 0);
    EXPECT_EQ(fit_sphere(bad, m).error().code, ErrorCode::OutOfRange);
    EXPECT_EQ(fit_sphere(bad, m).error().field, "points[3].x");
  }
}

}  // namespace test_fit_sphere
}  // namespace proxima
