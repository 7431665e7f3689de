// ConvexHull::mass_properties against references it does not compute itself: closed forms
// for boxes, a pyramid and tetrahedra (Tonon's explicit tetrahedron formulas, written out
// here) and quasi-Monte-Carlo integration over contains. CGAL's volume and centroid are
// compared in test_convex_hull_cgal.cpp.
#include <gtest/gtest.h>

#include <proxima/core/tolerance.hpp>
#include <proxima/shapes/convex_hull.hpp>

#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include "support/random.hpp"

namespace proxima {
namespace test_convex_hull_mass {

constexpr Real kEps = std::numeric_limits<Real>::epsilon();

ConvexHull build(const std::vector<Vec3>& pts) {
  auto r = ConvexHull::create(pts);
  if (!r) ADD_FAILURE() << r.error().what();
  return r.value();
}

void expect_mat_near(const Mat3& a, const Mat3& b, Real tol) {
  for (int c = 0; c < 3; ++c) {
    for (int r = 0; r < 3; ++r) EXPECT_NEAR(a[c][r], b[c][r], tol) << "element [" << c << "][" << r << "]";
  }
}

void expect_vec_near(const Vec3& a, const Vec3& b, Real tol) {
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(a[i], b[i], tol) << "component " << i;
}

std::vector<Vec3> box_corners(const Vec3& half, const Quat& q, const Vec3& center) {
  std::vector<Vec3> p;
  for (int i = 0; i < 8; ++i) {
    p.push_back(center + q * Vec3(i & 1 ? half.x : -half.x, i & 2 ? half.y : -half.y, i & 4 ? half.z : -half.z));
  }
  return p;
}

// ---------------------------------------------------------------------------------------
// Boxes: V = 8 hx hy hz, I = m/3 diag(hy^2 + hz^2, ...) in the box axes.

TEST(ConvexHullMass, CubeAndBoxMatchClosedForm) {
  test::Random rng(1);
  for (int k = 0; k < 50; ++k) {
    const Vec3 half = rng.vec3(Real(0.2), Real(3));
    const Quat q = k == 0 ? kIdentityQuat : rng.rotation();
    const Vec3 center = rng.vec3(Real(-20), Real(20));
    const Real density = rng.uniform(Real(0.5), Real(5));
    const ConvexHull h = build(box_corners(half, q, center));
    const MassProperties m = h.mass_properties(density);
    const Real volume = Real(8) * half.x * half.y * half.z;
    const Real size = Real(2) * std::max({half.x, half.y, half.z});
    // The corners are rounded to Real: relative errors of a few eps * (|center| / size).
    const Real rel = Real(256) * kEps * (Real(1) + Real(20) / size);
    EXPECT_NEAR(m.volume, volume, rel * volume);
    EXPECT_NEAR(m.mass, density * volume, rel * density * volume);
    expect_vec_near(m.centroid, center, rel * size);
    const Mat3 diag(Vec3(m.mass / Real(3) * (half.y * half.y + half.z * half.z), 0, 0),
                    Vec3(0, m.mass / Real(3) * (half.x * half.x + half.z * half.z), 0),
                    Vec3(0, 0, m.mass / Real(3) * (half.x * half.x + half.y * half.y)));
    const Mat3 r = glm::mat3_cast(q);
    expect_mat_near(m.inertia, r * diag * glm::transpose(r), rel * m.mass * size * size);
  }
}

TEST(ConvexHullMass, UnitCubeExactly) {
  std::vector<Vec3> p;
  for (int i = 0; i < 8; ++i) p.push_back(Vec3(i & 1 ? 1 : 0, i & 2 ? 1 : 0, i & 4 ? 1 : 0));
  const MassProperties m = build(p).mass_properties(Real(2));
  EXPECT_NEAR(m.volume, Real(1), Real(8) * kEps);
  EXPECT_NEAR(m.mass, Real(2), Real(16) * kEps);
  expect_vec_near(m.centroid, Vec3(Real(0.5)), Real(8) * kEps);
  expect_mat_near(m.inertia, Mat3(Real(2) / Real(6)), Real(16) * kEps);
}

// ---------------------------------------------------------------------------------------
// Tetrahedra.

TEST(ConvexHullMass, UnitRightTetrahedron) {
  // V = 1/6, centroid (1/4, 1/4, 1/4); about the centroid Ixx = 1/80 and the products of
  // inertia -(int xy - m cx cy) = 1/480, at density 1.
  const MassProperties m = build({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)}).mass_properties(Real(1));
  EXPECT_NEAR(m.volume, Real(1) / Real(6), Real(8) * kEps);
  expect_vec_near(m.centroid, Vec3(Real(0.25)), Real(8) * kEps);
  const Real d = Real(1) / Real(80);
  const Real o = Real(1) / Real(480);
  expect_mat_near(m.inertia, Mat3(Vec3(d, o, o), Vec3(o, d, o), Vec3(o, o, d)), Real(16) * kEps);
}

// Tonon, "Explicit Exact Formulas for the 3-D Tetrahedron Inertia Tensor in Terms of its
// Vertex Coordinates" (J. Math. Stat. 2004), with coordinates relative to the centroid.
Mat3 tonon_inertia(const std::array<std::array<double, 3>, 4>& v, double density, double& volume,
                   std::array<double, 3>& centroid) {
  centroid = {0, 0, 0};
  for (const auto& p : v) {
    for (int a = 0; a < 3; ++a) centroid[a] += p[a] / 4.0;
  }
  std::array<std::array<double, 3>, 4> r;
  for (int i = 0; i < 4; ++i) {
    for (int a = 0; a < 3; ++a) r[i][a] = v[i][a] - centroid[a];
  }
  const double e1[3] = {r[1][0] - r[0][0], r[1][1] - r[0][1], r[1][2] - r[0][2]};
  const double e2[3] = {r[2][0] - r[0][0], r[2][1] - r[0][1], r[2][2] - r[0][2]};
  const double e3[3] = {r[3][0] - r[0][0], r[3][1] - r[0][1], r[3][2] - r[0][2]};
  const double det = std::abs(e1[0] * (e2[1] * e3[2] - e2[2] * e3[1]) - e1[1] * (e2[0] * e3[2] - e2[2] * e3[0]) +
                              e1[2] * (e2[0] * e3[1] - e2[1] * e3[0]));
  volume = det / 6.0;
  auto square_sum = [&](int a) {  // sum_i a_i^2 + sum_{i<j} a_i a_j
    double s = 0;
    for (int i = 0; i < 4; ++i) {
      for (int j = i; j < 4; ++j) s += r[i][a] * r[j][a];
    }
    return s;
  };
  auto product_sum = [&](int a, int b) {  // sum_i 2 a_i b_i + sum_{i != j} a_i b_j
    double s = 0;
    for (int i = 0; i < 4; ++i) {
      for (int j = 0; j < 4; ++j) s += (i == j ? 2.0 : 1.0) * r[i][a] * r[j][b];
    }
    return s;
  };
  const double ia = density * det * (square_sum(1) + square_sum(2)) / 60.0;
  const double ib = density * det * (square_sum(0) + square_sum(2)) / 60.0;
  const double ic = density * det * (square_sum(0) + square_sum(1)) / 60.0;
  const double pa = density * det * product_sum(1, 2) / 120.0;  // yz
  const double pb = density * det * product_sum(0, 2) / 120.0;  // xz
  const double pc = density * det * product_sum(0, 1) / 120.0;  // xy
  return Mat3(Vec3(Real(ia), Real(-pc), Real(-pb)), Vec3(Real(-pc), Real(ib), Real(-pa)),
              Vec3(Real(-pb), Real(-pa), Real(ic)));
}

TEST(ConvexHullMass, RandomTetrahedraMatchTonon) {
  test::Random rng(2);
  int checked = 0;
  for (int k = 0; k < 2000; ++k) {
    std::array<Vec3, 4> p{rng.vec3(Real(-1), Real(1)), rng.vec3(Real(-1), Real(1)), rng.vec3(Real(-1), Real(1)),
                          rng.vec3(Real(-1), Real(1))};
    const Vec3 shift = rng.vec3(Real(-10), Real(10));
    for (Vec3& v : p) v += shift;
    std::array<std::array<double, 3>, 4> d;
    for (int i = 0; i < 4; ++i) d[i] = {double(p[i].x), double(p[i].y), double(p[i].z)};
    double volume = 0;
    std::array<double, 3> centroid{};
    const Mat3 ref = tonon_inertia(d, 1.5, volume, centroid);
    if (volume < 0.02) continue;  // slivers are the flatness tests' business
    auto r = ConvexHull::create(std::vector<Vec3>(p.begin(), p.end()));
    ASSERT_TRUE(r.ok()) << r.error().what();
    const MassProperties m = r->mass_properties(Real(1.5));
    const Real rel = Real(2048) * kEps / Real(volume);
    EXPECT_NEAR(m.volume, Real(volume), rel * Real(volume));
    expect_vec_near(m.centroid, Vec3(Real(centroid[0]), Real(centroid[1]), Real(centroid[2])), rel * Real(10));
    expect_mat_near(m.inertia, ref, rel * m.mass);
    ++checked;
  }
  EXPECT_GT(checked, 1000);
}

// ---------------------------------------------------------------------------------------
// Invariances.

TEST(ConvexHullMass, TranslationAndDensity) {
  test::Random rng(3);
  std::vector<Vec3> p;
  for (int i = 0; i < 200; ++i) p.push_back(rng.in_ball(Real(1)) * Vec3(1, 2, Real(0.5)));
  const MassProperties a = build(p).mass_properties(Real(1));
  const Vec3 t(Real(7), Real(-3), Real(11));
  for (Vec3& v : p) v += t;
  const MassProperties b = build(p).mass_properties(Real(3));
  const Real tol = Real(1024) * kEps;
  EXPECT_NEAR(b.volume, a.volume, tol * a.volume);
  EXPECT_NEAR(b.mass, Real(3) * a.mass, tol * b.mass);
  expect_vec_near(b.centroid, a.centroid + t, tol * Real(20));
  expect_mat_near(b.inertia, a.inertia * Real(3), tol * b.mass * Real(4));
}

// ---------------------------------------------------------------------------------------
// A square pyramid, where the centroid (h/4 above the base) differs from the mean of the
// vertices (h/5): V = a^2 h / 3, Ixx = Iyy = m (a^2/20 + 3 h^2/80), Izz = m a^2 / 10.

TEST(ConvexHullMass, SquarePyramidMatchesClosedForm) {
  const Real a = Real(2);
  const Real hgt = Real(3);
  const Vec3 base(Real(1), Real(-2), Real(0.5));
  const std::vector<Vec3> p{base + Vec3(-1, -1, 0), base + Vec3(1, -1, 0), base + Vec3(1, 1, 0), base + Vec3(-1, 1, 0),
                            base + Vec3(0, 0, hgt)};
  const MassProperties m = build(p).mass_properties(Real(2));
  const Real volume = a * a * hgt / Real(3);
  EXPECT_NEAR(m.volume, volume, Real(64) * kEps * volume);
  expect_vec_near(m.centroid, base + Vec3(0, 0, hgt / Real(4)), Real(64) * kEps * hgt);
  const Real ixx = m.mass * (a * a / Real(20) + Real(3) * hgt * hgt / Real(80));
  const Real izz = m.mass * a * a / Real(10);
  expect_mat_near(m.inertia, Mat3(Vec3(ixx, 0, 0), Vec3(0, ixx, 0), Vec3(0, 0, izz)),
                  Real(64) * kEps * m.mass * hgt * hgt);
}

// ---------------------------------------------------------------------------------------
// Quasi-Monte-Carlo integration over contains (Halton points, randomly shifted).

double radical_inverse(int base, long i) {
  double f = 1, r = 0;
  while (i > 0) {
    f /= base;
    r += f * double(i % base);
    i /= base;
  }
  return r;
}

TEST(ConvexHullMass, MatchesQuasiMonteCarloIntegrationOfContains) {
  test::Random rng(4);
  for (int cloud = 0; cloud < 3; ++cloud) {
    SCOPED_TRACE(cloud);
    std::vector<Vec3> p;
    for (int i = 0; i < 150; ++i) {
      if (cloud == 0) p.push_back(rng.unit_vector() * Vec3(Real(1), Real(1.5), Real(0.7)));
      if (cloud == 1) p.push_back(rng.vec3(Real(-1), Real(1)) * Vec3(Real(0.5), Real(1), Real(2)));
      if (cloud == 2) {
        const Vec3 u = rng.unit_vector();
        const Vec3 b = rng.in_ball(Real(1));
        p.push_back(b * Real(0.5) + u * Real(0.8) + Vec3(3, 0, -2));
      }
    }
    const ConvexHull h = build(p);
    const MassProperties m = h.mass_properties(Real(1));
    const Aabb box = h.local_aabb();
    const Vec3 ext = box.extents();
    const double shift[3] = {double(rng.uniform(0, 1)), double(rng.uniform(0, 1)), double(rng.uniform(0, 1))};
    const long n = 200000;
    long inside = 0;
    double sum[3] = {0, 0, 0};
    double second[3][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
    for (long k = 1; k <= n; ++k) {
      double u[3] = {radical_inverse(2, k) + shift[0], radical_inverse(3, k) + shift[1],
                     radical_inverse(5, k) + shift[2]};
      for (double& x : u) x -= std::floor(x);
      const Vec3 q = box.min + Vec3(Real(u[0]), Real(u[1]), Real(u[2])) * ext;
      if (!h.contains(q)) continue;
      ++inside;
      for (int a = 0; a < 3; ++a) {
        sum[a] += double(q[a]);
        for (int b = 0; b < 3; ++b) second[a][b] += double(q[a]) * double(q[b]);
      }
    }
    const double volume = double(box.volume()) * double(inside) / double(n);
    EXPECT_NEAR(double(m.volume), volume, 2e-3 * volume);
    const double c[3] = {sum[0] / double(inside), sum[1] / double(inside), sum[2] / double(inside)};
    const double size = double(h.scale());
    for (int a = 0; a < 3; ++a) EXPECT_NEAR(double(m.centroid[a]), c[a], 1e-3 * size);
    // Inertia about the sampled centroid, at the analytic mass.
    double cov[3][3];
    for (int a = 0; a < 3; ++a) {
      for (int b = 0; b < 3; ++b) cov[a][b] = (second[a][b] / double(inside) - c[a] * c[b]) * double(m.mass);
    }
    const double trace = cov[0][0] + cov[1][1] + cov[2][2];
    for (int a = 0; a < 3; ++a) {
      for (int b = 0; b < 3; ++b) {
        const double ref = (a == b ? trace : 0.0) - cov[a][b];
        EXPECT_NEAR(double(m.inertia[a][b]), ref, 2e-3 * trace);
      }
    }
  }
}

}  // namespace test_convex_hull_mass
}  // namespace proxima
