// The one touching rule of contact.hpp on every ordered pair of shape types (the 11 convex
// kinds, meshes and compounds, mirrored cells included): at near-touching poses, gaps of
// +-1e-7 ... +-1e-3 of the pair's size and +-0.5 / +-2 times the pair's own tolerance (so
// that both precisions see touching and just-apart pairs), intersect answers exactly
// in_contact(distance), and collide gives contacts exactly then; for convex pairs collide's
// status is distance's. The poses come from seeded random pairs, B moved along the distance
// normal to the target gap. Named cases: the sphere and box 9.5e-7 apart (touching in float:
// a hit with one contact of depth about 0 in every query).
#include <gtest/gtest.h>

#include <proxima/narrowphase/narrowphase.hpp>
#include <proxima/shapes/shape.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "narrowphase/narrowphase_test_util.hpp"
#include "support/solid_test_meshes.hpp"
#include "sweep_size.hpp"

namespace proxima {
namespace test_touching_rule {

using test::TypePair;

// Every ordered pair of shape types except two half-spaces (only their boolean answer means
// anything).
std::vector<TypePair> every_pair() {
  return test::type_pairs(kShapeTypeCount, [](ShapeType a, ShapeType b) {
    return !(a == ShapeType::HalfSpace && b == ShapeType::HalfSpace);
  });
}

// A random shape of any type: test::random_shape for the convex kinds, an icosphere or torus
// mesh, or a compound of a sphere, a box and a capsule at random local poses.
Shape any_shape(test::Random& rng, ShapeType t) {
  if (t == ShapeType::TriangleMesh) {
    const Real r = rng.uniform(Real(0.4), Real(1.2));
    if (rng.integer(0, 1) == 0) return TriangleMesh::create(test::icosphere_mesh(1, r)).value();
    return TriangleMesh::create(test::torus_mesh(r, Real(0.3) * r, 12, 8)).value();
  }
  if (t == ShapeType::Compound) {
    std::vector<CompoundChild> kids;
    kids.push_back({Sphere::create(rng.uniform(Real(0.2), Real(0.5))).value(), rng.pose(Real(0.6))});
    kids.push_back({Box::create(test::random_extents(rng, Real(0.4))).value(), rng.pose(Real(0.6))});
    kids.push_back({Capsule::create(Real(0.2), Real(0.3)).value(), rng.pose(Real(0.6))});
    return Compound::create(std::move(kids)).value();
  }
  return test::random_shape(rng, t);
}

// Counts of what the sweep saw, for the check that it saw every outcome.
struct Seen {
  int cases = 0;
  int touching = 0;
  int hits = 0;
  int misses = 0;
};

// One pose: intersect, collide and in_contact(distance) agree (and collide's status is
// distance's for a convex pair). Returns a description of the disagreement, or "".
std::string disagreement(const Shape& a, const Transform& pa, const Shape& b, const Transform& pb,
                         const PairRequest& request, Seen& seen) {
  const DistanceResult d = distance(a, pa, b, pb, request);
  const bool hit = intersect(a, pa, b, pb, request);
  const ContactManifold m = collide(a, pa, b, pb, request);
  if (!std::isfinite(d.signed_distance)) return "";
  const bool contact = in_contact(d, request);
  ++seen.cases;
  if (d.status == PairStatus::Touching) ++seen.touching;
  if (contact) {
    ++seen.hits;
  } else {
    ++seen.misses;
  }
  const bool convex = is_convex(shape_type(a)) && is_convex(shape_type(b));
  std::string why;
  if (hit != contact) why += " intersect!=in_contact(distance)";
  if ((m.count > 0) != contact) why += " collide!=in_contact(distance)";
  if (d.status == PairStatus::Touching && !hit) why += " touching_but_no_hit";
  if (convex && m.status != d.status) why += " collide_status!=distance_status";
  if (why.empty()) return "";
  std::ostringstream o;
  o.precision(9);
  o << why << ": sd=" << d.signed_distance << " tol=" << d.tolerance << " status=" << test::status_name(d.status)
    << " collide_status=" << test::status_name(m.status) << " hit=" << hit << " count=" << m.count
    << " cd=" << request.contact_distance << " A=" << test::describe(a, pa) << " B=" << test::describe(b, pb);
  return o.str();
}

class TouchingRule : public testing::TestWithParam<TypePair> {};

TEST_P(TouchingRule, IntersectDistanceCollideAgreeNearContact) {
  const TypePair p = GetParam();
  const std::uint64_t seed = 0x5eed7a11ull ^ (std::uint64_t(p.a) * 257u + std::uint64_t(p.b));
  test::Random rng(seed);
  const bool composite = !is_convex(p.a) || !is_convex(p.b);
  const int cases = test::sweep_size(composite ? 6 : 24);
  // Gaps relative to the pair's size, then multiples of the pair's own tolerance.
  const std::array<Real, 10> relative{Real(1e-7),  Real(-1e-7), Real(1e-6),  Real(-1e-6), Real(1e-5),
                                      Real(-1e-5), Real(1e-4),  Real(-1e-4), Real(1e-3),  Real(-1e-3)};
  const std::array<Real, 5> of_tolerance{Real(0), Real(0.5), Real(-0.5), Real(2), Real(-2)};
  Seen seen;
  std::vector<std::string> failures;
  int failed = 0;
  for (int i = 0; i < cases; ++i) {
    const Shape a = any_shape(rng, p.a);
    const Shape b = any_shape(rng, p.b);
    const Transform pa = rng.pose(Real(0.5));
    const Transform pb = rng.pose(Real(1.5));
    const DistanceResult d0 = distance(a, pa, b, pb);
    if (!std::isfinite(d0.signed_distance)) continue;
    const Real size = std::max({test::shape_scale(a), test::shape_scale(b), Real(1)});
    std::vector<Real> gaps;
    for (Real g : relative) gaps.push_back(g * size);
    for (Real k : of_tolerance) gaps.push_back(k * d0.tolerance);
    for (Real gap : gaps) {
      Transform moved = pb;
      moved.position += (gap - d0.signed_distance) * d0.normal;
      for (Real cd : {Real(0), Real(1e-4) * size}) {
        PairRequest request;
        request.contact_distance = cd;
        const std::string why = disagreement(a, pa, b, moved, request, seen);
        if (why.empty()) continue;
        ++failed;
        if (failures.size() < 4) failures.push_back("case " + std::to_string(i) + why);
      }
    }
  }
  std::string detail;
  for (const std::string& f : failures) detail += "\n  " + f;
  EXPECT_EQ(failed, 0) << failed << " of " << seen.cases << " poses disagree (seed " << seed << ")" << detail;
  // The sweep sees hits, misses and touching pairs (a half-space side, or a point or segment
  // against a mesh, may leave no miss or no touch in a short sweep: only the hits count).
  EXPECT_GT(seen.hits, 0);
  if (p.a != ShapeType::HalfSpace && p.b != ShapeType::HalfSpace) {
    EXPECT_GT(seen.misses, 0);
  }
  if (!composite && p.a != ShapeType::HalfSpace && p.b != ShapeType::HalfSpace) {
    EXPECT_GT(seen.touching, 0);
  }
}

INSTANTIATE_TEST_SUITE_P(EveryPair, TouchingRule, testing::ValuesIn(every_pair()), test::type_pair_name);

// The case: a sphere and a box 9.5e-7 apart. In float that is within the pair's
// tolerance: touching, so every query calls it a hit, and collide gives one contact of depth
// about 0 with the same status. In double it is a gap: every query says no.
TEST(TouchingRule, SphereNearBoxIsOneAnswerInEveryQuery) {
  const Sphere sphere = Sphere::create(Real(0.5)).value();
  const Box box = Box::create(Vec3(Real(1))).value();
  const Transform pose_box{Vec3(Real(0)), Quat(Real(1), Real(0), Real(0), Real(0))};
  const Transform pose_sphere{Vec3(Real(1.5) + Real(9.5e-7), Real(0.2), Real(-0.3)),
                              Quat(Real(1), Real(0), Real(0), Real(0))};
  const DistanceResult d = distance(sphere, pose_sphere, box, pose_box);
  const bool hit = intersect(sphere, pose_sphere, box, pose_box);
  const ContactManifold m = collide(sphere, pose_sphere, box, pose_box);
  const bool touching = test::kFloatBuild;
  EXPECT_EQ(d.status, touching ? PairStatus::Touching : PairStatus::Separated);
  EXPECT_EQ(hit, touching);
  EXPECT_EQ(m.count > 0, touching);
  EXPECT_EQ(m.status, d.status);
  if (m.count > 0) {
    EXPECT_NEAR(m.points[0].depth, Real(0), d.tolerance);
  }
}

// Sweep EveryPair/TouchingRule.IntersectDistanceCollideAgreeNearContact/triangle_cone at
// 139 times its size, case 884 (double): a triangle 7.3e-14 from a cone (3.2 tolerances;
// the long double gap along the answer's normal 7.29e-14), and intersect answered a hit:
// boolean GJK ended on a sliver tetrahedron (edges 1.2 and 2.7e-5 long) whose origin depth
// enclosed_depth computed as 2.9e-12, above the band (1.44e-12), where in long double the
// origin lies 9.9e-13 outside one face. The depth now subtracts its faces' rounding.
TEST(TouchingRule, SliverTetrahedronProvesNoOverlap) {
  const auto v = test::printed;
  const Shape a = Triangle::create(v(0.52452940948623494, 0.5429927750859973, 0.49020646637683685),
                                   v(-0.27448580653725696, 0.019339924313958035, 0.6909858882518336),
                                   v(-0.21739902626876484, 0.70859045292352296, -0.29665320345181878))
                      .value();
  const Shape b = Cone::create(Real(0.017170096502798604), Real(0.50547174151435648)).value();
  const Transform pa{v(-0.09855034856200473, 0.1326429125870302, -0.33979061989833248),
                     Quat(Real(-0.31885505959539001), Real(-0.43272527343740474), Real(0.43348599296942725),
                          Real(0.72330504118128003))};
  const Transform pb{v(0.25967484123915863, 0.28364688010002381, 0.64168103452590586),
                     Quat(Real(0.78261253734606395), Real(-0.36827395361017035), Real(0.13839059556190769),
                          Real(0.48243129515104038))};
  const PairRequest request{};
  const DistanceResult d = distance(a, pa, b, pb, request);
  EXPECT_EQ(intersect(a, pa, b, pb, request), in_contact(d, request)) << "sd=" << d.signed_distance;
  EXPECT_EQ(collide(a, pa, b, pb, request).count > 0, in_contact(d, request));
}

// The distance's accuracy near contact, with no reference needed: moving B along the pair's
// normal by a small step changes a positive distance by exactly that step. For every convex
// pair (half-spaces aside) at gaps 1e-3, 1e-5, 1e-7 and 0 of the pair's size, the change
// must match the step within twice the answer's own tolerance. The double build's GJK on
// curved pairs stalls near contact and is off by up to about 2e-7 (docs/validation.md,
// "GJK near contact"): open in the double and sanitizer builds (tests/known_failures.txt).
TEST(DistanceShift, MovingBAlongTheNormalChangesTheDistanceByTheStep) {
  test::Random rng(0x5417ull);
  const int cases = test::sweep_size(12);
  std::string worst_by_pair;
  int failed_pairs = 0;
  for (int i = 0; i < kConvexShapeTypeCount; ++i) {
    for (int j = 0; j < kConvexShapeTypeCount; ++j) {
      const auto ta = static_cast<ShapeType>(i);
      const auto tb = static_cast<ShapeType>(j);
      if (ta == ShapeType::HalfSpace || tb == ShapeType::HalfSpace) continue;
      double worst = 0;
      double worst_tolerance = 0;
      for (int k = 0; k < cases; ++k) {
        const Shape a = test::random_shape(rng, ta);
        const Shape b = test::random_shape(rng, tb);
        const Transform pa = rng.pose(Real(0.5));
        Transform pb = rng.pose(Real(1.5));
        const DistanceResult d0 = distance(a, pa, b, pb);
        if (!std::isfinite(d0.signed_distance)) continue;
        const Real size = std::max({test::shape_scale(a), test::shape_scale(b), Real(1)});
        // The reference pose: B 1e-3 of the size away along the normal.
        pb.position += (Real(1e-3) * size - d0.signed_distance) * d0.normal;
        const DistanceResult ref = distance(a, pa, b, pb);
        if (!(ref.signed_distance > Real(0))) continue;
        for (const Real gap : {Real(1e-5), Real(1e-7), Real(0)}) {
          const Real step = gap * size - ref.signed_distance;
          Transform moved = pb;
          moved.position += step * ref.normal;
          const DistanceResult d = distance(a, pa, b, moved);
          const double error = std::abs(double(d.signed_distance) - double(ref.signed_distance) - double(step));
          if (error > 2.0 * double(ref.tolerance) && error > worst) {
            worst = error;
            worst_tolerance = double(ref.tolerance);
          }
        }
      }
      if (worst > 0) {
        ++failed_pairs;
        std::ostringstream o;
        o.precision(3);
        o << "\n  " << to_string(ta) << "_" << to_string(tb) << ": off by " << worst << " (tolerance "
          << worst_tolerance << ")";
        worst_by_pair += o.str();
      }
    }
  }
  EXPECT_EQ(failed_pairs, 0) << "pairs whose distance does not follow the step:" << worst_by_pair;
}

}  // namespace test_touching_rule
}  // namespace proxima
