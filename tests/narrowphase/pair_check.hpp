#pragma once
// Invariant checks shared by the narrow-phase pair tests: the sign convention, the normal,
// the witnesses as extreme points along the normal, agreement with an independent reference
// distance or depth, the flip of intersect when B moves across the contact along the normal,
// and the manifold's agreement with the distance query.
#include <gtest/gtest.h>

#include <proxima/core/tolerance.hpp>
#include <proxima/narrowphase/contact.hpp>

#include <string>

#include "narrowphase/pair_reference.hpp"
// The closed-form pair routines the checks call by qualified name (narrow::pair_distance):
// declared before the templates below so that qualified lookup finds them.
#include "narrowphase/pairs_rounded.hpp"

namespace proxima::test {

// What the caller knows independently of the code under test.
struct Reference {
  bool has_distance = false;  // `distance` is the exact signed distance (cores apart)
  LD distance = 0;
  bool check_depth = true;  // penetrating: compare the depth to the sampled minimum overlap
  bool on_surfaces = true;  // witnesses lie on the surfaces (closest_point), also when overlapping
};

template <class A, class B>
void check_pair(const A& a, const Transform& pa, const B& b, const Transform& pb, const Reference& ref, Real tol,
                Real contact_distance, const std::string& ctx) {
  PairRequest request;
  request.contact_distance = contact_distance;
  const DistanceResult d = narrow::pair_distance(a, pa, b, pb, request, nullptr);
  ASSERT_TRUE(std::isfinite(d.signed_distance)) << ctx;
  ASSERT_TRUE(is_finite(d.normal) && is_finite(d.point_a) && is_finite(d.point_b)) << ctx;
  EXPECT_NEAR(glm::length(d.normal), Real(1), Real(1e-4)) << ctx;
  EXPECT_LE(glm::length(d.point_b - (d.point_a + d.signed_distance * d.normal)), tol) << ctx;
  if (d.signed_distance > tol) {
    EXPECT_EQ(d.status, PairStatus::Separated) << ctx;
  }
  if (d.signed_distance < -tol) {
    EXPECT_EQ(d.status, PairStatus::Penetrating) << ctx;
  }
  // The signed distance along the normal, and the witnesses as the extremes along it.
  const LVec n = ld(d.normal) / lnorm(ld(d.normal));
  EXPECT_NEAR(double(-overlap_along(a, pa, b, pb, n)), double(d.signed_distance), double(tol)) << ctx;
  EXPECT_NEAR(double(glm::dot(n, ld(d.point_a))), double(support_world(a, pa, n)), double(tol)) << ctx;
  EXPECT_NEAR(double(glm::dot(n, ld(d.point_b))), double(-support_world(b, pb, -n)), double(tol)) << ctx;
  if (ref.has_distance) {
    EXPECT_NEAR(double(d.signed_distance), double(ref.distance), double(tol)) << ctx;
  } else if (ref.check_depth) {
    // Optimality: no sampled direction separates with less motion.
    const LD best = min_overlap(a, pa, b, pb);
    EXPECT_LE(double(-d.signed_distance), double(best) + double(tol)) << ctx;
  }
  if (ref.on_surfaces) {
    EXPECT_LE(std::abs(a.closest_point(pa.inverse_apply(d.point_a)).signed_distance), tol) << ctx;
    EXPECT_LE(std::abs(b.closest_point(pb.inverse_apply(d.point_b)).signed_distance), tol) << ctx;
  }
  // intersect agrees with the distance; moving B across the contact flips it.
  // (the touching rule of contact.hpp: within max(contact distance, the pair's tolerance))
  EXPECT_EQ(narrow::pair_intersect(a, pa, b, pb, request, nullptr), in_contact(d, request)) << ctx;
  const Real eps = Real(8) * tol;
  PairRequest plain;
  Transform apart = pb;
  apart.position += (-d.signed_distance + eps) * d.normal;
  Transform into = pb;
  into.position += (-d.signed_distance - eps) * d.normal;
  EXPECT_FALSE(narrow::pair_intersect(a, pa, b, apart, plain, nullptr)) << ctx << " moved apart";
  EXPECT_TRUE(narrow::pair_intersect(a, pa, b, into, plain, nullptr)) << ctx << " moved into";
  // The manifold.
  const ContactManifold m = narrow::pair_collide(a, pa, b, pb, request, nullptr);
  EXPECT_EQ(m.count > 0, in_contact(d, request)) << ctx;
  EXPECT_LE(m.count, request.max_contacts) << ctx;
  if (m.count > 0) {
    EXPECT_LE(glm::length(m.normal - d.normal), Real(0.05)) << ctx;
    Real deepest = -std::numeric_limits<Real>::infinity();
    for (int i = 0; i < m.count; ++i) {
      const ContactPoint& c = m.points[static_cast<std::size_t>(i)];
      EXPECT_LE(glm::length(c.point_b - (c.point_a - c.depth * c.normal)), tol) << ctx << " point " << i;
      EXPECT_LE(glm::length(c.normal - m.normal), Real(0)) << ctx;
      EXPECT_GE(c.depth, -(contact_distance + Real(2) * tol)) << ctx << " point " << i;
      deepest = std::max(deepest, c.depth);
    }
    EXPECT_EQ(m.points[0].depth, deepest) << ctx << " deepest first";
    EXPECT_NEAR(double(deepest), double(-d.signed_distance),
                double(tol) + 2e-3 * std::max(1.0, std::abs(double(d.signed_distance))))
        << ctx;
  }
}

// Tolerance on distances at coordinate magnitude `scale`.
inline Real pair_tol(Real scale) { return Real(256) * kEpsilon * std::max(Real(1), scale); }

}  // namespace proxima::test
