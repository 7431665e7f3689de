// The polytope SAT fall-back: exact penetration depth and normal of Box, ConvexHull,
// Triangle, Segment and Point pairs against an exhaustive, unpruned axis search in double;
// the Gauss-map pruning never drops the deciding axis.
#include <gtest/gtest.h>

#include <proxima/shapes/shape.hpp>

#include <cmath>

#include "gjk_reference.hpp"
#include "narrowphase/generic_distance.hpp"
#include "narrowphase/polytope_sat.hpp"
#include "support/random.hpp"

namespace proxima {
namespace test_polytope_sat {

namespace ref = test::gjkref;
using narrow::polytope_sat;
using narrow::PolytopeView;

Real tol_at(Real s) { return (sizeof(Real) == 4 ? Real(2e-4) : Real(1e-9)) * std::max(Real(1), s); }

// SAT of (a, pa) and (b, pb) through the A-frame interface.
template <class A, class B>
narrow::SatResult run(const A& a, const Transform& pa, const B& b, const Transform& pb) {
  const Transform rel = relative(pa, pb);
  const PolytopeView va(a);
  const PolytopeView vb(b);
  return polytope_sat(va, vb, glm::mat3_cast(rel.rotation), rel.position);
}

// Exhaustive separation over generic axes for any polytope shapes via their supports.
template <class A, class B>
double exhaustive(const A& a, const Transform& pa, const B& b, const Transform& pb, const std::vector<ref::V>& axes) {
  double best = -1e300;
  for (const ref::V& l : axes) {
    const double n = ref::norm(l);
    if (!(n > 1e-9)) continue;
    const ref::V u = (1.0 / n) * l;
    best = std::max({best, ref::support_gap(a, pa, b, pb, u), ref::support_gap(a, pa, b, pb, -1.0 * u)});
  }
  return best;
}

TEST(PolytopeSat, HullAndBoxPairsMatchExhaustiveSearch) {
  test::Random rng(31);
  int overlapping = 0;
  for (int t = 0; t < 1500; ++t) {
    const ConvexHull a = ref::random_hull(rng, rng.integer(4, 40), Real(0.6));
    const Box b = Box::create(rng.vec3(Real(0.1), Real(0.6))).value();
    const Transform pa = rng.pose(Real(0.6));
    const Transform pb = rng.pose(Real(0.6));
    const narrow::SatResult s = t % 2 ? run(a, pa, b, pb) : run(b, pb, a, pa);
    const double expected = t % 2 ? ref::polytope_sat_exhaustive(ref::world_poly(a, pa), ref::world_poly(b, pb))
                                  : ref::polytope_sat_exhaustive(ref::world_poly(b, pb), ref::world_poly(a, pa));
    ASSERT_TRUE(s.valid);
    if (expected < 0) {
      ++overlapping;
      EXPECT_NEAR(s.signed_distance, expected, tol_at(2)) << "case " << t;
    } else {
      // Separated: the pruned SAT gives a valid lower bound (> 0 proves separation).
      EXPECT_LE(s.signed_distance, expected + tol_at(2)) << "case " << t;
    }
    EXPECT_NEAR(glm::length(s.normal), 1, 1e-4);
    EXPECT_LT(glm::length(s.point_b - (s.point_a + s.signed_distance * s.normal)), tol_at(2));
  }
  EXPECT_GT(overlapping, 500);
}

TEST(PolytopeSat, HullHullPairsMatchExhaustiveSearch) {
  test::Random rng(32);
  for (int t = 0; t < 800; ++t) {
    const ConvexHull a = ref::random_hull(rng, rng.integer(4, 30), Real(0.6));
    const ConvexHull b = ref::random_hull(rng, rng.integer(4, 30), Real(0.6));
    const Transform pa = rng.pose(Real(0.4));
    const Transform pb = rng.pose(Real(0.4));
    const narrow::SatResult s = run(a, pa, b, pb);
    const double expected = ref::polytope_sat_exhaustive(ref::world_poly(a, pa), ref::world_poly(b, pb));
    if (expected < 0) {
      EXPECT_NEAR(s.signed_distance, expected, tol_at(2)) << "case " << t;
    }
  }
}

TEST(PolytopeSat, FlatAndLowerDimensionalPolytopes) {
  test::Random rng(33);
  const Point point = Point::create().value();
  for (int t = 0; t < 600; ++t) {
    const Vec3 tc = rng.vec3(-1, 1);
    const Vec3 tb = rng.vec3(-1, 1);
    const Triangle tri = Triangle::create(rng.vec3(-1, 1), tb, tc).value();
    const Vec3 sb = rng.vec3(-1, 1);
    const Segment seg = Segment::create(rng.vec3(-1, 1), sb).value();
    const Box box = Box::create(rng.vec3(Real(0.2), Real(0.8))).value();
    const Transform pa = rng.pose(Real(0.5));
    const Transform pb = rng.pose(Real(0.5));
    // Axes of the exhaustive search in the world frame.
    std::vector<ref::V> axes;
    const ref::V tn = ref::v(pa.apply_vector(tri.normal()));
    axes.push_back(tn);
    std::vector<ref::V> tri_edges, box_edges;
    for (int i = 0; i < 3; ++i) tri_edges.push_back(ref::v(pa.apply_vector(tri.vertex((i + 1) % 3) - tri.vertex(i))));
    for (int i = 0; i < 3; ++i) {
      Vec3 e(0);
      e[i] = 1;
      box_edges.push_back(ref::v(pb.apply_vector(e)));
      axes.push_back(box_edges.back());
    }
    for (const auto& e0 : tri_edges)
      for (const auto& e1 : box_edges) axes.push_back(ref::cross(e0, e1));
    const narrow::SatResult s = run(tri, pa, box, pb);
    const double expected = exhaustive(tri, pa, box, pb, axes);
    ASSERT_TRUE(s.valid);
    EXPECT_NEAR(s.signed_distance, expected, tol_at(2)) << "triangle-box " << t;
    // Segment against the box: box faces and segment x box edges.
    std::vector<ref::V> seg_axes(box_edges);
    const ref::V sd = ref::v(pa.apply_vector(seg.b() - seg.a()));
    for (const auto& e1 : box_edges) seg_axes.push_back(ref::cross(sd, e1));
    const narrow::SatResult ss = run(seg, pa, box, pb);
    EXPECT_NEAR(ss.signed_distance, exhaustive(seg, pa, box, pb, seg_axes), tol_at(2)) << "segment-box " << t;
    // Point against the box: the box faces.
    const narrow::SatResult ps = run(point, pa, box, pb);
    EXPECT_NEAR(ps.signed_distance, exhaustive(point, pa, box, pb, box_edges), tol_at(2)) << "point-box " << t;
  }
  // Two points have no axis: no answer (the caller falls back to GJK's contact).
  EXPECT_FALSE(run(point, Transform{}, point, Transform{}).valid);
}

TEST(PolytopeSat, GenericRoutineUsesSatWhenEpaCannotAnswer) {
  // A starved EPA (four faces) cannot expand: the SAT gives the exact depth, method Sat.
  const Box box = Box::create(Vec3(0.5, 0.4, 0.3)).value();
  test::Random rng(34);
  PairRequest starved;
  starved.max_epa_faces = 4;
  int sat_answers = 0;
  for (int t = 0; t < 200; ++t) {
    const Transform pa = rng.pose(Real(0.3));
    const Transform pb = rng.pose(Real(0.3));
    const double expected = ref::polytope_sat_exhaustive(ref::world_poly(box, pa), ref::world_poly(box, pb));
    if (expected > -1e-3) continue;
    const DistanceResult d = narrow::generic_distance(box, pa, box, pb, starved, nullptr);
    sat_answers += d.method == PairMethod::Sat;
    EXPECT_NEAR(d.signed_distance, expected, tol_at(2)) << t;
  }
  EXPECT_GT(sat_answers, 50);
  // Coplanar overlapping triangles (a flat Minkowski difference): depth 0 along the normal.
  const Triangle tri = Triangle::create(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)).value();
  Transform pb;
  pb.position = Vec3(0.2f, 0.2f, 0);
  const DistanceResult d = narrow::generic_distance(tri, Transform{}, tri, pb, {}, nullptr);
  EXPECT_NEAR(d.signed_distance, 0, tol_at(1));
  EXPECT_NEAR(std::abs(d.normal.z), 1, 1e-3);
}

}  // namespace test_polytope_sat
}  // namespace proxima
