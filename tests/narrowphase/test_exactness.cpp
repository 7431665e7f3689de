// Exactness of the narrow phase's distance on every ordered pair of bounded convex shapes, at
// random poses, sizes from 1e-3 to 1e3 and offsets up to 1e4, against long double references
// that share no code with the library (pair_reference.hpp: support functions written from
// the shapes' definitions):
//   - self-consistency: the overlap of the two shapes along the reported normal,
//     h_A(n) + h_B(-n) in long double, is the reported depth (minus the distance) within 8
//     ulps (double) / 64 ulps (float) of the pair's size, offsets included;
//   - the normal: where the reference minimum of that overlap over directions is smooth and
//     pinned (its Hessian's least eigenvalue at least 1e-2 of the size), the reported normal
//     lies within 1e-9 rad (double) / 1e-5 rad (float) of the reference's, or of 64 ulps of
//     the offset over the size, the rounding of the pose itself (cases where that exceeds
//     1e-2 rad, tiny shapes far out in float, pin no normal and are skipped).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "narrowphase/narrowphase_test_util.hpp"
#include "narrowphase/pair_reference.hpp"
#include "sweep_size.hpp"

namespace proxima {
namespace test_exactness {

using test::TypePair;

/// Every ordered pair of bounded convex shape types (half-spaces have no bounded support).
std::vector<TypePair> bounded_pairs() {
  return test::type_pairs(kConvexShapeTypeCount, [](ShapeType a, ShapeType b) {
    return a != ShapeType::HalfSpace && b != ShapeType::HalfSpace;
  });
}

constexpr double kUlpsAllowed = test::kFloatBuild ? 64.0 : 8.0;
constexpr double kAngleAllowed = test::kFloatBuild ? 1e-5 : 1e-9;

/// One drawn case: the shapes, their poses, and the answer.
struct Case {
  Shape a = Point::create().value();
  Shape b = Point::create().value();
  Transform pose_a;
  Transform pose_b;
  DistanceResult d;
  Real shape_size = Real(0);  ///< the larger shape's size
  Real size = Real(0);        ///< the pair's size: the shapes and their offsets
};

/// Draws case `i` of a pair: sizes log-uniform in [1e-3, 1e3], both shapes moved by one
/// offset up to 1e4 (half the cases near the origin).
Case draw(test::Random& rng, const TypePair& p, int i) {
  Case c;
  const Real s = test::log_uniform(rng, Real(1e-3), Real(1e3));
  const Vec3 offset = i % 2 == 0 ? Vec3(Real(0)) : rng.in_ball(Real(1e4));
  c.a = test::random_shape(rng, p.a, s);
  c.b = test::random_shape(rng, p.b, s);
  c.pose_a = rng.pose(Real(0.5) * s);
  c.pose_b = rng.pose(Real(1.8) * s);
  c.pose_a.position += offset;
  c.pose_b.position += offset;
  c.d = distance(c.a, c.pose_a, c.b, c.pose_b);
  c.shape_size = std::max({test::shape_scale(c.a), test::shape_scale(c.b), Real(1e-30)});
  c.size = std::max({c.shape_size, max_abs_component(c.pose_a.position), max_abs_component(c.pose_b.position)});
  return c;
}

std::string describe(const Case& c) {
  std::ostringstream o;
  o.precision(17);
  o << test::describe(c.a, c.pose_a) << " | " << test::describe(c.b, c.pose_b) << " sd=" << c.d.signed_distance
    << " status=" << int(c.d.status);
  return o.str();
}

class Exactness : public testing::TestWithParam<TypePair> {};

#ifdef NDEBUG
constexpr int kCases = 200;
#else
constexpr int kCases = 40;
#endif

std::uint64_t seed_of(const TypePair& p) { return 0xe4ac7ull ^ (std::uint64_t(p.a) * 977u + std::uint64_t(p.b) * 31u); }

TEST_P(Exactness, OverlapAlongTheNormalIsTheSignedDistance) {
  const TypePair p = GetParam();
  test::Random rng(seed_of(p));
  const int cases = test::sweep_size(kCases);
  double worst = 0;
  std::string worst_case;
  for (int i = 0; i < cases; ++i) {
    const Case c = draw(rng, p, i);
    ASSERT_TRUE(std::isfinite(c.d.signed_distance)) << describe(c);
    const test::LVec n = test::ld(c.d.normal) / test::lnorm(test::ld(c.d.normal));
    const test::LD overlap = test::overlap_along_shapes(c.a, c.pose_a, c.b, c.pose_b, n);
    const double ulps = double(std::abs(overlap + test::LD(c.d.signed_distance))) / (double(kEpsilon) * double(c.size));
    if (ulps > worst) {
      worst = ulps;
      std::ostringstream o;
      o.precision(17);
      o << describe(c) << " overlap=" << double(overlap) << " (" << ulps << " ulps)";
      worst_case = o.str();
    }
  }
  EXPECT_LE(worst, kUlpsAllowed) << "worst case: " << worst_case;
}

TEST_P(Exactness, NormalIsTheLongDoubleMinimumsWhereThatIsPinned) {
  const TypePair p = GetParam();
  test::Random rng(seed_of(p) + 1);
  const int cases = test::sweep_size(kCases);
  int pinned = 0;
  double worst = 0;
  std::string worst_case;
  for (int i = 0; i < cases; ++i) {
    const Case c = draw(rng, p, i);
    const test::LVec n = test::ld(c.d.normal) / test::lnorm(test::ld(c.d.normal));
    const auto overlap = [&](const test::LVec& u) {
      return test::overlap_along_shapes(c.a, c.pose_a, c.b, c.pose_b, u);
    };
    const test::DirectionMinimum ref = test::minimize_over_directions(overlap, n, test::LD(c.shape_size));
    if (!(ref.converged && ref.smooth && ref.curvature > test::LD(1e-2) * test::LD(c.shape_size))) continue;
    ++pinned;
    const double angle = double(test::lnorm(glm::cross(ref.normal, n)));
    const double allowed = std::max(kAngleAllowed, 64.0 * double(kEpsilon) * double(c.size / c.shape_size));
    if (allowed > 1e-2) continue;  // the pose's rounding alone turns the normal (float, tiny shapes far out)
    if (angle / allowed > worst) {
      worst = angle / allowed;
      std::ostringstream o;
      o << describe(c) << " angle=" << angle << " allowed=" << allowed;
      worst_case = o.str();
    }
  }
  EXPECT_LE(worst, 1.0) << pinned << " pinned cases; worst (angle over allowed): " << worst_case;
}

INSTANTIATE_TEST_SUITE_P(BoundedPairs, Exactness, testing::ValuesIn(bounded_pairs()), test::type_pair_name);

}  // namespace test_exactness
}  // namespace proxima
