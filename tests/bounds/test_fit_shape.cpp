// Bounding volumes of placed shapes (every shape type): each volume contains the shape's
// support points in thousands of directions and points sampled inside it (the shape's own
// contains on its box), all mapped by the pose; the box and k-DOP bounds are attained by
// support points (tight) and the sphere is within a few percent of the minimal sphere of
// dense surface samples (Welzl on them).
#include <gtest/gtest.h>

#include <proxima/bounds/fit_shape.hpp>
#include <proxima/bounds/fit_shape_capsule.hpp>
#include <proxima/bounds/fit_sphere.hpp>
#include <proxima/core/tolerance.hpp>
#include <proxima/shapes/shape.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include "bounds/test_bounds_support.hpp"
#include "support/random.hpp"

namespace proxima {
namespace test_fit_shape {

template <class S>
std::vector<Vec3> sample_world(const S& shape, const Transform& pose, test::Random& rng, bool bounded) {
  std::vector<Vec3> pts;
  for (int i = 0; i < 1500; ++i) pts.push_back(support(shape, pose, rng.unit_vector()));
  for (int i = 0; i < 13; ++i) {
    const Vec3 d = kdop_base_direction(i);
    pts.push_back(support(shape, pose, d));
    pts.push_back(support(shape, pose, -d));
  }
  if (bounded) {
    const Aabb box = shape.local_aabb();
    int kept = 0;
    for (int i = 0; i < 4000 && kept < 300; ++i) {
      const Real lz = rng.uniform(box.min.z, box.max.z);
      const Real ly = rng.uniform(box.min.y, box.max.y);
      const Real lx = rng.uniform(box.min.x, box.max.x);
      const Vec3 l(lx, ly, lz);
      if (shape.contains(l)) {
        pts.push_back(pose.apply(l));
        ++kept;
      }
    }
  }
  return pts;
}

struct ShapeCaseStats {
  double worst_sphere_ratio = 0;
};

template <class S>
void check_shape(const S& shape, const Transform& pose, test::Random& rng, bool bounded, bool exact_sphere,
                 const std::string& label, ShapeCaseStats& stats) {
  const std::vector<Vec3> pts = sample_world(shape, pose, rng, bounded);
  const Aabb box = fit_shape_aabb(shape, pose);
  const Obb obb = fit_shape_obb(shape, pose);
  const Kdop14 k14 = fit_shape_kdop<14>(shape, pose);
  const Kdop26 k26 = fit_shape_kdop<26>(shape, pose);
  for (const Vec3& p : pts) {
    ASSERT_TRUE(box.contains(p)) << label;
    ASSERT_TRUE(obb.contains(p)) << label;
    ASSERT_TRUE(k14.contains(p)) << label;
    ASSERT_TRUE(k26.contains(p)) << label;
  }
  if (!bounded) return;
  Real mag = Real(0), size = Real(0);
  for (const Vec3& p : pts) mag = std::max({mag, std::abs(p.x), std::abs(p.y), std::abs(p.z)});
  size = glm::length(box.extents());
  const Real tol = test::abs_tol(size, mag) * Real(4);
  // Tightness: the bounds are attained by support points.
  for (int i = 0; i < 13; ++i) {
    Real hi = -kRealMax, lo = kRealMax;
    for (const Vec3& p : pts) {
      hi = std::max(hi, Kdop26::project(i, p));
      lo = std::min(lo, Kdop26::project(i, p));
    }
    EXPECT_NEAR(hi, k26.max[i], tol * 2) << label << " slab " << i;
    EXPECT_NEAR(lo, k26.min[i], tol * 2) << label << " slab " << i;
  }
  for (int i = 0; i < 3; ++i) {
    Real hi = -kRealMax;
    for (const Vec3& p : pts) hi = std::max(hi, p[i]);
    EXPECT_NEAR(hi, box.max[i], tol) << label;
  }
  const BoundingSphere sphere = fit_shape_sphere(shape, pose);
  for (const Vec3& p : pts) ASSERT_TRUE(sphere.contains(p)) << label;
  const BoundingCapsule capsule = fit_shape_capsule(shape, pose);
  for (const Vec3& p : pts) ASSERT_TRUE(capsule.contains(p)) << label;
  // Not minimal, but never looser than the sphere around the oriented box's long axis
  // allows: the radius is at most the box's half diagonal across the axis (+ 0.2 %).
  const Obb around = fit_shape_obb(shape, pose);
  Vec3 h = around.half_extents;
  std::sort(&h[0], &h[0] + 3);
  EXPECT_LE(capsule.radius, std::hypot(h[0], h[1]) * Real(1.002) + tol) << label;
  if (exact_sphere) {
    const Real ref = fit_sphere_minimal(pts)->radius;
    const double ratio = double(sphere.radius) / double(ref);
    if (tol < Real(1e-3) * ref) stats.worst_sphere_ratio = std::max(stats.worst_sphere_ratio, ratio);
    EXPECT_LE(sphere.radius, ref * Real(1.02) + tol) << label;
  }
}

TEST(FitShape, EveryShapeTypeIsBounded) {
  test::Random rng(701);
  ShapeCaseStats stats;
  int cases = 0;
  for (int i = 0; i < 60; ++i) {
    const int variant = i % 3;
    const Real scale = variant == 1 ? Real(1e-3) : (variant == 2 ? Real(1e3) : Real(1));
    Transform pose = rng.pose(Real(10) * scale);
    if (i % 5 == 4) pose.position += Vec3(Real(1e4), Real(-1e4), Real(1e4));
    auto r = [&] { return rng.uniform(Real(0.2), Real(3)) * scale; };
    const std::string tag = " case " + std::to_string(i);
    check_shape(*Point::create(), pose, rng, false, false, "point" + tag, stats);
    // One draw per statement (the order of evaluation of arguments is unspecified).
    auto r2 = [&] {
      const Real second = r();
      const Real first = r();
      return std::pair{first, second};
    };
    auto r3 = [&] {
      const Real z = r();
      const Real y = r();
      const Real x = r();
      return Vec3(x, y, z);
    };
    const Vec3 s1 = rng.vec3(-1, 1) * scale;
    const Vec3 s0 = rng.vec3(-1, 1) * scale;
    check_shape(*Segment::create(s0, s1), pose, rng, false, false, "segment" + tag, stats);
    const Vec3 t2 = rng.vec3(-1, 1) * scale;
    const Vec3 t1 = rng.vec3(-1, 1) * scale;
    const Vec3 t0 = rng.vec3(-1, 1) * scale;
    check_shape(*Triangle::create(t0, t1, t2), pose, rng, false, false, "triangle" + tag, stats);
    check_shape(*Sphere::create(r()), pose, rng, true, true, "sphere" + tag, stats);
    const auto [cap_r, cap_h] = r2();
    check_shape(*Capsule::create(cap_r, cap_h), pose, rng, true, true, "capsule" + tag, stats);
    check_shape(*Box::create(r3()), pose, rng, true, true, "box" + tag, stats);
    const auto [cyl_r, cyl_h] = r2();
    check_shape(*Cylinder::create(cyl_r, cyl_h), pose, rng, true, true, "cylinder" + tag, stats);
    const auto [cone_r, cone_h] = r2();
    check_shape(*Cone::create(cone_r, cone_h), pose, rng, true, true, "cone" + tag, stats);
    check_shape(*Ellipsoid::create(r3()), pose, rng, true, true, "ellipsoid" + tag, stats);
    std::vector<Vec3> cloud;
    for (int k = 0; k < 20; ++k) cloud.push_back(rng.vec3(-1, 1) * scale);
    check_shape(*ConvexHull::create(cloud), pose, rng, true, true, "hull" + tag, stats);
    const Real offset = r();
    check_shape(*HalfSpace::create(rng.unit_vector(), offset), pose, rng, false, false, "halfspace" + tag, stats);
    cases += 11;
  }
  std::printf("placed shapes: %d cases, worst sphere / minimal-of-samples ratio %.4f (where rounding is negligible)\n",
              cases, stats.worst_sphere_ratio);
}

// Case 9 of the sweep above as the sanitizer build (clang) drew it while its draws were
// arguments of one call: a half-space placed 1.7e4 from the origin whose support point in the
// direction below lies near 1.1e5, while the slab of the edge diagonal (1, 0, 1) that should
// hold it projects it to -2.2e4 (the coordinates cancel). The 26-DOP must contain it.
TEST(FitShape, KdopOfAFarHalfSpaceHoldsItsSupportPoints) {
  const HalfSpace h =
      *HalfSpace::create(Vec3(Real(-0.715107024), Real(-0.665610731), Real(0.213504583)), Real(0.776233137));
  const Transform pose{Vec3(Real(9990.71875), Real(-9996.43262), Real(10006.8262)),
                       Quat(Real(-0.870532155), Real(-0.369591236), Real(0.224783346), Real(0.234624282))};
  const Vec3 p = support(h, pose, Vec3(Real(-0.654624104), Real(-0.253752172), Real(-0.712093532)));
  const Kdop26 k26 = fit_shape_kdop<26>(h, pose);
  EXPECT_TRUE(k26.contains(p)) << p.x << " " << p.y << " " << p.z;
  EXPECT_TRUE(fit_shape_kdop<14>(h, pose).contains(p));
  EXPECT_TRUE(fit_shape_aabb(h, pose).contains(p));
  EXPECT_TRUE(fit_shape_obb(h, pose).contains(p));
}

TEST(FitShape, CapsulesOfRoundShapesAreExact) {
  const Transform pose{Vec3(1, -2, 3), glm::angleAxis(Real(0.7), glm::normalize(Vec3(1, 2, 3)))};
  const BoundingCapsule c = fit_shape_capsule(*Capsule::create(Real(0.5), Real(2)), pose);
  EXPECT_NEAR(c.radius, Real(0.5), Real(1e-5));
  EXPECT_NEAR(glm::length(c.p1 - c.p0), Real(4), Real(1e-5));
  const BoundingCapsule s = fit_shape_capsule(*Sphere::create(Real(2)), pose);
  EXPECT_NEAR(s.radius, Real(2), Real(1e-5));
  EXPECT_EQ(s.p0, pose.position);
  const BoundingCapsule seg = fit_shape_capsule(*Segment::create(Vec3(0), Vec3(0, 0, 1)), pose);
  EXPECT_LE(seg.radius, Real(1e-5));
  EXPECT_EQ(fit_shape_capsule(*HalfSpace::create(Vec3(0, 0, 1), Real(0)), pose).radius, kRealMax);
  // A cylinder of radius 1 and half length 3: the axis is found, the radius within 0.2 %.
  const BoundingCapsule cyl = fit_shape_capsule(*Cylinder::create(Real(1), Real(3)), pose);
  EXPECT_NEAR(cyl.radius, Real(1), Real(2e-3));
  EXPECT_NEAR(glm::length(cyl.p1 - cyl.p0), Real(6), Real(1e-4));
}

TEST(FitShape, SpheresOfShapesAreTheAnalyticMinimalSpheres) {
  const Transform id;
  EXPECT_NEAR(fit_shape_sphere(*Box::create(Vec3(1, 2, 2)), id).radius, Real(3), Real(1e-5));
  EXPECT_NEAR(fit_shape_sphere(*Capsule::create(Real(1), Real(2)), id).radius, Real(3), Real(1e-5));
  EXPECT_NEAR(fit_shape_sphere(*Cylinder::create(Real(3), Real(4)), id).radius, Real(5), Real(1e-5));
  EXPECT_NEAR(fit_shape_sphere(*Ellipsoid::create(Vec3(1, 4, 2)), id).radius, Real(4), Real(1e-5));
  // Cone with r <= 2h: the ball through apex and rim; r > 2h: the base disc's ball.
  const BoundingSphere tall = fit_shape_sphere(*Cone::create(Real(1), Real(2)), id);
  EXPECT_NEAR(tall.radius, Real(2) + Real(1) / Real(8), Real(1e-5));
  const BoundingSphere flat = fit_shape_sphere(*Cone::create(Real(5), Real(1)), id);
  EXPECT_NEAR(flat.radius, Real(5), Real(1e-5));
  EXPECT_NEAR(flat.center.z, Real(-1), Real(1e-5));
  const BoundingSphere seg =
      fit_shape_sphere(*Segment::create(Vec3(0), Vec3(0, 0, 4)), Transform{Vec3(1, 0, 0), kIdentityQuat});
  EXPECT_NEAR(seg.radius, Real(2), Real(1e-5));
  EXPECT_NEAR(glm::length(seg.center - Vec3(1, 0, 2)), Real(0), Real(1e-5));
  // Unbounded half-space: the sphere is as large as Real allows.
  EXPECT_EQ(fit_shape_sphere(*HalfSpace::create(Vec3(0, 0, 1), Real(0)), id).radius, kRealMax);
  const Aabb hb = fit_shape_aabb(*HalfSpace::create(Vec3(0, 0, 1), Real(0)), id);
  EXPECT_TRUE(std::isfinite(hb.min.x) && std::isfinite(hb.max.z));
  const Obb ho = fit_shape_obb(*HalfSpace::create(Vec3(0, 0, 1), Real(0)), id);
  EXPECT_TRUE(std::isfinite(ho.half_extents.x) && std::isfinite(ho.center.z));
}

}  // namespace test_fit_shape
}  // namespace proxima
