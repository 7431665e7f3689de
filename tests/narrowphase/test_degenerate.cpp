// Degenerate and extreme inputs for every pair of shape types: exactly touching supports,
// coincident centres, identical shapes at identical poses, zero-length capsules, flat and
// needle hulls, tiny (1e-4) and huge (1e4) shapes, shapes 1e4 from the origin, touching box
// faces and parallel edges, and non-finite transforms (status InvalidInput, no NaN out).
// Every case goes through the convention checks of pair_checker.hpp; the touching cases
// also compare with the gap they were built with (the supports of A and B in direction n
// are placed gap apart, so the exact signed distance is the gap for gap >= 0).
#include <gtest/gtest.h>

#include <limits>
#include <string>

#include "narrowphase/pair_checker.hpp"
#include "narrowphase/reference_distance.hpp"
#include "shapes/shape_visit.hpp"

namespace proxima {
namespace test_degenerate {

using test::PairChecker;

#ifdef NDEBUG
constexpr int kReps = 12;
#else
constexpr int kReps = 3;
#endif

void expect_clean(const PairChecker& checker, const std::string& what) {
  std::string detail;
  for (const std::string& m : checker.messages()) detail += "\n  " + m;
  EXPECT_EQ(checker.failed_cases(), 0) << what << ": " << checker.failed_cases() << " of " << checker.cases()
                                       << " cases failed: " << checker.summary() << detail;
}

std::string pair_label(ShapeType a, ShapeType b) { return std::string(to_string(a)) + "-" + to_string(b); }

// Runs `make(rng, a, b, checker)` for every ordered pair of types.
template <class Make>
void for_every_pair(std::uint64_t seed, Make make, const std::string& what, bool skip_halfspace_pair = true) {
  for (ShapeType ta : test::all_shape_types()) {
    for (ShapeType tb : test::all_shape_types()) {
      if (skip_halfspace_pair && ta == ShapeType::HalfSpace && tb == ShapeType::HalfSpace) continue;
      test::Random rng(seed + std::uint64_t(ta) * 17u + std::uint64_t(tb));
      PairChecker checker;
      for (int i = 0; i < kReps; ++i) make(rng, ta, tb, checker, pair_label(ta, tb) + " rep=" + std::to_string(i));
      expect_clean(checker, what + " " + pair_label(ta, tb));
    }
  }
}

// World point of `shape` at `pose` farthest in `n`, and for half-spaces the plane point
// nearest the pose origin (their support is a far corner of a huge clipping cube).
Vec3 world_extreme(const Shape& shape, const Transform& pose, const Vec3& n) {
  if (const HalfSpace* h = std::get_if<HalfSpace>(&shape)) return pose.apply(h->offset() * h->normal());
  return detail::visit_convex(shape, [&](const auto& s) { return support(s, pose, n); });
}

// Places B so that A's farthest point in n and B's farthest point in -n are `gap` apart
// along n (n is forced to a half-space's normal when one is involved). `support_a` and
// `support_b` receive those two world points (support_b = support_a + gap n).
Transform place_touching(const Shape& a, const Transform& pose_a, const Shape& b, const Quat& rot_b, Vec3 n, Real gap,
                         Vec3* support_a = nullptr, Vec3* support_b = nullptr) {
  if (const HalfSpace* h = std::get_if<HalfSpace>(&a)) n = pose_a.apply_vector(h->normal());
  if (const HalfSpace* h = std::get_if<HalfSpace>(&b)) n = -(rot_b * h->normal());
  const Vec3 pa = world_extreme(a, pose_a, n);
  const Transform at_origin{Vec3(Real(0)), rot_b};
  const Vec3 sb = world_extreme(b, at_origin, -n);
  if (support_a) *support_a = pa;
  if (support_b) *support_b = pa + gap * n;
  return Transform{pa - sb + gap * n, rot_b};
}

TEST(Degenerate, TouchingSupportsEveryPair) {
  for_every_pair(
      11,
      [](test::Random& rng, ShapeType ta, ShapeType tb, PairChecker& checker, const std::string& label) {
        const Shape a = test::random_shape(rng, ta);
        const Shape b = test::random_shape(rng, tb);
        const Transform pose_a = rng.pose(Real(0.5));
        const Vec3 n = rng.unit_vector();
        const Quat rot_b = rng.rotation();
        for (Real gap : {Real(0), Real(0.01), Real(-0.01)}) {
          Vec3 sa;
          Vec3 sb;
          const Transform pose_b = place_touching(a, pose_a, b, rot_b, n, gap, &sa, &sb);
          checker.check(a, pose_a, b, pose_b, label + " gap=" + std::to_string(gap));
          const DistanceResult d = distance(a, pose_a, b, pose_b);
          const Real tol = Real(4) * test::narrow_tolerance(Real(2));
          if (gap >= Real(0)) {
            // The slab between the two support planes separates them, and the support
            // points are gap apart: the distance is exactly the gap.
            EXPECT_NEAR(d.signed_distance, gap, tol) << label << " gap " << gap;
          } else {
            // A lies in n . x <= n . sa and B in n . x >= n . sa + gap: the depth is at most
            // the overlap along n.
            EXPECT_GE(d.signed_distance, gap - tol) << label;
            // The construction makes an overlap only where a support point lies inside the
            // other shape; a shape without volume (point, segment, triangle) has no inside,
            // and a solid's inside need not hold the direction n at a vertex or rim. The
            // signed distance is at most the signed distance of either support point to the
            // other shape (the shape layer's closest_point, not the narrow phase), which is
            // <= 0 exactly when the construction overlaps.
            const Real bound = std::min(test::surface_distance(b, pose_b, sa), test::surface_distance(a, pose_a, sb));
            EXPECT_LE(d.signed_distance, bound + tol) << label << " support points " << bound;
          }
        }
      },
      "touching supports");
}

TEST(Degenerate, CoincidentCentresEveryPair) {
  for_every_pair(
      23,
      [](test::Random& rng, ShapeType ta, ShapeType tb, PairChecker& checker, const std::string& label) {
        const Shape a = test::random_shape(rng, ta);
        const Shape b = test::random_shape(rng, tb);
        const Vec3 c = rng.vec3(Real(-1), Real(1));
        const Quat qb = rng.rotation();
        const Quat qa = rng.rotation();
        checker.check(a, Transform{c, qa}, b, Transform{c, qb}, label);
        const Quat q = rng.rotation();
        checker.check(a, Transform{c, q}, b, Transform{c, q}, label + " same rotation");
      },
      "coincident centres");
}

TEST(Degenerate, IdenticalShapesAtIdenticalPoses) {
  test::Random rng(31);
  for (ShapeType t : test::all_shape_types()) {
    if (t == ShapeType::HalfSpace) continue;
    PairChecker checker;
    for (int i = 0; i < kReps; ++i) {
      const Shape s = test::random_shape(rng, t);
      const Transform pose = rng.pose(Real(2));
      checker.check(s, pose, s, pose, std::string(to_string(t)) + " rep=" + std::to_string(i));
      const DistanceResult d = distance(s, pose, s, pose);
      if (!test::is_thin(t) && t != ShapeType::Point) {
        EXPECT_LT(d.signed_distance, Real(0)) << to_string(t);
      }
      EXPECT_TRUE(intersect(s, pose, s, pose)) << to_string(t);
    }
    expect_clean(checker, std::string("identical ") + to_string(t));
  }
}

TEST(Degenerate, ZeroLengthCapsuleAgainstEveryType) {
  test::Random rng(41);
  const Shape cap = Capsule::create(Real(0.5), Real(0)).value();
  for (ShapeType t : test::all_shape_types()) {
    PairChecker checker;
    for (int i = 0; i < 4 * kReps; ++i) {
      const Shape other = test::random_shape(rng, t);
      const Transform pc = rng.pose(Real(0.5));
      const Transform po = rng.pose(Real(1.5));
      checker.check(cap, pc, other, po, std::string("capsule(h=0)-") + to_string(t));
      checker.check(other, po, cap, pc, std::string(to_string(t)) + "-capsule(h=0)");
      // Reference: a zero-length capsule is a sphere of the same radius.
      const Shape sphere = Sphere::create(Real(0.5)).value();
      const DistanceResult dc = distance(cap, pc, other, po);
      const DistanceResult ds = distance(sphere, pc, other, po);
      EXPECT_NEAR(dc.signed_distance, ds.signed_distance, test::narrow_tolerance(Real(2)))
          << to_string(t) << " " << test::describe(other, po);
    }
    expect_clean(checker, std::string("zero-length capsule vs ") + to_string(t));
  }
}

Shape flat_or_needle_hull(test::Random& rng, bool needle) {
  for (;;) {
    Vec3 e(Real(1), needle ? Real(2e-3) : Real(1), Real(2e-3));
    std::vector<Vec3> pts = test::random_cloud(rng, rng.integer(8, 32), e);
    // Make sure the cloud spans all three dimensions (qhull rejects a truly flat one).
    pts.push_back(Vec3(Real(0), Real(0), Real(2e-3)));
    pts.push_back(Vec3(Real(0), Real(2e-3), Real(-2e-3)));
    auto r = ConvexHull::create(pts);
    if (r.ok()) return r.value();
  }
}

TEST(Degenerate, FlatAndNeedleHullsAgainstEveryType) {
  test::Random rng(53);
  for (bool needle : {false, true}) {
    for (ShapeType t : test::all_shape_types()) {
      PairChecker checker;
      for (int i = 0; i < 3 * kReps; ++i) {
        const Shape hull = flat_or_needle_hull(rng, needle);
        const Shape other = test::random_shape(rng, t);
        const Transform ph = rng.pose(Real(0.5));
        const Transform po = rng.pose(Real(1.5));
        checker.check(hull, ph, other, po, std::string(needle ? "needle" : "flat") + "-" + to_string(t));
        checker.check(other, po, hull, ph, std::string(to_string(t)) + "-" + (needle ? "needle" : "flat"));
      }
      expect_clean(checker, std::string(needle ? "needle hull vs " : "flat hull vs ") + to_string(t));
    }
  }
}

TEST(Degenerate, TinyAndHugeScalesEveryPair) {
  for (Real s : {Real(1e-4), Real(1e4)}) {
    for_every_pair(
        61,
        [s](test::Random& rng, ShapeType ta, ShapeType tb, PairChecker& checker, const std::string& label) {
          const Shape a = test::random_shape(rng, ta, s);
          const Shape b = test::random_shape(rng, tb, s);
          Transform pa = rng.pose(Real(0.5));
          Transform pb = rng.pose(Real(1.8));
          pa.position *= s;
          pb.position *= s;
          checker.check(a, pa, b, pb, label + " scale=" + std::to_string(s));
        },
        "scale " + std::to_string(s));
  }
}

TEST(Degenerate, FarFromOriginEveryPair) {
  for_every_pair(
      71,
      [](test::Random& rng, ShapeType ta, ShapeType tb, PairChecker& checker, const std::string& label) {
        const Shape a = test::random_shape(rng, ta);
        const Shape b = test::random_shape(rng, tb);
        const Vec3 offset(Real(1e4), Real(-1e4), Real(1e4));
        Transform pa = rng.pose(Real(0.5));
        Transform pb = rng.pose(Real(1.8));
        pa.position += offset;
        pb.position += offset;
        checker.check(a, pa, b, pb, label + " far");
      },
      "far from origin");
}

TEST(Degenerate, BoxFacesTouchingAndParallelEdges) {
  const Box box = Box::create(Vec3(Real(1), Real(0.5), Real(0.25))).value();
  PairChecker checker;
  test::Random rng(83);
  for (int i = 0; i < 20 * kReps; ++i) {
    // Face on face, shifted sideways, exactly touching (gap 0) or slightly apart/overlapping.
    const Real gap = Real(rng.integer(-1, 1)) * Real(1e-3);
    const Real shift_y = rng.uniform(Real(-0.8), Real(0.8));
    const Real shift_x = rng.uniform(Real(-1.5), Real(1.5));
    const Vec3 shift(shift_x, shift_y, Real(0.5) + gap);
    const Transform pa = Transform::identity();
    const Transform pb{shift, Quat(Real(1), Real(0), Real(0), Real(0))};
    checker.check(box, pa, box, pb, "faces gap=" + std::to_string(gap));
    const DistanceResult d = distance(box, pa, box, pb);
    EXPECT_NEAR(d.signed_distance, gap, test::narrow_tolerance(Real(2))) << "faces " << shift.x << "," << shift.y;
    EXPECT_NEAR(d.normal.z, Real(1), Real(1e-3)) << "faces";
    const ContactManifold m = collide(box, pa, box, pb);
    if (gap < Real(0)) {
      EXPECT_EQ(m.count, 4) << "face-face overlap should give a four-point manifold";
    }
    // Parallel edges: B turned 45 degrees about x, resting edge-down on A's top face.
    const Quat q = glm::angleAxis(Real(0.7853981633974483), Vec3(Real(1), Real(0), Real(0)));
    const Real reach = (Real(0.5) + Real(0.25)) * std::sqrt(Real(0.5));
    const Transform pe{Vec3(rng.uniform(Real(-1), Real(1)), Real(0), Real(0.25) + reach + gap), q};
    checker.check(box, pa, box, pe, "parallel edge on face gap=" + std::to_string(gap));
    EXPECT_NEAR(distance(box, pa, box, pe).signed_distance, gap, test::narrow_tolerance(Real(2))) << "edge";
    // Edge on edge: A turned 45 degrees about x too, B above it.
    const Transform pa2{Vec3(Real(0)), q};
    // The top edge of the turned A sits at y = (0.5 - 0.25) sqrt(1/2), B's bottom edge at
    // minus that from B's centre.
    const Real side = (Real(0.5) - Real(0.25)) * std::sqrt(Real(0.5));
    const Transform pe2{Vec3(rng.uniform(Real(-1), Real(1)), Real(2) * side, Real(2) * reach + gap), q};
    checker.check(box, pa2, box, pe2, "parallel edges gap=" + std::to_string(gap));
    // Overlapping edge on edge, the least depth is along the 45-degree face normals: gap / sqrt(2).
    const Real edge_depth = gap < Real(0) ? gap * std::sqrt(Real(0.5)) : gap;
    EXPECT_NEAR(distance(box, pa2, box, pe2).signed_distance, edge_depth, test::narrow_tolerance(Real(2))) << "edges";
  }
  expect_clean(checker, "box faces and edges");
}

TEST(Degenerate, NonFiniteTransformsGiveInvalidInput) {
  const Real nan = std::numeric_limits<Real>::quiet_NaN();
  const Real inf = std::numeric_limits<Real>::infinity();
  test::Random rng(97);
  for (ShapeType ta : test::all_shape_types()) {
    for (ShapeType tb : test::all_shape_types()) {
      const Shape a = test::random_shape(rng, ta);
      const Shape b = test::random_shape(rng, tb);
      const Transform good = rng.pose(Real(1));
      const std::array<Transform, 4> bad = {
          Transform{Vec3(nan, Real(0), Real(0)), Quat(Real(1), Real(0), Real(0), Real(0))},
          Transform{Vec3(Real(0), inf, Real(0)), Quat(Real(1), Real(0), Real(0), Real(0))},
          Transform{Vec3(Real(0), Real(0), -inf), Quat(Real(1), Real(0), Real(0), Real(0))},
          Transform{Vec3(Real(0)), Quat(nan, Real(0), Real(0), Real(0))},
      };
      for (std::size_t k = 0; k < bad.size(); ++k) {
        for (int side = 0; side < 2; ++side) {
          const Transform& pa = side == 0 ? bad[k] : good;
          const Transform& pb = side == 0 ? good : bad[k];
          DistanceResult d;
          ContactManifold m;
          bool hit = true;
          {
            test::ScopedNoFpTraps no_traps;  // the inputs themselves hold NaN
            d = distance(a, pa, b, pb);
            m = collide(a, pa, b, pb);
            hit = intersect(a, pa, b, pb);
          }
          const std::string where = pair_label(ta, tb) + " bad=" + std::to_string(k) + " side=" + std::to_string(side);
          EXPECT_EQ(d.status, PairStatus::InvalidInput) << where;
          EXPECT_EQ(m.status, PairStatus::InvalidInput) << where;
          EXPECT_FALSE(hit) << where;
          EXPECT_EQ(m.count, 0) << where;
          EXPECT_FALSE(std::isnan(d.signed_distance)) << where;
          EXPECT_TRUE(d.signed_distance > Real(0)) << where;
          EXPECT_TRUE(test::finite3(d.normal)) << where;
          EXPECT_FALSE(std::isnan(d.point_a.x) || std::isnan(d.point_a.y) || std::isnan(d.point_a.z)) << where;
          EXPECT_FALSE(std::isnan(d.point_b.x) || std::isnan(d.point_b.y) || std::isnan(d.point_b.z)) << where;
        }
      }
    }
  }
}

// Named regressions: cases the sweeps found where Proxima disagrees with an independent
// reference (the shape layer's closest_point for a point or a sphere centre inside a solid:
// the depth of a point is its distance to the nearest surface point; exact SAT for boxes).
Quat quat_xyzw(Real x, Real y, Real z, Real w) { return glm::normalize(Quat(w, x, y, z)); }

TEST(DegenerateRegression, PointInsideCylinderHasItsDepth) {
  const Shape a = Point::create().value();
  const Shape b = Cylinder::create(Real(0.474859864), Real(1.04806459)).value();
  const Transform pa{Vec3(Real(0.323978513), Real(-0.395196468), Real(0.1121087)), Quat(1, 0, 0, 0)};
  const Transform pb{Vec3(Real(0.790367126), Real(-1.16161013), Real(0.214803293)),
                     quat_xyzw(Real(-0.67889148), Real(0.174177587), Real(-0.661284089), Real(-0.267342269))};
  const Real expected = test::surface_distance(b, pb, pa.position);  // about -0.1235
  ASSERT_LT(expected, Real(-0.1));
  const DistanceResult d = distance(a, pa, b, pb);
  EXPECT_NEAR(d.signed_distance, expected, test::narrow_tolerance(Real(2))) << test::status_name(d.status);
  EXPECT_EQ(d.status, PairStatus::Penetrating);
}

TEST(DegenerateRegression, SphereCentreInsideCylinderHasFullDepth) {
  const Shape a = Cylinder::create(Real(1.20059097), Real(1.21182144)).value();
  const Shape b = Sphere::create(Real(0.659485638)).value();
  const Transform pa{Vec3(Real(0.311585188), Real(0.127514184), Real(-0.139358237)),
                     quat_xyzw(Real(-0.746628582), Real(-0.0728900582), Real(0.576641798), Real(-0.323600173))};
  const Transform pb{Vec3(Real(1.27226567), Real(0.605910301), Real(-0.409590006)), Quat(1, 0, 0, 0)};
  // Depth of a sphere whose centre is inside: centre depth plus radius (about 0.852).
  const Real expected = test::surface_distance(a, pa, pb.position) - Real(0.659485638);
  const DistanceResult d = distance(a, pa, b, pb);
  EXPECT_NEAR(d.signed_distance, expected, test::narrow_tolerance(Real(2))) << test::status_name(d.status);
  EXPECT_EQ(d.status, PairStatus::Penetrating);
}

TEST(DegenerateRegression, PointInsideBoxWitnessesAlongTheNormal) {
  const Shape a = Point::create().value();
  const Shape b = Box::create(Vec3(Real(0.92252934), Real(1.01535082), Real(0.736761034))).value();
  const Transform pa{Vec3(Real(0.335912228), Real(0.0764173642), Real(0.140884981)), Quat(1, 0, 0, 0)};
  const Transform pb{Vec3(Real(0.299190283), Real(0.00392830512), Real(0.445921928)),
                     quat_xyzw(Real(0.108593345), Real(-0.329925925), Real(0.895570517), Real(0.278046459))};
  const SurfacePoint sp = closest_point(std::get<Box>(b), pb, pa.position);
  const DistanceResult d = distance(a, pa, b, pb);
  const Real tol = test::narrow_tolerance(Real(2));
  EXPECT_NEAR(d.signed_distance, sp.signed_distance, tol);
  // The witness on the box is the nearest surface point, and the normal (A to B) is minus
  // the box's outward normal there.
  EXPECT_LE(glm::length(d.point_b - sp.point), tol);
  EXPECT_LE(glm::length(d.normal + sp.normal), Real(1e-3));
  EXPECT_LE(glm::length(d.point_a + d.signed_distance * d.normal - d.point_b), tol);
}

TEST(DegenerateRegression, BoxBoxManifoldNoDeeperThanThePair) {
  const Shape a = Box::create(Vec3(Real(0.696924627), Real(0.301372379), Real(0.391439617))).value();
  const Shape b = Box::create(Vec3(Real(1.41585064), Real(0.776285052), Real(0.531192005))).value();
  const Transform pa{Vec3(Real(0.00447324943), Real(0.306857497), Real(-0.239830032)),
                     quat_xyzw(Real(0.184314162), Real(0.271779269), Real(0.900201917), Real(-0.286008477))};
  const Transform pb{Vec3(Real(-0.661844909), Real(-0.245100841), Real(-0.130647331)),
                     quat_xyzw(Real(0.274618715), Real(-0.112324059), Real(-0.442257553), Real(-0.846390069))};
  const double exact = test::polytope_depth_sat(*test::world_polytope(a, pa), *test::world_polytope(b, pb));
  const Real tol = test::narrow_tolerance(Real(3));
  const DistanceResult d = distance(a, pa, b, pb);
  EXPECT_NEAR(double(d.signed_distance), -exact, double(tol));
  const ContactManifold m = collide(a, pa, b, pb);
  ASSERT_GT(m.count, 0);
  for (int i = 0; i < m.count; ++i) {
    EXPECT_LE(double(m.points[static_cast<std::size_t>(i)].depth), exact + double(tol)) << "point " << i;
  }
}

// Found by the peer cross-validation (Bullet and the support-function reference agree, ours
// stopped at max_iterations with too small a depth).
TEST(DegenerateRegression, CylinderBoxDepthAtIterationCap) {
  const Shape a = Cylinder::create(Real(0.846213162), Real(1.4571054)).value();
  const Shape b = Box::create(Vec3(Real(0.377202779), Real(1.41666675), Real(0.288165748))).value();
  const Transform pa{Vec3(Real(-0.0916636735), Real(0.144602478), Real(-0.173393071)),
                     quat_xyzw(Real(0.571705759), Real(-0.282159895), Real(-0.150283307), Real(0.755614638))};
  const Transform pb{Vec3(Real(1.20520043), Real(-0.00541394623), Real(1.1379478)),
                     quat_xyzw(Real(-0.263324231), Real(-0.0893702954), Real(-0.00665297732), Real(0.960535824))};
  const double ref = test::reference_signed_distance(a, pa, b, pb).signed_distance;  // about -0.2378
  const DistanceResult d = distance(a, pa, b, pb);
  EXPECT_NEAR(double(d.signed_distance), ref, double(test::narrow_tolerance(Real(3)))) << test::status_name(d.status);
}

TEST(DegenerateRegression, CapsuleCoreInsideConeHasFullDepth) {
  const Shape a = Capsule::create(Real(0.158505112), Real(0.0150759397)).value();
  const Shape b = Cone::create(Real(1.42092168), Real(1.45894063)).value();
  const Transform pa{Vec3(Real(-0.199290499), Real(0.0795319825), Real(-0.451174408)),
                     quat_xyzw(Real(0.439373434), Real(-0.232769847), Real(0.846018195), Real(0.192412049))};
  const Transform pb{Vec3(Real(-0.378558755), Real(0.51059401), Real(-0.153617978)),
                     quat_xyzw(Real(-0.049712263), Real(-0.575284243), Real(-0.810588002), Real(0.0975899398))};
  // A dense seeding (the default 1,500 directions start the refinement on the wrong ridge here).
  const double ref = test::reference_signed_distance(a, pa, b, pb, 200000, 64).signed_distance;  // about -0.83077
  const DistanceResult d = distance(a, pa, b, pb);
  EXPECT_NEAR(double(d.signed_distance), ref, double(test::narrow_tolerance(Real(3)))) << test::status_name(d.status);
}

// Identical segments at one pose (found by IdenticalShapesAtIdenticalPoses): the normal of
// touching segments must be orthogonal to both, so that moving B along it by eps leaves
// them exactly eps apart (analytic: the distance of two parallel segments offset
// perpendicularly by eps is eps). Also collinear overlapping, coplanar crossing and parallel
// coplanar segments.
TEST(DegenerateRegression, IdenticalSegmentsNormalOrthogonal) {
  test::Random rng(5);
  const Real eps = Real(1e-2);
  for (int i = 0; i < 50; ++i) {
    const Vec3 p = rng.vec3(Real(-1), Real(1));
    const Real length = rng.uniform(Real(0.2), Real(2));
    const Vec3 q = p + rng.unit_vector() * length;
    const Shape s = Segment::create(p, q).value();
    const Transform pose = rng.pose(Real(2));
    const Vec3 u = glm::normalize(pose.apply_vector(q - p));
    const DistanceResult d = distance(s, pose, s, pose);
    const Real tol = test::narrow_tolerance(Real(4));
    EXPECT_NEAR(d.signed_distance, Real(0), tol);
    EXPECT_LE(std::abs(glm::dot(d.normal, u)), Real(1e-4)) << "normal along the segment";
    EXPECT_TRUE(intersect(s, pose, s, pose));
    Transform apart = pose;
    apart.position += eps * d.normal;
    EXPECT_NEAR(distance(s, pose, s, apart).signed_distance, eps, tol);
    // Collinear, overlapping half of the length.
    Transform slid = pose;
    slid.position += Real(0.5) * glm::length(q - p) * u;
    const DistanceResult dc = distance(s, pose, s, slid);
    EXPECT_NEAR(dc.signed_distance, Real(0), tol);
    EXPECT_LE(std::abs(glm::dot(dc.normal, u)), Real(1e-4)) << "collinear";
    slid.position += eps * dc.normal;
    EXPECT_NEAR(distance(s, pose, s, slid).signed_distance, eps, tol) << "collinear moved apart";
    const ContactManifold m = collide(s, pose, s, pose);
    ASSERT_GE(m.count, 1);
    for (int k = 0; k < m.count; ++k) EXPECT_NEAR(m.points[static_cast<std::size_t>(k)].depth, Real(0), tol);
    // Crossing at their midpoints in a common plane: the normal is the plane's.
    const Vec3 w = glm::normalize(glm::cross(u, rng.unit_vector()));
    const Vec3 mid = pose.apply(Real(0.5) * (p + q));
    const Shape cross_seg = Segment::create(mid - w, mid + w).value();
    const DistanceResult dx = distance(s, pose, cross_seg, Transform::identity());
    EXPECT_NEAR(dx.signed_distance, Real(0), tol);
    EXPECT_NEAR(std::abs(glm::dot(dx.normal, glm::normalize(glm::cross(u, w)))), Real(1), Real(1e-4)) << "crossing";
  }
}

// A point at the middle of a capsule's core: the cores touch and their Minkowski difference
// is a segment through the origin, too thin for EPA. The depth is the radius, along a normal
// across the axis (analytic); the witness on the capsule lies on its surface.
TEST(DegenerateRegression, PointAtCapsuleCentreHasRadiusDepthAcrossTheAxis) {
  test::Random rng(41);
  for (int i = 0; i < 200; ++i) {
    const Real r = rng.uniform(Real(0.05), Real(1));
    const Real h = rng.uniform(Real(0.01), Real(1.5));
    const Shape cap = Capsule::create(r, h).value();
    const Shape pt = Point::create().value();
    const Transform pc{rng.vec3(Real(-1), Real(1)), rng.rotation()};
    const Transform pp{pc.position, rng.rotation()};
    const Vec3 axis = pc.apply_vector(Vec3(Real(0), Real(0), Real(1)));
    const Real tol = test::narrow_tolerance(Real(2));
    for (int order = 0; order < 2; ++order) {
      const DistanceResult d = order == 0 ? distance(cap, pc, pt, pp) : distance(pt, pp, cap, pc);
      const std::string where = "case " + std::to_string(i) + " order " + std::to_string(order);
      EXPECT_NEAR(d.signed_distance, -r, tol) << where;
      EXPECT_LE(std::abs(glm::dot(d.normal, axis)), test::narrow_tolerance(Real(1)))
          << where << " normal along the axis";
      const Vec3& on_cap = order == 0 ? d.point_a : d.point_b;
      EXPECT_NEAR(test::surface_distance(cap, pc, on_cap), Real(0), tol) << where;
    }
  }
}

// A point on a segment's interior touches it; the normal must lie across the segment, so
// that moving the point by eps along it puts them eps apart (analytic).
TEST(DegenerateRegression, PointOnSegmentTouchesAcrossIt) {
  test::Random rng(43);
  for (int i = 0; i < 200; ++i) {
    const Vec3 b = rng.vec3(Real(-1), Real(1));
    const Shape seg = Segment::create(rng.vec3(Real(-1), Real(1)), b).value();
    const Segment& sg = std::get<Segment>(seg);
    const Transform ps{rng.vec3(Real(-1), Real(1)), rng.rotation()};
    const Real t = rng.uniform(Real(0.1), Real(0.9));
    const Vec3 on = ps.apply(sg.a() + t * (sg.b() - sg.a()));
    const Vec3 u = glm::normalize(ps.apply_vector(sg.b() - sg.a()));
    const Shape pt = Point::create().value();
    const Transform pp{on, rng.rotation()};
    const Real tol = test::narrow_tolerance(Real(2));
    const DistanceResult d = distance(seg, ps, pt, pp);
    const std::string where = "case " + std::to_string(i);
    EXPECT_NEAR(d.signed_distance, Real(0), tol) << where;
    EXPECT_LE(std::abs(glm::dot(d.normal, u)), test::narrow_tolerance(Real(1))) << where << " normal along the segment";
    const Real eps = Real(1e-2);
    const Transform apart{on + eps * d.normal, pp.rotation};
    EXPECT_NEAR(distance(seg, ps, pt, apart).signed_distance, eps, tol) << where;
  }
}

// Coincident box and segment: EPA's nearest face did not hold the origin's projection (by
// less than 1e-4 in barycentric terms) and clamping broke point_b = point_a + sd n by 2e-5.
TEST(DegenerateRegression, BoxSegmentCoincidentKeepsTheWitnessRelation) {
  const Shape box = Box::create(Vec3(Real(0.260667003), Real(0.233573666), Real(0.302929109))).value();
  const Shape seg = Segment::create(Vec3(Real(-0.41089321), Real(0.634891011), Real(-0.397019046)),
                                    Vec3(Real(0.392629666), Real(0.0568791072), Real(-0.257038096)))
                        .value();
  const Transform pose{Vec3(Real(0.930247806), Real(-0.923639132), Real(0.624902946)),
                       quat_xyzw(Real(0.753680971), Real(-0.0947318618), Real(-0.649748261), Real(-0.0286018279))};
  const DistanceResult d = distance(box, pose, seg, pose);
  const Real tol = test::narrow_tolerance(Real(1));
  EXPECT_LT(d.signed_distance, Real(0));
  EXPECT_LE(glm::length(d.point_a + d.signed_distance * d.normal - d.point_b), tol);
  EXPECT_NEAR(test::surface_distance(box, pose, d.point_a), Real(0), tol);
  EXPECT_NEAR(test::surface_distance(seg, pose, d.point_b), Real(0), tol);
}

// Moving both shapes by the same far offset must not change the answer beyond the rounding
// of the far coordinates (the solve is sized by the pair, not by its distance from the
// origin): every generic-path pair of curved shapes, at the origin and 1e4 away.
TEST(DegenerateRegression, FarOffsetKeepsTheAnswer) {
  const ShapeType curved[] = {ShapeType::Segment,  ShapeType::Triangle, ShapeType::Box,       ShapeType::Capsule,
                              ShapeType::Cylinder, ShapeType::Cone,     ShapeType::Ellipsoid, ShapeType::ConvexHull};
  const Vec3 far(Real(1e4), Real(-1e4), Real(1e4));
  for (ShapeType ta : curved) {
    for (ShapeType tb : curved) {
      test::Random rng(47 + std::uint64_t(ta) * 31u + std::uint64_t(tb));
      for (int i = 0; i < 6; ++i) {
        const Shape a = test::random_shape(rng, ta);
        const Shape b = test::random_shape(rng, tb);
        const Transform pa{rng.vec3(Real(-0.3), Real(0.3)), rng.rotation()};
        const Transform pb{rng.vec3(Real(-0.3), Real(0.3)), rng.rotation()};
        const DistanceResult d0 = distance(a, pa, b, pb);
        const DistanceResult d1 =
            distance(a, Transform{pa.position + far, pa.rotation}, b, Transform{pb.position + far, pb.rotation});
        const Real tol = test::narrow_tolerance(Real(2)) + Real(256) * kEpsilon * Real(1e4);
        EXPECT_NEAR(d1.signed_distance, d0.signed_distance, tol) << pair_label(ta, tb) << " case " << i;
        EXPECT_NEAR(test::surface_distance(a, Transform{pa.position + far, pa.rotation}, d1.point_a), Real(0), tol)
            << pair_label(ta, tb) << " case " << i;
      }
    }
  }
}

}  // namespace test_degenerate
}  // namespace proxima
