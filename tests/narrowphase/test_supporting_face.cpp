// Supporting features: every point lies on the shape's surface (the shape's own
// closest_point), the feature contains the shape's support point in the direction (its
// largest dot product equals the support value), polygons are convex and counter-clockwise
// about their unit normal, and curved shapes give a face only within the documented angle.
#include <gtest/gtest.h>

#include <proxima/shapes/shape.hpp>

#include <cmath>
#include <vector>

#include "narrowphase/supporting_face.hpp"
#include "support/random.hpp"

namespace proxima::test {
namespace test_supporting_face {

constexpr bool kFloat = sizeof(Real) == 4;

template <class S>
void check_shape(const S& shape, Real scale, bool exact_support, Random& rng, int count = 400) {
  const Real tol = (kFloat ? Real(5e-5) : Real(1e-11)) * scale;
  for (int n = 0; n < count; ++n) {
    const Transform pose = rng.pose(scale);
    const Vec3 dir = rng.unit_vector();
    const narrow::SupportingFace f = narrow::supporting_face(shape, pose, dir);
    ASSERT_GE(f.count, 1);
    ASSERT_LE(f.count, narrow::kMaxFacePoints);
    EXPECT_NEAR(glm::length(f.normal), 1, 1e-5);
    EXPECT_GT(glm::dot(f.normal, dir), 0) << n;
    const Vec3 sup = pose.apply(shape.core_support(pose.inverse_apply_vector(dir)));
    Real best = -std::numeric_limits<Real>::infinity();
    for (int i = 0; i < f.count; ++i) {
      const Vec3 local = pose.inverse_apply(f.points[i]);
      if (shape.core_radius() == Real(0)) {
        EXPECT_LE(std::abs(shape.closest_point(local).signed_distance), tol) << n << " point " << i;
      } else {
        EXPECT_NEAR(shape.closest_point(local).signed_distance, -shape.core_radius(), tol);
      }
      EXPECT_LE(glm::dot(f.points[i], dir), glm::dot(sup, dir) + tol);
      best = std::max(best, glm::dot(f.points[i], dir));
    }
    if (exact_support || f.count == 1) {
      EXPECT_NEAR(best, glm::dot(sup, dir), tol) << n;
    } else {
      // A face within acos(kCurvedFaceCosine) of the direction: its points lag the support
      // value by at most (1 - cos) times the shape's size.
      EXPECT_GE(best, glm::dot(sup, dir) - Real(0.2) * scale);
    }
    if (f.count >= 3) {
      for (int i = 0; i < f.count; ++i) {
        const Vec3& p0 = f.points[i];
        const Vec3& p1 = f.points[(i + 1) % f.count];
        const Vec3& p2 = f.points[(i + 2) % f.count];
        EXPECT_GT(glm::dot(glm::cross(p1 - p0, p2 - p1), f.normal), 0) << n << " corner " << i;
        EXPECT_NEAR(glm::dot(p1 - p0, f.normal), 0, tol);
      }
    }
  }
}

TEST(SupportingFace, PolyhedraAndFlatShapes) {
  Random rng(11);
  check_shape(Box::create(Vec3(1, Real(0.5), 2)).value(), Real(2), true, rng);
  check_shape(Triangle::create(Vec3(0, 0, 0), Vec3(1, 0, Real(0.2)), Vec3(0, 1, 0)).value(), Real(2), true, rng);
  check_shape(Segment::create(Vec3(-1, 0, 0), Vec3(1, Real(0.5), 0)).value(), Real(2), true, rng);
  check_shape(Point::create().value(), Real(2), true, rng);
  std::vector<Vec3> cloud;
  for (int i = 0; i < 40; ++i) cloud.push_back(rng.vec3(-1, 1));
  check_shape(ConvexHull::create(cloud).value(), Real(2), true, rng);
  check_shape(Capsule::create(Real(0.3), Real(1)).value(), Real(2), true, rng);
  check_shape(Sphere::create(Real(0.7)).value(), Real(2), true, rng);
}

TEST(SupportingFace, CurvedShapes) {
  Random rng(12);
  const Cylinder cyl = Cylinder::create(Real(0.5), Real(1)).value();
  const Cone cone = Cone::create(Real(0.6), Real(0.8)).value();
  check_shape(cyl, Real(2), false, rng);
  check_shape(cone, Real(2), false, rng);
  check_shape(Ellipsoid::create(Vec3(1, Real(0.5), Real(0.3))).value(), Real(2), true, rng);
  // Along the axis: the cap (kRimPoints points, normal +z); across: the side line.
  const Transform id;
  const auto cap = narrow::supporting_face(cyl, id, Vec3(0, 0, 1));
  EXPECT_EQ(cap.count, narrow::kRimPoints);
  EXPECT_NEAR(cap.normal.z, 1, 1e-6);
  const auto side = narrow::supporting_face(cyl, id, Vec3(1, 0, Real(0.05)));
  EXPECT_EQ(side.count, 2);
  const auto tilted = narrow::supporting_face(cyl, id, Vec3(1, 0, 1));
  EXPECT_EQ(tilted.count, 1);
  const auto base = narrow::supporting_face(cone, id, Vec3(0, 0, -1));
  EXPECT_EQ(base.count, narrow::kRimPoints);
  // Cone slant normal: (2h, r) in the (radial, z) plane.
  const auto slant = narrow::supporting_face(cone, id, Vec3(Real(1.6), 0, Real(0.6)));
  EXPECT_EQ(slant.count, 2);
  EXPECT_EQ(narrow::supporting_face(cone, id, Vec3(0, 0, 1)).count, 1);
}

TEST(SupportingFace, BoxFaceIdsAreCornerBits) {
  const Box box = Box::create(Vec3(1, 2, 3)).value();
  const auto f = narrow::supporting_face(box, {}, Vec3(0, 0, 1));
  EXPECT_EQ(f.index, 5u);
  for (int i = 0; i < 4; ++i) {
    EXPECT_NEAR(f.points[i].z, 3, 0);
    EXPECT_EQ(f.ids[i] & 4u, 4u);
    EXPECT_EQ(f.ids[i] & 1u, f.points[i].x > 0 ? 1u : 0u);
  }
}

}  // namespace test_supporting_face
}  // namespace proxima::test
