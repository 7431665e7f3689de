#pragma once
// The checks every closed-form curved pair passes on one answer (test_cylinder_cylinder.cpp,
// test_cone_cone.cpp), against references that share no code with it (pair_reference.hpp,
// long double): the overlap of the two support functions along the reported normal is minus
// the signed distance (returned, in ulps of the pair's size, for the sweep's worst case), a
// search over directions finds no direction overlapping less, the witnesses lie on the
// surfaces (the test's own long-double surface distance), the generic ladder agrees to its
// own precision, and intersect and collide follow the touching rule on the distance.
#include <gtest/gtest.h>

#include <proxima/narrowphase/narrowphase.hpp>

#include <algorithm>
#include <cmath>
#include <string>

#include "narrowphase/generic_distance.hpp"
#include "narrowphase/narrowphase_test_util.hpp"
#include "narrowphase/pair_reference.hpp"

namespace proxima::test {

/// The closed forms' allowance: 8 ulps of the pair's size in double, 64 in float.
inline constexpr double kClosedFormUlps = kFloatBuild ? 64.0 : 8.0;

/// Checks `d`, the closed form's answer for (a, pa, b, pb); `surface(shape, pose, point)` is
/// the signed distance of a world point from a shape's surface in long double; `label` names
/// the case in failures. Returns the self-consistency error in ulps of the pair's size (the
/// shapes' and the positions').
template <class A, class B, class Surface>
double check_closed_form_answer(const A& a, const Transform& pa, const B& b, const Transform& pb,
                                const DistanceResult& d, Surface surface, const std::string& label) {
  const Real size = std::max(
      {shape_scale(Shape(a)), shape_scale(Shape(b)), max_abs_component(pa.position), max_abs_component(pb.position)});
  const LVec n = ld(d.normal) / lnorm(ld(d.normal));
  const LD overlap = overlap_along(a, pa, b, pb, n);
  const LD searched = min_overlap(a, pa, b, pb);
  EXPECT_GE(double(searched), double(-d.signed_distance) - kClosedFormUlps * double(kEpsilon) * double(size)) << label;
  const LD on_surface = LD(32) * LD(kEpsilon) * LD(size);
  EXPECT_LE(std::abs(surface(a, pa, d.point_a)), on_surface) << label;
  EXPECT_LE(std::abs(surface(b, pb, d.point_b)), on_surface) << label;
  const DistanceResult g = narrow::generic_distance(a, pa, b, pb, PairRequest{}, nullptr);
  EXPECT_NEAR(g.signed_distance, d.signed_distance, Real(1e-4) * size) << label;
  EXPECT_EQ(intersect(a, pa, b, pb), in_contact(d, PairRequest{})) << label;
  EXPECT_EQ(collide(a, pa, b, pb).count > 0, in_contact(d, PairRequest{})) << label;
  return double(std::abs(overlap + LD(d.signed_distance))) / (double(kEpsilon) * double(size));
}

}  // namespace proxima::test
