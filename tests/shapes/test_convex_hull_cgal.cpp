// ConvexHull against CGAL: convex_hull_3 on the Epick kernel, then Polygon Mesh
// Processing's volume and centroid of the resulting mesh, as a second reference for the
// mass properties (and, through the volume, for the hull itself).
#include <gtest/gtest.h>

#include <proxima/core/tolerance.hpp>
#include <proxima/shapes/convex_hull.hpp>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/convex_hull_3.h>

#include <limits>
#include <set>
#include <tuple>
#include <vector>

#include "support/random.hpp"

namespace proxima {
namespace test_convex_hull_cgal {

constexpr Real kEps = std::numeric_limits<Real>::epsilon();

TEST(ConvexHullCgal, VolumeAndCentroidMatchCgal) {
  using K = CGAL::Exact_predicates_inexact_constructions_kernel;
  using Mesh = CGAL::Surface_mesh<K::Point_3>;
  test::Random rng(5);
  for (int k = 0; k < 60; ++k) {
    SCOPED_TRACE(k);
    std::vector<Vec3> p;
    const int n = rng.integer(4, 400);
    const Real scale = k % 3 == 0 ? Real(1e-3) : (k % 3 == 1 ? Real(1) : Real(1e3));
    const Vec3 shift = rng.vec3(Real(-2), Real(2)) * scale;
    for (int i = 0; i < n; ++i) {
      Vec3 v = k % 2 ? rng.unit_vector() : rng.vec3(Real(-1), Real(1));
      if (k % 5 == 0) v = glm::round(v * Real(3)) / Real(3);  // many coplanar points
      p.push_back(v * scale + shift);
    }
    auto r = ConvexHull::create(p);
    if (!r.ok()) {
      EXPECT_EQ(r.error().code, ErrorCode::Degenerate) << r.error().what();
      continue;
    }
    std::vector<K::Point_3> cp;
    for (const Vec3& v : p) cp.emplace_back(double(v.x), double(v.y), double(v.z));
    Mesh mesh;
    CGAL::convex_hull_3(cp.begin(), cp.end(), mesh);
    const double volume = CGAL::to_double(CGAL::Polygon_mesh_processing::volume(mesh));
    const K::Point_3 centroid = CGAL::Polygon_mesh_processing::centroid(mesh);
    // The hull itself: every vertex is one of CGAL's extreme points, and an extreme point
    // that merging within the input's resolution dropped lies within tolerance of the hull.
    std::set<std::tuple<double, double, double>> ours;
    for (const Vec3& v : r->vertices()) ours.insert({double(v.x), double(v.y), double(v.z)});
    std::size_t theirs = 0;
    for (auto vi : mesh.vertices()) {
      const K::Point_3& q = mesh.point(vi);
      ++theirs;
      if (ours.count({q.x(), q.y(), q.z()})) continue;
      const Vec3 qv(Real(q.x()), Real(q.y()), Real(q.z()));
      EXPECT_LE(r->closest_point(qv).signed_distance, r->tolerance()) << "an extreme point lost beyond tolerance";
    }
    std::size_t shared = 0;
    for (auto vi : mesh.vertices()) shared += ours.count({mesh.point(vi).x(), mesh.point(vi).y(), mesh.point(vi).z()});
    EXPECT_EQ(shared, ours.size()) << "a hull vertex that is not one of CGAL's extreme points";
    EXPECT_LE(ours.size(), theirs);
    const MassProperties m = r->mass_properties();
    const double size = double(r->scale());
    // Merging within the hull's tolerance may move the surface by that much.
    const double tol_volume = 64 * double(kEps) * volume + 8 * double(r->tolerance()) * size * size;
    EXPECT_NEAR(double(m.volume), volume, tol_volume);
    const double tol_centroid = 64 * double(kEps) * (size + 2 * double(scale)) + 8 * double(r->tolerance());
    EXPECT_NEAR(double(m.centroid.x), centroid.x(), tol_centroid);
    EXPECT_NEAR(double(m.centroid.y), centroid.y(), tol_centroid);
    EXPECT_NEAR(double(m.centroid.z), centroid.z(), tol_centroid);
  }
}

}  // namespace test_convex_hull_cgal
}  // namespace proxima
