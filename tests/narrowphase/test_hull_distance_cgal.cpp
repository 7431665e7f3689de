// The narrow phase's distance between polyhedral shapes (point, segment, triangle, box,
// convex hull: every pair of them, both orders) against CGAL's exact Polytope_distance_d on
// the shapes' world-frame vertices (Gmpzf arithmetic). Apart, the signed distance must
// match the exact distance; when CGAL's distance is zero (the polytopes meet), ours must
// be <= the tolerance.
#include <gtest/gtest.h>

#include <CGAL/Gmpzf.h>
#include <CGAL/Homogeneous.h>
#include <CGAL/Polytope_distance_d.h>
#include <CGAL/Polytope_distance_d_traits_3.h>

#include <iostream>
#include <string>
#include <vector>

#include "narrowphase/narrowphase_test_util.hpp"

namespace proxima {
namespace test_hull_distance_cgal {

using K = CGAL::Homogeneous<double>;
using CPoint = K::Point_3;
using DistanceTraits = CGAL::Polytope_distance_d_traits_3<K, CGAL::Gmpzf, double>;
using PolytopeDistance = CGAL::Polytope_distance_d<DistanceTraits>;

// World-frame vertices of a polyhedral shape.
std::vector<CPoint> world_vertices(const Shape& shape, const Transform& pose) {
  std::vector<Vec3> local;
  if (std::holds_alternative<Point>(shape)) local.push_back(Vec3(Real(0)));
  if (const auto* s = std::get_if<Segment>(&shape)) local = {s->a(), s->b()};
  if (const auto* t = std::get_if<Triangle>(&shape)) local = {t->a(), t->b(), t->c()};
  if (const auto* b = std::get_if<Box>(&shape)) {
    const Vec3 h = b->half_extents();
    for (int i = 0; i < 8; ++i) local.push_back(Vec3((i & 1) ? h.x : -h.x, (i & 2) ? h.y : -h.y, (i & 4) ? h.z : -h.z));
  }
  if (const auto* hull = std::get_if<ConvexHull>(&shape))
    local.assign(hull->vertices().begin(), hull->vertices().end());
  std::vector<CPoint> out;
  for (const Vec3& v : local) {
    const Vec3 w = pose.apply(v);
    out.emplace_back(double(w.x), double(w.y), double(w.z));
  }
  return out;
}

double exact_distance(const std::vector<CPoint>& p, const std::vector<CPoint>& q) {
  PolytopeDistance pd(p.begin(), p.end(), q.begin(), q.end());
  return std::sqrt(CGAL::to_double(pd.squared_distance_numerator()) /
                   CGAL::to_double(pd.squared_distance_denominator()));
}

TEST(HullDistanceCgal, PolyhedralPairsMatchExactPolytopeDistance) {
  const std::vector<ShapeType> types = {ShapeType::Point, ShapeType::Segment, ShapeType::Triangle, ShapeType::Box,
                                        ShapeType::ConvexHull};
#ifdef NDEBUG
  const int cases = 120;
#else
  const int cases = 20;
#endif
  int apart = 0;
  int meeting = 0;
  for (ShapeType ta : types) {
    for (ShapeType tb : types) {
      test::Random rng(7000 + std::uint64_t(ta) * 16u + std::uint64_t(tb));
      int failures = 0;
      for (int i = 0; i < cases; ++i) {
        const Shape a = test::random_shape(rng, ta);
        const Shape b = test::random_shape(rng, tb);
        const Transform pa = rng.pose(Real(0.5));
        const Transform pb = rng.pose(Real(1.8));
        const double exact = exact_distance(world_vertices(a, pa), world_vertices(b, pb));
        const DistanceResult d = distance(a, pa, b, pb);
        const double tol =
            double(test::narrow_tolerance(std::max({test::shape_scale(a), test::shape_scale(b), Real(1)})));
        const std::string where = "A=" + test::describe(a, pa) + " B=" + test::describe(b, pb);
        if (exact > 0) {
          ++apart;
          if (std::abs(double(d.signed_distance) - exact) > tol && failures++ < 3) {
            ADD_FAILURE() << "distance " << d.signed_distance << " exact " << exact << " " << where;
          }
        } else {
          ++meeting;
          if (double(d.signed_distance) > tol && failures++ < 3) {
            ADD_FAILURE() << "distance " << d.signed_distance << " but CGAL finds them meeting " << where;
          }
        }
      }
      EXPECT_EQ(failures, 0) << to_string(ta) << "-" << to_string(tb);
    }
  }
  std::cout << "[cgal] polyhedral pairs: " << apart << " apart, " << meeting << " meeting\n";
  EXPECT_GT(apart, 0);
  EXPECT_GT(meeting, 0);
}

}  // namespace test_hull_distance_cgal
}  // namespace proxima
