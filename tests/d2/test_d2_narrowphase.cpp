/// @file test_d2_narrowphase.cpp
/// The 2D narrow phase on every pair of convex kinds against the long-double references of
/// d2_reference.hpp (Minkowski-difference hulls): signed distance, witnesses, intersect,
/// manifolds; plus analytic cases and named regressions.

#include <gtest/gtest.h>

#include <proxima/d2/narrowphase.hpp>

#include <array>
#include <string>
#include <utility>
#include <vector>

#include "d2/d2_reference.hpp"
#include "sweep_size.hpp"

namespace proxima::d2 {
namespace {

using test::LD;
using test::RefPose;

using test::kConvexKinds;

/// Distance tolerance at coordinate scale `scale`.
Real tolerance(Real scale) { return (sizeof(Real) == 4 ? Real(2e-5) : Real(1e-10)) * (Real(1) + scale); }

/// A random pair near contact: A near the origin, B along a random direction at 0.2..1.4
/// times the sum of the sizes.
struct RandomPair {
  test::RandomShape a, b;
  RefPose pa, pb;
};

RandomPair random_pair(proxima::test::Random& rng, ShapeType ta, ShapeType tb) {
  const Real size_a = rng.uniform(Real(0.3), Real(2));
  const Real size_b = rng.uniform(Real(0.3), Real(2));
  RandomPair p{test::random_shape(rng, ta, size_a), test::random_shape(rng, tb, size_b), {}, {}};
  p.pa = {rng.uniform(Real(-1), Real(1)), rng.uniform(Real(-1), Real(1)), rng.uniform(Real(-3.2), Real(3.2))};
  const Real angle = rng.uniform(Real(-3.2), Real(3.2));
  const Real reach = rng.uniform(Real(0.1), Real(1.3)) * (size_a + size_b);
  p.pb = {p.pa.x + reach * std::cos(angle), p.pa.y + reach * std::sin(angle), rng.uniform(Real(-3.2), Real(3.2))};
  return p;
}

std::string pair_name(ShapeType a, ShapeType b) { return std::string(to_string(a)) + "-" + to_string(b); }

TEST(D2Distance, EveryConvexPairMatchesTheMinkowskiHull) {
  proxima::test::Random rng(0xD2D15);
  const int per_pair = proxima::test::sweep_size(800);
  for (ShapeType ta : kConvexKinds) {
    for (ShapeType tb : kConvexKinds) {
      int overlapping = 0;
      for (int i = 0; i < per_pair; ++i) {
        const RandomPair p = random_pair(rng, ta, tb);
        const LD expected = test::signed_distance(p.a.ref, p.pa, p.b.ref, p.pb);
        const DistanceResult r = distance(p.a.shape, p.pa.pose(), p.b.shape, p.pb.pose());
        const Real tol = tolerance(Real(8));
        ASSERT_NEAR(r.signed_distance, static_cast<Real>(expected), tol) << pair_name(ta, tb) << " case " << i;
        overlapping += expected < 0;
        // Witnesses: on their surfaces, joined by signed_distance * normal.
        ASSERT_NEAR(glm::length(r.normal), Real(1), Real(1e-5)) << pair_name(ta, tb) << " case " << i;
        const Vec2 gap = r.point_b - r.point_a - r.signed_distance * r.normal;
        ASSERT_LE(glm::length(gap), tol) << pair_name(ta, tb) << " case " << i;
        const LD on_a = test::point_signed_distance(p.a.ref, p.pa, {r.point_a.x, r.point_a.y});
        const LD on_b = test::point_signed_distance(p.b.ref, p.pb, {r.point_b.x, r.point_b.y});
        ASSERT_NEAR(static_cast<Real>(on_a), Real(0), Real(4) * tol) << pair_name(ta, tb) << " case " << i;
        ASSERT_NEAR(static_cast<Real>(on_b), Real(0), Real(4) * tol) << pair_name(ta, tb) << " case " << i;
        // intersect agrees outside the tolerance band.
        if (std::abs(expected) > 4 * tol) {
          ASSERT_EQ(intersect(p.a.shape, p.pa.pose(), p.b.shape, p.pb.pose()), expected < 0) << pair_name(ta, tb);
        }
      }
      const auto solid = [](ShapeType t) { return t != ShapeType::Point && t != ShapeType::Segment; };
      if (solid(ta) || solid(tb)) {
        EXPECT_GT(overlapping, per_pair / 20) << pair_name(ta, tb);
      }
    }
  }
}

TEST(D2Distance, SwappingTheShapesMirrorsTheAnswer) {
  proxima::test::Random rng(0xD2D16);
  for (int i = 0; i < proxima::test::sweep_size(2000); ++i) {
    const RandomPair p = random_pair(rng, kConvexKinds[i % 5], kConvexKinds[(i / 5) % 5]);
    const DistanceResult ab = distance(p.a.shape, p.pa.pose(), p.b.shape, p.pb.pose());
    const DistanceResult ba = distance(p.b.shape, p.pb.pose(), p.a.shape, p.pa.pose());
    ASSERT_NEAR(ab.signed_distance, ba.signed_distance, tolerance(Real(8))) << "case " << i;
  }
}

TEST(D2Distance, AnalyticCases) {
  const Shape circle = Circle::create(Real(1)).value();
  const Shape box = Polygon::box(Real(1), Real(2)).value();
  const Shape capsule = Capsule::create({Real(-1), Real(0)}, {Real(1), Real(0)}, Real(0.5)).value();
  // Circles 3 apart: gap 1, normal +x.
  DistanceResult r = distance(circle, Pose::from({0, 0}, 0), circle, Pose::from({3, 0}, 0));
  EXPECT_NEAR(r.signed_distance, Real(1), Real(1e-6));
  EXPECT_NEAR(r.normal.x, Real(1), Real(1e-6));
  EXPECT_EQ(r.status, PairStatus::Separated);
  // A circle sunk 0.25 into the box's top face.
  r = distance(box, Pose::identity(), circle, Pose::from({Real(0.5), Real(2.75)}, 0));
  EXPECT_NEAR(r.signed_distance, Real(-0.25), Real(1e-6));
  EXPECT_NEAR(r.normal.y, Real(1), Real(1e-6));
  EXPECT_EQ(r.status, PairStatus::Penetrating);
  EXPECT_EQ(r.method, PairMethod::Gjk);  // the cores (a point, the box) are apart
  // The circle's centre inside the box: the cores overlap, the SAT gives the depth.
  r = distance(box, Pose::identity(), circle, Pose::from({Real(0.5), Real(1.5)}, 0));
  EXPECT_NEAR(r.signed_distance, Real(-1.5), Real(1e-6));
  EXPECT_EQ(r.method, PairMethod::Sat);
  // A box turned 45 degrees with its corner 0.1 above a capsule.
  const Real corner = std::sqrt(Real(2));
  r = distance(capsule, Pose::identity(), Shape(Polygon::box(1, 1).value()),
               Pose::from({0, Real(0.6) + corner}, kPi / 4));
  EXPECT_NEAR(r.signed_distance, Real(0.1), Real(1e-5));
  EXPECT_NEAR(r.point_a.y, Real(0.5), Real(1e-5));
}

TEST(D2Distance, CoincidentCentresGetTheSumOfTheRadii) {
  const Shape circle = Circle::create(Real(1)).value();
  const DistanceResult r = distance(circle, Pose::from({2, 3}, 0), circle, Pose::from({2, 3}, 1));
  EXPECT_EQ(r.signed_distance, Real(-2));
  EXPECT_NEAR(glm::length(r.normal), Real(1), Real(1e-6));
}

/// Regression: a segment lying on a polygon's edge (the Minkowski difference's boundary
/// through the origin) made GJK cycle to its iteration cap and report the witnesses of an
/// unsolved simplex, a distance of 2.04 for touching shapes.
TEST(D2Distance, TouchingParallelEdgesConverge) {
  proxima::test::Random rng(0x70C4);
  int exact = 0;
  for (int i = 0; i < proxima::test::sweep_size(3000); ++i) {
    // A random polygon and a segment along part of one of its edges, outside it by 0 or by a
    // rounding-level gap, both under one random pose.
    const test::RandomShape a = test::random_shape(rng, ShapeType::Polygon, rng.uniform(Real(0.3), Real(2)));
    const ConvexCore core = a.shape.core();
    const int e = rng.integer(0, core.count - 1);
    const Vec2 p = core.vertices[e], q = core.vertices[(e + 1) % core.count];
    const Real s0 = rng.uniform(Real(-0.5), Real(0.6)), s1 = rng.uniform(Real(0.7), Real(1.5));
    const Shape segment = Segment::create(p + s0 * (q - p), p + s1 * (q - p)).value();
    const Pose pose =
        Pose::from({rng.uniform(Real(-5), Real(5)), rng.uniform(Real(-5), Real(5))}, rng.uniform(Real(-3), Real(3)));
    const DistanceResult r = distance(a.shape, pose, segment, pose);
    ASSERT_NEAR(r.signed_distance, -core.radius, tolerance(Real(8))) << "case " << i;
    ASSERT_LT(r.iterations, 20) << "case " << i;
    exact += r.signed_distance == -core.radius;
  }
  EXPECT_GT(exact, 0);
}

TEST(D2Distance, NonFinitePoseIsInvalidInput) {
  const Shape circle = Circle::create(Real(1)).value();
  const Real nan = std::numeric_limits<Real>::quiet_NaN();
  proxima::test::ScopedNoFpTraps no_traps;
  const DistanceResult r = distance(circle, Pose::from({nan, 0}, 0), circle, Pose::identity());
  EXPECT_EQ(r.status, PairStatus::InvalidInput);
  EXPECT_FALSE(intersect(circle, Pose::from({nan, 0}, 0), circle, Pose::identity()));
  EXPECT_EQ(collide(circle, Pose::from({nan, 0}, 0), circle, Pose::identity()).count, 0);
}

/// The signed distance of `a` and `b` against the long-double Minkowski hull, with the
/// witnesses on their surfaces.
void expect_distance_matches_hull(const test::RandomShape& a, const RefPose& pa, const test::RandomShape& b,
                                  const RefPose& pb, const std::string& what) {
  const LD expected = test::signed_distance(a.ref, pa, b.ref, pb);
  const DistanceResult r = distance(a.shape, pa.pose(), b.shape, pb.pose());
  const Real tol = tolerance(Real(8));
  ASSERT_NEAR(r.signed_distance, static_cast<Real>(expected), tol) << what;
  ASSERT_LE(glm::length(r.point_b - r.point_a - r.signed_distance * r.normal), tol) << what;
  ASSERT_NEAR(static_cast<Real>(test::point_signed_distance(a.ref, pa, {r.point_a.x, r.point_a.y})), Real(0), 4 * tol)
      << what;
  ASSERT_NEAR(static_cast<Real>(test::point_signed_distance(b.ref, pb, {r.point_b.x, r.point_b.y})), Real(0), 4 * tol)
      << what;
  const LD cores = expected + a.ref.radius + b.ref.radius;  // the cores' signed distance
  if (std::abs(cores) > 4 * tol) {
    ASSERT_EQ(r.method, cores > 0 ? PairMethod::Gjk : PairMethod::Sat) << what;
  }
}

/// A shape with its defining numbers from a core's vertices (counter-clockwise) and radius.
test::RandomShape shape_of(const std::vector<Vec2>& core, Real radius) {
  test::RandomShape s{Shape(Point::create(core[0]).value()), {}};
  for (const Vec2& v : core) s.ref.core.push_back({v.x, v.y});
  s.ref.radius = radius;
  if (core.size() == 1) {
    s.shape = radius > Real(0) ? Shape(Circle::create(radius, core[0]).value()) : Shape(Point::create(core[0]).value());
  } else if (core.size() == 2) {
    s.shape = radius > Real(0) ? Shape(Capsule::create(core[0], core[1], radius).value())
                               : Shape(Segment::create(core[0], core[1]).value());
  } else {
    s.shape = Shape(Polygon::create(core, radius).value());
  }
  return s;
}

// The closed form of a 1-vertex core against a core with edges: the point in every region
// of a polygon (each vertex's and edge's outer region, inside, on edges and vertices) and
// of a segment (beside it, beyond each end, on its line, on it).
TEST(D2ClosedForm, PointAgainstPolygonAndSegmentInEveryRegion) {
  const std::vector<Vec2> pentagon = {
      {Real(-1), Real(-1)}, {Real(1.5), Real(-1)}, {Real(2), Real(0.5)}, {Real(0), Real(1.5)}, {Real(-1.2), Real(0.4)}};
  const std::vector<Vec2> stick = {{Real(-1), Real(0.2)}, {Real(1.5), Real(-0.3)}};
  proxima::test::Random rng(0xD2CF1);
  for (const auto& core : {pentagon, stick}) {
    for (const Real core_radius : {Real(0), Real(0.25)}) {
      const test::RandomShape c = shape_of(core, core_radius);
      for (int i = 0; i < proxima::test::sweep_size(2000); ++i) {
        const Real x = rng.uniform(Real(-3), Real(3)), y = rng.uniform(Real(-3), Real(3));
        const int k = rng.integer(0, static_cast<int>(core.size()) - 1);
        const Vec2 on_edge = core[k] + rng.uniform(Real(0), Real(1)) * (core[(k + 1) % core.size()] - core[k]);
        const Vec2 q = i % 4 == 0 ? on_edge : (i % 4 == 1 ? core[k] : Vec2(x, y));
        const test::RandomShape p = shape_of({Vec2(Real(0))}, i % 2 == 0 ? Real(0) : Real(0.3));
        const RefPose pose_c{rng.uniform(Real(-2), Real(2)), rng.uniform(Real(-2), Real(2)),
                             rng.uniform(Real(-3), Real(3))};
        const test::P wq = pose_c.apply({q.x, q.y});
        const RefPose moved{wq.x, wq.y, rng.uniform(Real(-3), Real(3))};
        expect_distance_matches_hull(c, pose_c, p, moved, "core-point case " + std::to_string(i));
        expect_distance_matches_hull(p, moved, c, pose_c, "point-core case " + std::to_string(i));
      }
    }
  }
}

// The closed form of two 2-vertex cores: crossing, touching at an end, T-junctions,
// parallel and collinear (apart, overlapping, touching end to end) segments and capsules.
TEST(D2ClosedForm, SegmentPairsCrossingParallelAndCollinear) {
  const std::vector<std::pair<std::vector<Vec2>, std::vector<Vec2>>> cases = {
      {{{-1, 0}, {1, 0}}, {{0, -1}, {0, 1}}},                                // crossing
      {{{-1, 0}, {1, 0}}, {{Real(0.3), Real(-0.2)}, {Real(0.5), Real(2)}}},  // crossing near an end
      {{{-1, 0}, {1, 0}}, {{0, 0}, {0, 1}}},                                 // T-junction
      {{{-1, 0}, {1, 0}}, {{1, 0}, {2, 1}}},                                 // end to end
      {{{-1, 0}, {1, 0}}, {{-2, 1}, {3, 1}}},                                // parallel
      {{{-1, 0}, {1, 0}}, {{2, 0}, {3, 0}}},                                 // collinear, apart
      {{{-1, 0}, {1, 0}}, {{Real(0.5), 0}, {3, 0}}},                         // collinear, overlapping
      {{{-1, 0}, {1, 0}}, {{1, 0}, {3, 0}}},                                 // collinear, end to end
      {{{-1, 0}, {1, 0}}, {{Real(1.5), Real(0.5)}, {Real(3), Real(0.501)}}}  // nearly parallel, apart
  };
  proxima::test::Random rng(0xD2CF2);
  for (std::size_t c = 0; c < cases.size(); ++c) {
    for (int i = 0; i < 50; ++i) {
      const Real ra = i % 2 == 0 ? Real(0) : Real(0.2), rb = i % 3 == 0 ? Real(0) : Real(0.1);
      const test::RandomShape a = shape_of(cases[c].first, ra), b = shape_of(cases[c].second, rb);
      const RefPose pose{rng.uniform(Real(-4), Real(4)), rng.uniform(Real(-4), Real(4)),
                         rng.uniform(Real(-3), Real(3))};
      expect_distance_matches_hull(a, pose, b, pose, "segment case " + std::to_string(c));
      expect_distance_matches_hull(b, pose, a, pose, "segment case " + std::to_string(c) + " swapped");
    }
  }
}

// The closed form of cores with area apart: corner to corner, corner to edge, and parallel
// edges overlapping or not along their length (the reference edge's deepest vertex ties).
TEST(D2ClosedForm, PolygonsApartByCornersEdgesAndParallelFaces) {
  proxima::test::Random rng(0xD2CF3);
  const std::vector<Vec2> box = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
  const std::vector<Vec2> stick = {{-1, 0}, {1, 0}};
  for (int i = 0; i < proxima::test::sweep_size(3000); ++i) {
    const test::RandomShape a = shape_of(box, i % 2 == 0 ? Real(0) : Real(0.1));
    const test::RandomShape b = shape_of(i % 3 == 0 ? stick : box, i % 5 == 0 ? Real(0.2) : Real(0));
    // B beside A's right face, turned by a multiple of a quarter (parallel faces) or freely.
    const Real angle = i % 4 == 0 ? rng.uniform(Real(-3), Real(3)) : Real(rng.integer(0, 3)) * kPi / 2;
    const RefPose pa{0, 0, 0};
    const RefPose pb{rng.uniform(Real(1.8), Real(3.5)), rng.uniform(Real(-3), Real(3)), angle};
    const RefPose frame{rng.uniform(Real(-4), Real(4)), rng.uniform(Real(-4), Real(4)), rng.uniform(Real(-3), Real(3))};
    const auto moved = [&](const RefPose& p) {
      const test::P o = frame.apply({p.x, p.y});
      return RefPose{o.x, o.y, p.angle + frame.angle};
    };
    expect_distance_matches_hull(a, moved(pa), b, moved(pb), "case " + std::to_string(i));
    expect_distance_matches_hull(b, moved(pb), a, moved(pa), "swapped case " + std::to_string(i));
  }
}

/// Checks a manifold against the reference: count iff within reach, points on or in their
/// shapes, depths consistent with the witnesses, the deepest depth equal to the exact one.
void expect_manifold_matches(const RandomPair& p, Real contact_distance, const std::string& what) {
  const Manifold m = collide(p.a.shape, p.pa.pose(), p.b.shape, p.pb.pose(), contact_distance);
  const LD expected = test::signed_distance(p.a.ref, p.pa, p.b.ref, p.pb);
  const Real tol = tolerance(Real(8));
  if (expected > contact_distance + 4 * tol) {
    ASSERT_EQ(m.count, 0) << what;
    return;
  }
  if (expected < contact_distance - 4 * tol) {
    ASSERT_GT(m.count, 0) << what << " expected " << static_cast<double>(expected);
  }
  if (m.count == 0) return;
  ASSERT_NEAR(glm::length(m.normal), Real(1), Real(1e-5)) << what;
  Real deepest = -std::numeric_limits<Real>::infinity();
  for (int k = 0; k < m.count; ++k) {
    const ContactPoint& c = m.points[k];
    deepest = std::max(deepest, c.depth);
    ASSERT_NEAR(glm::dot(c.point_a - c.point_b, m.normal), c.depth, tol) << what;
    // The reference edge may be the one within the tie margin (1e-4 of the pair's scale) of
    // the least-penetrating axis: a point's depth can exceed the exact one by that much.
    ASSERT_LE(c.depth, static_cast<Real>(-expected) + tol + Real(1e-4) * Real(8)) << what << " point " << k;
    ASSERT_GE(c.depth, -contact_distance - tol) << what;
    const LD on_a = test::point_signed_distance(p.a.ref, p.pa, {c.point_a.x, c.point_a.y});
    const LD on_b = test::point_signed_distance(p.b.ref, p.pb, {c.point_b.x, c.point_b.y});
    ASSERT_LE(static_cast<Real>(std::min(on_a, on_b)), 4 * tol) << what << " point " << k;  // one lies on its surface
    ASSERT_LE(static_cast<Real>(std::max(on_a, on_b)), 4 * tol) << what << " point " << k;  // neither outside
  }
  // The deepest point carries the exact depth (up to the reference edge's tie margin).
  ASSERT_NEAR(deepest, static_cast<Real>(-expected), Real(1e-3) * Real(8) + 4 * tol) << what;
}

TEST(D2Manifold, EveryConvexPairMatchesTheReference) {
  proxima::test::Random rng(0xD2C011);
  const int per_pair = proxima::test::sweep_size(600);
  for (ShapeType ta : kConvexKinds) {
    for (ShapeType tb : kConvexKinds) {
      for (int i = 0; i < per_pair; ++i) {
        const RandomPair p = random_pair(rng, ta, tb);
        const Real contact_distance = i % 3 == 0 ? Real(0.1) : Real(0);
        expect_manifold_matches(p, contact_distance, pair_name(ta, tb) + " case " + std::to_string(i));
      }
    }
  }
}

TEST(D2Manifold, BoxRestingOnABoxHasTwoPointsAtTheRightDepth) {
  const Shape ground = Polygon::box(Real(5), Real(1)).value();
  const Shape box = Polygon::box(Real(0.5), Real(0.5)).value();
  const Manifold m = collide(ground, Pose::identity(), box, Pose::from({Real(1), Real(1.49)}, 0));
  ASSERT_EQ(m.count, 2);
  EXPECT_NEAR(m.normal.y, Real(1), Real(1e-6));
  for (int k = 0; k < 2; ++k) {
    EXPECT_NEAR(m.points[k].depth, Real(0.01), Real(1e-5));
    EXPECT_NEAR(m.points[k].point_a.y, Real(1), Real(1e-5));
    EXPECT_NEAR(m.points[k].point_b.y, Real(0.99), Real(1e-5));
  }
  EXPECT_NEAR(std::min(m.points[0].point_b.x, m.points[1].point_b.x), Real(0.5), Real(1e-5));
  EXPECT_NEAR(std::max(m.points[0].point_b.x, m.points[1].point_b.x), Real(1.5), Real(1e-5));
  EXPECT_NE(m.points[0].feature_id, m.points[1].feature_id);
}

TEST(D2Manifold, CapsuleLyingOnABoxHasTwoPoints) {
  const Shape ground = Polygon::box(Real(5), Real(1)).value();
  const Shape capsule = Capsule::create({Real(-1), Real(0)}, {Real(1), Real(0)}, Real(0.25)).value();
  const Manifold m = collide(ground, Pose::identity(), capsule, Pose::from({0, Real(1.2)}, 0));
  ASSERT_EQ(m.count, 2);
  for (int k = 0; k < 2; ++k) EXPECT_NEAR(m.points[k].depth, Real(0.05), Real(1e-5));
}

TEST(D2Manifold, FeatureIdsStayWhileTheSameFeaturesTouch) {
  const Shape ground = Polygon::box(Real(5), Real(1)).value();
  const Shape box = Polygon::box(Real(0.5), Real(0.5)).value();
  const Manifold first = collide(ground, Pose::identity(), box, Pose::from({Real(1), Real(1.49)}, Real(0.01)));
  const Manifold later = collide(ground, Pose::identity(), box, Pose::from({Real(1.2), Real(1.48)}, Real(0.015)));
  ASSERT_EQ(first.count, 2);
  ASSERT_EQ(later.count, 2);
  EXPECT_EQ(first.points[0].feature_id, later.points[0].feature_id);
  EXPECT_EQ(first.points[1].feature_id, later.points[1].feature_id);
}

TEST(D2Manifold, SwappingTheShapesMirrorsTheManifold) {
  proxima::test::Random rng(0xD2C012);
  for (int i = 0; i < proxima::test::sweep_size(2000); ++i) {
    const RandomPair p = random_pair(rng, kConvexKinds[i % 5], kConvexKinds[(i / 5) % 5]);
    const Manifold ab = collide(p.a.shape, p.pa.pose(), p.b.shape, p.pb.pose());
    const Manifold ba = collide(p.b.shape, p.pb.pose(), p.a.shape, p.pa.pose());
    ASSERT_EQ(ab.count > 0, ba.count > 0) << "case " << i;
    if (ab.count == 0) continue;
    Real deepest_ab = -kRealMax, deepest_ba = -kRealMax;
    for (int k = 0; k < ab.count; ++k) deepest_ab = std::max(deepest_ab, ab.points[k].depth);
    for (int k = 0; k < ba.count; ++k) deepest_ba = std::max(deepest_ba, ba.points[k].depth);
    ASSERT_NEAR(deepest_ab, deepest_ba, Real(1e-3) * Real(8)) << "case " << i;
  }
}

}  // namespace
}  // namespace proxima::d2
