// Bounding-volume types: validation per field, volume against analytic values and
// Monte-Carlo integration, containment against analytic predicates, k-DOP vertices against
// the slab definitions and the fitted points.
#include <gtest/gtest.h>

#include <proxima/bounds/bounding_capsule.hpp>
#include <proxima/bounds/bounding_sphere.hpp>
#include <proxima/bounds/fit_kdop.hpp>
#include <proxima/bounds/kdop.hpp>
#include <proxima/bounds/obb.hpp>
#include <proxima/core/tolerance.hpp>

#include <cmath>
#include <limits>
#include <vector>

#include "bounds/test_bounds_support.hpp"
#include "support/random.hpp"

namespace proxima {
namespace test_bounds_types {

const Real kNan = std::numeric_limits<Real>::quiet_NaN();
const Real kInf = std::numeric_limits<Real>::infinity();

TEST(BoundsTypes, SphereValidation) {
  test::ScopedNoFpTraps no_traps;
  EXPECT_TRUE(BoundingSphere::create(Vec3(1, 2, 3), Real(0)).ok());
  auto a = BoundingSphere::create(Vec3(0, kNan, 0), Real(1));
  ASSERT_FALSE(a.ok());
  EXPECT_EQ(a.error().field, "center.y");
  EXPECT_EQ(a.error().code, ErrorCode::NotFinite);
  auto b = BoundingSphere::create(Vec3(0), Real(-1));
  EXPECT_EQ(b.error().field, "radius");
  EXPECT_EQ(b.error().code, ErrorCode::Negative);
  EXPECT_EQ(BoundingSphere::create(Vec3(0), kInf).error().code, ErrorCode::NotFinite);
}

TEST(BoundsTypes, ObbValidation) {
  test::ScopedNoFpTraps no_traps;
  const Mat3 id(Real(1));
  EXPECT_TRUE(Obb::create(Vec3(0), id, Vec3(1, 0, 2)).ok());
  EXPECT_EQ(Obb::create(Vec3(kInf, 0, 0), id, Vec3(1)).error().field, "center.x");
  Mat3 bad = id;
  bad[1].z = kNan;
  EXPECT_EQ(Obb::create(Vec3(0), bad, Vec3(1)).error().field, "axes[1].z");
  Mat3 skew = id;
  skew[1] = Vec3(Real(0.1), 1, 0);
  auto s = Obb::create(Vec3(0), skew, Vec3(1));
  EXPECT_EQ(s.error().field, "axes");
  EXPECT_EQ(s.error().code, ErrorCode::InvalidArgument);
  Mat3 longer = id;
  longer[2] = Vec3(0, 0, 2);
  EXPECT_EQ(Obb::create(Vec3(0), longer, Vec3(1)).error().field, "axes");
  auto h = Obb::create(Vec3(0), id, Vec3(1, -1, 1));
  EXPECT_EQ(h.error().field, "half_extents.y");
  EXPECT_EQ(h.error().code, ErrorCode::Negative);
  // Slightly non-orthonormal axes are accepted and re-orthonormalised (handedness kept).
  Mat3 near = id;
  near[1] = Vec3(Real(1e-4), 1, 0);
  near[2] = Vec3(0, 0, -1);
  auto n = Obb::create(Vec3(0), near, Vec3(1));
  ASSERT_TRUE(n.ok());
  EXPECT_NEAR(glm::dot(n->axes[0], n->axes[1]), Real(0), Real(1e-6));
  EXPECT_LT(glm::dot(glm::cross(n->axes[0], n->axes[1]), n->axes[2]), Real(0));
}

TEST(BoundsTypes, CapsuleValidation) {
  test::ScopedNoFpTraps no_traps;
  EXPECT_TRUE(BoundingCapsule::create(Vec3(0), Vec3(0), Real(0)).ok());
  EXPECT_EQ(BoundingCapsule::create(Vec3(kNan), Vec3(0), Real(1)).error().field, "p0.x");
  EXPECT_EQ(BoundingCapsule::create(Vec3(0), Vec3(0, 0, kInf), Real(1)).error().field, "p1.z");
  EXPECT_EQ(BoundingCapsule::create(Vec3(0), Vec3(1), Real(-2)).error().field, "radius");
}

TEST(BoundsTypes, KdopValidation) {
  test::ScopedNoFpTraps no_traps;
  std::array<Real, 7> lo{-1, -1, -1, -3, -3, -3, -3};
  std::array<Real, 7> hi{1, 1, 1, 3, 3, 3, 3};
  EXPECT_TRUE(Kdop14::create(lo, hi).ok());
  auto l = lo;
  l[3] = kNan;
  EXPECT_EQ(Kdop14::create(l, hi).error().field, "min[3]");
  auto h = hi;
  h[0] = kInf;
  EXPECT_EQ(Kdop14::create(lo, h).error().field, "max[0]");
  h = hi;
  h[2] = Real(-2);
  auto inv = Kdop14::create(lo, h);
  EXPECT_EQ(inv.error().field, "max[2]");
  EXPECT_EQ(inv.error().code, ErrorCode::InvalidArgument);
  // Consistent slabs, empty intersection: x, y, z in [-1, 1] but x + y + z >= 5.
  l = lo;
  h = hi;
  l[3] = Real(5);
  h[3] = Real(6);
  auto empty = Kdop14::create(l, h);
  ASSERT_FALSE(empty.ok());
  EXPECT_EQ(empty.error().code, ErrorCode::Degenerate);
  EXPECT_EQ(empty.error().field, "max");
}

TEST(BoundsTypes, AnalyticVolumes) {
  const Real tol = Real(1e-5);
  EXPECT_NEAR((BoundingSphere{Vec3(3), Real(2)}.volume()), Real(32) / 3 * kPi, tol * 40);
  EXPECT_NEAR((Obb{Vec3(1), Mat3(Real(1)), Vec3(1, 2, 3)}.volume()), Real(48), tol * 50);
  EXPECT_NEAR((BoundingCapsule{Vec3(0), Vec3(0, 0, 4), Real(1)}.volume()), kPi * (4 + Real(4) / 3), tol * 20);
  // 6-DOP = box.
  Kdop6 box;
  box.grow(Vec3(-1, -2, -3));
  box.grow(Vec3(1, 2, 3));
  EXPECT_NEAR(box.volume(), Real(48), tol * 50);
  // 18-DOP of a cube's corners = the cube (edge planes touch only its edges).
  std::vector<Vec3> cube;
  for (int k = 0; k < 8; ++k) cube.push_back(Vec3(k & 1 ? 1 : -1, k & 2 ? 1 : -1, k & 4 ? 1 : -1));
  EXPECT_NEAR(fit_kdop<18>(cube)->volume(), Real(8), tol * 10);
  EXPECT_NEAR(fit_kdop<26>(cube)->volume(), Real(8), tol * 10);
  // 14-DOP of the cube with |x + y + z| <= 2 etc.: each corner loses a tetrahedron of
  // legs 1 (volume 1/6).
  Kdop14 cut = *fit_kdop<14>(cube);
  for (int i = 3; i < 7; ++i) {
    cut.min[i] = Real(-2);
    cut.max[i] = Real(2);
  }
  EXPECT_NEAR(cut.volume(), Real(8) - Real(8) / 6, tol * 10);
  EXPECT_EQ(cut.vertices().size(), 12u);  // the cuboctahedron: the 12 edge midpoints
  // Flat and single-point k-DOPs have zero volume.
  const std::vector<Vec3> flat{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}};
  EXPECT_NEAR(fit_kdop<26>(flat)->volume(), Real(0), tol);
  const std::vector<Vec3> one{{5, 5, 5}};
  EXPECT_EQ(fit_kdop<26>(one)->volume(), Real(0));
  EXPECT_EQ(Kdop26().volume(), Real(0));
  EXPECT_TRUE(Kdop26().is_empty());
  EXPECT_TRUE(Kdop26().vertices().empty());
}

// Monte-Carlo volume of a predicate inside a box.
template <class Pred>
double monte_carlo_volume(const Aabb& box, Pred&& inside, int samples, std::uint64_t seed) {
  test::Random rng(seed);
  int hits = 0;
  for (int i = 0; i < samples; ++i) {
    const Real z = rng.uniform(box.min.z, box.max.z);
    const Real y = rng.uniform(box.min.y, box.max.y);
    const Real x = rng.uniform(box.min.x, box.max.x);
    if (inside(Vec3(x, y, z))) ++hits;
  }
  return double(box.volume()) * hits / samples;
}

template <int K>
void check_kdop_against_points(std::uint64_t seed, int clouds) {
  test::Random rng(seed);
  for (int c = 0; c < clouds; ++c) {
    const auto kind =
        c % 3 == 0 ? test::CloudKind::Sphere : (c % 3 == 1 ? test::CloudKind::Uniform : test::CloudKind::Gaussian);
    const Vec3 offset = c % 4 == 3 ? Vec3(Real(1e4), Real(2e3), Real(-1e4)) : Vec3(0);
    const auto pts = test::make_cloud(rng, kind, rng.integer(4, 40), Real(1), offset);
    const Kdop<K> k = *fit_kdop<K>(pts);
    for (const Vec3& p : pts) ASSERT_TRUE(k.contains(p));
    const std::vector<Vec3> v = k.vertices();
    ASSERT_GE(v.size(), 4u);
    Real mag = Real(0);
    for (const Vec3& p : pts) mag = std::max({mag, std::abs(p.x), std::abs(p.y), std::abs(p.z)});
    const Real tol = test::abs_tol(Real(2), mag);
    // (a) every vertex lies in every slab; (b) each bound is attained by a vertex.
    for (int i = 0; i < K / 2; ++i) {
      Real lo = kRealMax, hi = -kRealMax;
      for (const Vec3& q : v) {
        const Real s = Kdop<K>::project(i, q);
        EXPECT_GE(s, k.min[i] - tol);
        EXPECT_LE(s, k.max[i] + tol);
        lo = std::min(lo, s);
        hi = std::max(hi, s);
      }
      EXPECT_NEAR(lo, k.min[i], tol);
      EXPECT_NEAR(hi, k.max[i], tol);
    }
    // (c) the vertices' hull contains the points: support over vertices dominates.
    for (int d = 0; d < 50; ++d) {
      const Vec3 dir = rng.unit_vector();
      Real sv = -kRealMax, sp = -kRealMax;
      for (const Vec3& q : v) sv = std::max(sv, glm::dot(q, dir));
      for (const Vec3& q : pts) sp = std::max(sp, glm::dot(q, dir));
      EXPECT_GE(sv, sp - tol);
    }
    // (d) volume against Monte Carlo (only near the origin, where float sampling is fine).
    if (c % 4 != 3 && c < 12) {
      const Aabb box = k.aabb();
      const double mc = monte_carlo_volume(
          box, [&](const Vec3& p) { return k.contains(p); }, 100000, seed + c);
      EXPECT_NEAR(double(k.volume()), mc, 0.015 * double(box.volume()) + 1e-9) << "K=" << K << " cloud " << c;
    }
  }
}

TEST(BoundsTypes, Kdop6VerticesAndVolume) { check_kdop_against_points<6>(11, 60); }
TEST(BoundsTypes, Kdop14VerticesAndVolume) { check_kdop_against_points<14>(12, 60); }
TEST(BoundsTypes, Kdop18VerticesAndVolume) { check_kdop_against_points<18>(13, 60); }
TEST(BoundsTypes, Kdop26VerticesAndVolume) { check_kdop_against_points<26>(14, 60); }

TEST(BoundsTypes, ContainsMatchesAnalyticPredicates) {
  test::Random rng(21);
  for (int i = 0; i < 3000; ++i) {
    const Vec3 c = rng.vec3(Real(-5), Real(5));
    const Mat3 axes = glm::mat3_cast(rng.rotation());
    const Vec3 h = rng.vec3(Real(0.1), Real(2));
    const Obb box{c, axes, h};
    const BoundingSphere s{c, h.x};
    const BoundingCapsule cap{c, c + axes[0] * h.y, h.z};
    // Points at box coordinates u: inside iff every |u_i| <= h_i; keep away from the surface.
    const Vec3 u = rng.vec3(Real(-3), Real(3));
    const Vec3 p = c + axes * u;
    bool in_box = true, near_box = false;
    for (int k = 0; k < 3; ++k) {
      in_box = in_box && std::abs(u[k]) <= h[k];
      near_box = near_box || std::abs(std::abs(u[k]) - h[k]) < Real(1e-3);
    }
    if (!near_box) {
      EXPECT_EQ(box.contains(p), in_box);
    }
    const Real ds = glm::length(p - c);
    if (std::abs(ds - h.x) > Real(1e-3)) {
      EXPECT_EQ(s.contains(p), ds <= h.x);
    }
    // Capsule: distance to the segment by dense sampling of the segment.
    Real dseg = kRealMax;
    for (int k = 0; k <= 2000; ++k) dseg = std::min(dseg, glm::length(p - (c + axes[0] * (h.y * Real(k) / 2000))));
    if (std::abs(dseg - h.z) > Real(5e-3)) {
      EXPECT_EQ(cap.contains(p), dseg <= h.z);
    }
  }
}

TEST(BoundsTypes, ObbCornersSupportAndBox) {
  test::Random rng(22);
  for (int i = 0; i < 1000; ++i) {
    const Obb box{rng.vec3(Real(-5), Real(5)), glm::mat3_cast(rng.rotation()), rng.vec3(Real(0), Real(2))};
    const auto corners = box.corners();
    const Aabb aabb = box.aabb();
    const Vec3 d = rng.unit_vector();
    Real best = -kRealMax;
    for (const Vec3& c : corners) {
      EXPECT_TRUE(aabb.inflated(Real(1e-4)).contains(c));
      best = std::max(best, glm::dot(c, d));
    }
    EXPECT_NEAR(glm::dot(box.support(d), d), best, Real(1e-4));
    // The box of the corners is tight.
    Aabb ref = Aabb::from_point(corners[0]);
    for (const Vec3& c : corners) ref.grow(c);
    for (int k = 0; k < 3; ++k) {
      EXPECT_NEAR(aabb.min[k], ref.min[k], Real(1e-4));
      EXPECT_NEAR(aabb.max[k], ref.max[k], Real(1e-4));
    }
  }
}

}  // namespace test_bounds_types
}  // namespace proxima
