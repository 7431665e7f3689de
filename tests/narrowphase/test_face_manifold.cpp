// The generic clipped manifold (generic_collide.hpp, face_clipping.hpp): flat contacts get
// up to four points whose area matches the analytic overlap, rounded cores add their
// radius, tilted features keep one point; checked against closed-form configurations and,
// on random box pairs, against the exact box-box distance (points on both surfaces, depths
// bounded by the pair's).
#include <gtest/gtest.h>

#include <proxima/shapes/shape.hpp>

#include <cmath>
#include <vector>

#include "narrowphase/face_clipping.hpp"
#include "narrowphase/pairs_polyhedral.hpp"
#include "narrowphase/supporting_face.hpp"
// The generic manifold over the box-box distance (the template, not the box-box routine).
#include "narrowphase/generic_collide.hpp"
#include "polytope_reference.hpp"
#include "support/random.hpp"

namespace proxima::test {
namespace test_face_manifold {

constexpr bool kFloat = sizeof(Real) == 4;

template <class A, class B>
ContactManifold clip_along(const A& a, const Transform& pa, const B& b, const Transform& pb, const Vec3& n,
                           Real contact_distance = Real(0.1)) {
  PairRequest req;
  req.contact_distance = contact_distance;
  ContactManifold m;
  m.normal = n;
  const auto fa = narrow::supporting_face(a, pa, n);
  const auto fb = narrow::supporting_face(b, pb, -n);
  if (!narrow::clipped_manifold(fa, fb, n, req, m)) m.count = 0;
  return m;
}

TEST(FaceManifold, CylinderRestingOnBox) {
  const Box ground = Box::create(Vec3(3, 3, 1)).value();
  const Cylinder cyl = Cylinder::create(Real(0.5), Real(1)).value();
  Transform pc;
  pc.position = Vec3(Real(0.4), Real(-0.3), Real(1.98));  // 0.02 deep
  const ContactManifold m = clip_along(ground, {}, cyl, pc, Vec3(0, 0, 1));
  ASSERT_EQ(m.count, 4);
  // The largest quadrilateral of the regular octagon inscribed in the rim: a square of
  // area 2 r^2.
  EXPECT_NEAR(manifold_area(m), Real(2 * 0.25), Real(1e-5));
  for (int i = 0; i < 4; ++i) {
    EXPECT_NEAR(m.points[i].depth, Real(0.02), Real(1e-5));
    EXPECT_NEAR(glm::length(Vec2(m.points[i].point_b - pc.position)), Real(0.5), Real(1e-5));
    EXPECT_NEAR(m.points[i].point_a.z, 1, Real(1e-6));
  }
  // Lying on its side: the side line gives two points.
  Transform lying;
  lying.position = Vec3(0, 0, Real(1.49));
  lying.rotation = glm::angleAxis(kPi / 2, Vec3(1, 0, 0));
  const ContactManifold s = clip_along(ground, {}, cyl, lying, Vec3(0, 0, 1));
  ASSERT_EQ(s.count, 2);
  EXPECT_NEAR(glm::length(s.points[0].point_a - s.points[1].point_a), Real(2), Real(1e-5));
  // Tilted by 30 degrees: one point (the caller's distance witness).
  Transform tilted = pc;
  tilted.rotation = glm::angleAxis(Real(0.5), Vec3(1, 0, 0));
  EXPECT_EQ(clip_along(ground, {}, cyl, tilted, Vec3(0, 0, 1)).count, 0);
}

TEST(FaceManifold, CapsuleOnBoxAddsRadius) {
  const Box ground = Box::create(Vec3(3, 3, 1)).value();
  const Capsule cap = Capsule::create(Real(0.25), Real(0.8)).value();
  Transform pc;
  pc.position = Vec3(0, 0, Real(1.2));  // core 0.2 above, radius 0.25: 0.05 deep
  pc.rotation = glm::angleAxis(kPi / 2, Vec3(0, 1, 0));
  const ContactManifold m = clip_along(ground, {}, cap, pc, Vec3(0, 0, 1));
  ASSERT_EQ(m.count, 2);
  for (int i = 0; i < 2; ++i) {
    EXPECT_NEAR(m.points[i].depth, Real(0.05), Real(1e-5));
    EXPECT_NEAR(m.points[i].point_b.z, Real(0.95), Real(1e-5));
    EXPECT_NEAR(m.points[i].point_a.z, 1, Real(1e-5));
  }
  // Hanging over the edge: clipped to the box.
  pc.position.x = Real(3.4);
  const ContactManifold h = clip_along(ground, {}, cap, pc, Vec3(0, 0, 1));
  ASSERT_EQ(h.count, 2);
  EXPECT_NEAR(std::max(h.points[0].point_a.x, h.points[1].point_a.x), 3, Real(1e-5));
}

TEST(FaceManifold, HullsFaceToFace) {
  std::vector<Vec3> cube;
  for (int c = 0; c < 8; ++c) cube.emplace_back((c & 1) ? 1 : -1, (c & 2) ? 1 : -1, (c & 4) ? 1 : -1);
  const ConvexHull hull = ConvexHull::create(cube).value();
  Transform pb;
  pb.position = Vec3(Real(0.5), Real(0.5), Real(1.95));
  const ContactManifold m = clip_along(hull, {}, hull, pb, Vec3(0, 0, 1));
  ASSERT_EQ(m.count, 4);
  EXPECT_NEAR(manifold_area(m), Real(1.5 * 1.5), Real(1e-4));
  // Speculative: apart by 0.05 with a contact distance of 0.1 gives negative depths.
  pb.position.z = Real(2.05);
  const ContactManifold s = clip_along(hull, {}, hull, pb, Vec3(0, 0, 1));
  ASSERT_EQ(s.count, 4);
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(s.points[i].depth, Real(-0.05), Real(1e-5));
  EXPECT_EQ(clip_along(hull, {}, hull, pb, Vec3(0, 0, 1), Real(0.01)).count, 0);
}

TEST(FaceManifold, GenericTemplateOnRandomBoxes) {
  Random rng(31);
  const Real tol = kFloat ? Real(1e-3) : Real(1e-9);
  int multi = 0;
  for (int n = 0; n < 2000; ++n) {
    const Box a = Box::create(rng.vec3(Real(0.2), Real(1.5))).value();
    const Box b = Box::create(rng.vec3(Real(0.2), Real(1.5))).value();
    const Transform pa = rng.pose(Real(1.2));
    Transform pb = rng.pose(Real(1.2));
    if (n % 2 == 0) pb.rotation = pa.rotation * glm::angleAxis(rng.uniform(-Real(0.05), Real(0.05)), Vec3(0, 0, 1));
    PairRequest req;
    req.contact_distance = Real(0.05);
    const DistanceResult d = narrow::pair_distance(a, pa, b, pb, req, nullptr);
    const ContactManifold m = narrow::pair_collide<Box, Box>(a, pa, b, pb, req, nullptr);
    SCOPED_TRACE(n);
    if (d.signed_distance > req.contact_distance) {
      EXPECT_EQ(m.count, 0);
      continue;
    }
    ASSERT_GE(m.count, 1);
    multi += m.count > 1 ? 1 : 0;
    EXPECT_EQ(m.normal, d.normal);
    for (int i = 0; i < m.count; ++i) {
      const ContactPoint& c = m.points[i];
      EXPECT_LE(std::abs(a.closest_point(pa.inverse_apply(c.point_a)).signed_distance), tol);
      EXPECT_LE(std::abs(b.closest_point(pb.inverse_apply(c.point_b)).signed_distance), tol);
      EXPECT_LE(c.depth, -d.signed_distance + tol);
      EXPECT_LE(max_abs_component(c.point_a - c.depth * c.normal - c.point_b), tol);
    }
  }
  EXPECT_GT(multi, 200);
}

}  // namespace test_face_manifold
}  // namespace proxima::test
