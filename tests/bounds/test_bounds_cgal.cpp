// Exact references from CGAL (when available): the minimal enclosing sphere (Min_sphere_d
// with exact Gmpzf arithmetic) for Welzl, and the exact distance between convex hulls of
// point sets (Polytope_distance_d) for GJK and for the overlap decisions of every pair of
// bounding volumes (each volume = the hull of its core points grown by its radius).
#include <gtest/gtest.h>

#include <proxima/bounds/convex_distance.hpp>
#include <proxima/bounds/fit_sphere.hpp>
#include <proxima/bounds/overlap.hpp>
#include <proxima/core/tolerance.hpp>

#include <variant>
#include <vector>

#include "bounds/test_bounds_reference.hpp"
#include "bounds/test_bounds_support.hpp"
#include "support/random.hpp"

#if PROXIMA_HAVE_CGAL
#include <CGAL/Cartesian.h>
#include <CGAL/Gmpq.h>
#include <CGAL/Gmpzf.h>
#include <CGAL/Homogeneous.h>
#include <CGAL/Min_sphere_annulus_d_traits_3.h>
#include <CGAL/Min_sphere_d.h>
#include <CGAL/Polytope_distance_d.h>
#include <CGAL/Polytope_distance_d_traits_3.h>
#endif

namespace proxima {
namespace test_bounds_cgal {

#if PROXIMA_HAVE_CGAL
using K = CGAL::Homogeneous<double>;
using CPoint = K::Point_3;
using ET = CGAL::Gmpzf;
// Exact rationals throughout for the sphere (with double as the inner number type the
// algorithm goes wrong for clouds far from the origin).
using KQ = CGAL::Cartesian<CGAL::Gmpq>;
using SphereTraits = CGAL::Min_sphere_annulus_d_traits_3<KQ>;
using MinSphere = CGAL::Min_sphere_d<SphereTraits>;
using DistanceTraits = CGAL::Polytope_distance_d_traits_3<K, ET, double>;
using PolytopeDistance = CGAL::Polytope_distance_d<DistanceTraits>;

double cgal_min_radius(const std::vector<Vec3>& pts) {
  std::vector<KQ::Point_3> p;
  for (const Vec3& q : pts) p.emplace_back(CGAL::Gmpq(double(q.x)), CGAL::Gmpq(double(q.y)), CGAL::Gmpq(double(q.z)));
  MinSphere ms(p.begin(), p.end());
  return std::sqrt(CGAL::to_double(ms.squared_radius()));
}

double cgal_distance(const std::vector<test::D3>& a, const std::vector<test::D3>& b) {
  std::vector<CPoint> p, q;
  for (const test::D3& x : a) p.emplace_back(x.x, x.y, x.z);
  for (const test::D3& x : b) q.emplace_back(x.x, x.y, x.z);
  PolytopeDistance pd(p.begin(), p.end(), q.begin(), q.end());
  return std::sqrt(CGAL::to_double(pd.squared_distance_numerator()) /
                   CGAL::to_double(pd.squared_distance_denominator()));
}

TEST(BoundsCgal, WelzlMatchesExactMinSphere) {
  const auto sweep = test::make_cloud_sweep(901, 600, 200);
  for (const auto& c : sweep) {
    const double ref = cgal_min_radius(c.points);
    const BoundingSphere s = *fit_sphere_minimal(c.points);
    const double tol = 8.0 * double(kEpsilon) * double(c.magnitude) + 64.0 * double(kEpsilon) * ref;
    EXPECT_NEAR(double(s.radius), ref, tol) << c.label;
  }
}

TEST(BoundsCgal, GjkMatchesExactPolytopeDistance) {
  test::Random rng(902);
  for (int i = 0; i < 1500; ++i) {
    std::vector<Vec3> a, b;
    const Vec3 ca = rng.vec3(-2, 2), cb = rng.vec3(-2, 2);
    for (int k = rng.integer(1, 16); k > 0; --k) a.push_back(ca + rng.vec3(-1, 1));
    for (int k = rng.integer(1, 16); k > 0; --k) b.push_back(cb + rng.vec3(-1, 1));
    std::vector<test::D3> da, db;
    for (const Vec3& p : a) da.push_back(test::D3(p));
    for (const Vec3& p : b) db.push_back(test::D3(p));
    const double ref = cgal_distance(da, db);
    EXPECT_NEAR(double(convex_distance(a, b).distance), ref, 1e-5) << i;
  }
}

template <int K>
void overlaps_against_cgal(std::uint64_t seed, int cases) {
  test::Random rng(seed);
  int decided = 0, total = 0;
  for (int a = 0; a < test::kVolumeTypeCount; ++a) {
    for (int b = a; b < test::kVolumeTypeCount; ++b) {
      for (int i = 0; i < cases; ++i) {
        const auto va = test::make_volume<K>(rng, static_cast<test::VolumeType>(a), Real(1), Vec3(0));
        const auto vb = test::make_volume<K>(rng, static_cast<test::VolumeType>(b), Real(1), Vec3(0));
        const double d = cgal_distance(va.ref.core, vb.ref.core) - va.ref.radius - vb.ref.radius;
        const bool got = std::visit([](const auto& x, const auto& y) { return overlaps(x, y); }, va.volume, vb.volume);
        ++total;
        if (d < -1e-4) {
          EXPECT_TRUE(got) << test::volume_name(static_cast<test::VolumeType>(a)) << "-"
                           << test::volume_name(static_cast<test::VolumeType>(b)) << " case " << i << " d " << d;
          ++decided;
        } else if (d > 1e-4) {
          EXPECT_FALSE(got) << test::volume_name(static_cast<test::VolumeType>(a)) << "-"
                            << test::volume_name(static_cast<test::VolumeType>(b)) << " case " << i << " d " << d;
          ++decided;
        }
      }
    }
  }
  // Only polytope pairs that overlap by less than 1e-4 are undecided (distance 0 exactly).
  EXPECT_GT(decided, total * 6 / 10);
}

TEST(BoundsCgal, OverlapsMatchExactDistanceKdop14) { overlaps_against_cgal<14>(903, 120); }
TEST(BoundsCgal, OverlapsMatchExactDistanceKdop26) { overlaps_against_cgal<26>(904, 60); }

#else
TEST(BoundsCgal, NotAvailable) { GTEST_SKIP() << "CGAL not found: exact references skipped"; }
#endif

}  // namespace test_bounds_cgal
}  // namespace proxima
