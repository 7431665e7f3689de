// Movement bounds and swept volumes (src/midphase/movement_bounds.cpp) checked by dense
// sampling of intermediate poses and against analytic answers.
//
// Shapes: boxes, spheres, capsules, cylinders and random convex hulls at seeded random
// motions (pure translations and translations with rotation). For every motion, 65 placements
// (Motion::at) and their world support points in 24 directions (plus every vertex for boxes
// and hulls) must lie in the motion's box, ball and oriented box and in the swept hull; for
// pure translations the box is reached by the samples on every side (tight), the swept hull's
// support equals the larger of the start and end supports, and the swept ball of a sphere is
// the smallest one. With rotation, the swept hull exceeds the sampled supports by at most the
// stated growth sqrt(3) R step^2 / 8. Analytic: the capsule of a moving sphere, the volume of
// a translated box's sweep (8 + 4 (|dx| + |dy| + |dz|) for the unit-half-extent cube), the box
// of a rotating box (its ball about the origin).
#include <gtest/gtest.h>

#include <proxima/ccd/movement_bounds.hpp>
#include <proxima/core/tolerance.hpp>
#include <proxima/shapes/cylinder.hpp>
#include <proxima/shapes/placed.hpp>

#include <array>
#include <cmath>
#include <vector>

#include "support/random.hpp"

namespace proxima {
namespace test_movement_bounds {

Motion random_motion(test::Random& rng, bool rotate) {
  Motion m;
  m.start = rng.pose(Real(5));
  m.end.position = m.start.position + rng.vec3(Real(-4), Real(4));
  m.end.rotation = rotate ? rng.rotation() : m.start.rotation;
  return m;
}

// World points of `shape` at `pose` that every bound must contain: supports in 24 directions.
template <class S>
void sample_points(const S& shape, const Transform& pose, std::vector<Vec3>& out, std::span<const Vec3> dirs) {
  for (const Vec3& d : dirs) out.push_back(support(shape, pose, d));
}

std::vector<Vec3> directions(test::Random& rng) {
  std::vector<Vec3> d;
  for (int i = 0; i < 3; ++i) {
    Vec3 e(0);
    e[i] = 1;
    d.push_back(e);
    d.push_back(-e);
  }
  for (int i = 0; i < 18; ++i) d.push_back(rng.unit_vector());
  return d;
}

Real obb_excess(const Obb& box, const Vec3& p) {
  const Vec3 l = box.to_local(p);
  Real e = -kRealMax;
  for (int i = 0; i < 3; ++i) e = std::max(e, std::abs(l[i]) - box.half_extents[i]);
  return e;
}

template <class S>
void check_shape(const S& shape, std::span<const Vec3> vertices, test::Random& rng, bool rotate) {
  const std::vector<Vec3> dirs = directions(rng);
  for (int trial = 0; trial < 25; ++trial) {
    const Motion motion = random_motion(rng, rotate);
    const Aabb box = motion_aabb(shape, motion);
    const BoundingSphere ball = motion_sphere(shape, motion);
    const Obb obb = motion_obb(shape, motion);
    const Real tol = Real(64) * kEpsilon * Real(20);  // a few ulps at coordinates up to ~20
    std::vector<Vec3> pts;
    const int samples = 64;
    for (int k = 0; k <= samples; ++k) {
      const Transform pose = motion.at(Real(k) / Real(samples));
      sample_points(shape, pose, pts, dirs);
      for (const Vec3& v : vertices) pts.push_back(pose.apply(v));
    }
    Aabb sampled;
    for (const Vec3& p : pts) {
      sampled.grow(p);
      EXPECT_TRUE(box.inflated(tol).contains(p));
      EXPECT_LE(glm::length(p - ball.center), ball.radius + tol);
      EXPECT_LE(obb_excess(obb, p), tol);
    }
    if (!rotate) {
      // Tight: the samples reach every side of the box (the end poses are sampled).
      for (int i = 0; i < 3; ++i) {
        EXPECT_NEAR(sampled.min[i], box.min[i], 10 * tol);
        EXPECT_NEAR(sampled.max[i], box.max[i], 10 * tol);
      }
    }
  }
}

TEST(MovementBounds, MotionInterpolation) {
  test::Random rng(3);
  for (int i = 0; i < 100; ++i) {
    const Motion m = random_motion(rng, true);
    const Transform a = m.at(Real(0));
    const Transform b = m.at(Real(1));
    EXPECT_LT(glm::length(a.position - m.start.position), 1e-5);
    EXPECT_LT(glm::length(b.position - m.end.position), 1e-5);
    const Vec3 x(1, 2, 3);
    EXPECT_LT(glm::length(a.apply(x) - m.start.apply(x)), 1e-4);
    EXPECT_LT(glm::length(b.apply(x) - m.end.apply(x)), 1e-4);
    // The angle grows linearly along the slerp path.
    Motion half{m.start, m.at(Real(0.5))};
    EXPECT_NEAR(half.rotation_angle(), m.rotation_angle() * Real(0.5), 2e-3);
    EXPECT_FALSE(m.is_translation());
  }
  Motion t{Transform{Vec3(0), kIdentityQuat}, Transform{Vec3(1, 0, 0), Quat(-1, 0, 0, 0)}};
  EXPECT_TRUE(t.is_translation());
  EXPECT_EQ(t.rotation_angle(), 0);
  const Motion quarter{Transform{}, Transform{Vec3(0), glm::angleAxis(kPi / 2, Vec3(0, 0, 1))}};
  EXPECT_NEAR(quarter.rotation_angle(), kPi / 2, 1e-5);
}

TEST(MovementBounds, SampledPlacementsAreContained) {
  test::Random rng(20261121);
  const Box box = Box::create(Vec3(1, 0.5f, 0.25f)).value();
  std::array<Vec3, 8> corners;
  for (int c = 0; c < 8; ++c) {
    corners[std::size_t(c)] = Vec3((c & 1) ? 1 : -1, (c & 2) ? 0.5f : -0.5f, (c & 4) ? 0.25f : -0.25f);
  }
  const Sphere sphere = Sphere::create(Real(0.7)).value();
  const Capsule capsule = Capsule::create(Real(0.3), Real(1)).value();
  const Cylinder cylinder = Cylinder::create(Real(0.5), Real(0.8)).value();
  std::vector<Vec3> cloud;
  for (int i = 0; i < 30; ++i) cloud.push_back(rng.vec3(Real(-1), Real(1)) + Vec3(0.5f, 0, 0));
  const ConvexHull hull = ConvexHull::create(cloud).value();
  for (const bool rotate : {false, true}) {
    SCOPED_TRACE(rotate ? "with rotation" : "translation");
    check_shape(box, corners, rng, rotate);
    check_shape(sphere, std::span<const Vec3>(), rng, rotate);
    check_shape(capsule, std::span<const Vec3>(), rng, rotate);
    check_shape(cylinder, std::span<const Vec3>(), rng, rotate);
    check_shape(hull, hull.vertices(), rng, rotate);
  }
}

TEST(MovementBounds, TranslatedSphereBallIsSmallest) {
  test::Random rng(5);
  const Sphere sphere = Sphere::create(Real(0.5)).value();
  for (int i = 0; i < 100; ++i) {
    const Motion m = random_motion(rng, false);
    const BoundingSphere b = motion_sphere(sphere, m);
    const Real expected = Real(0.5) * glm::length(m.displacement()) + Real(0.5);
    EXPECT_NEAR(b.radius, expected, 1e-4);
    EXPECT_LT(glm::length(b.center - (m.start.position + m.end.position) * Real(0.5)), 1e-4);
  }
}

TEST(MovementBounds, RotatingBoxAnalytic) {
  // A box spinning in place: the box of its ball about the origin.
  const Box box = Box::create(Vec3(1, 2, 3)).value();
  const Motion spin{Transform{Vec3(1, 1, 1), kIdentityQuat},
                    Transform{Vec3(1, 1, 1), glm::angleAxis(Real(1), glm::normalize(Vec3(1, 1, 0)))}};
  const Aabb a = motion_aabb(box, spin);
  const Real r = std::sqrt(Real(14));
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(a.min[i], 1 - r, 1e-4);
    EXPECT_NEAR(a.max[i], 1 + r, 1e-4);
  }
  // A translating box along its own x: the OBB is the stretched box.
  const Motion slide{
      Transform{Vec3(0), glm::angleAxis(Real(0.3), Vec3(0, 0, 1))},
      Transform{glm::angleAxis(Real(0.3), Vec3(0, 0, 1)) * Vec3(4, 0, 0), glm::angleAxis(Real(0.3), Vec3(0, 0, 1))}};
  const Obb o = motion_obb(box, slide);
  EXPECT_NEAR(o.volume(), (2 + 4) * 4 * 6, 1e-2);
}

TEST(MovementBounds, SweptSphereIsTheCapsule) {
  test::Random rng(11);
  for (int i = 0; i < 200; ++i) {
    const Vec3 from = rng.vec3(Real(-5), Real(5));
    const Vec3 to = i % 10 == 0 ? from : rng.vec3(Real(-5), Real(5));
    const Real r = rng.uniform(Real(0.1), Real(2));
    const PlacedCapsule c = swept_sphere(from, to, r).value();
    EXPECT_NEAR(c.capsule.radius(), r, 1e-6);
    EXPECT_NEAR(Real(2) * c.capsule.half_length(), glm::length(to - from), 1e-4);
    const Vec3 top = c.pose.apply(c.capsule.top());
    const Vec3 bottom = c.pose.apply(c.capsule.bottom());
    EXPECT_LT(std::min(glm::length(top - to) + glm::length(bottom - from),
                       glm::length(top - from) + glm::length(bottom - to)),
              1e-4);
    // Every sampled sphere surface point lies on the capsule's surface or inside.
    for (int k = 0; k <= 20; ++k) {
      const Vec3 center = from + (to - from) * (Real(k) / Real(20));
      const Vec3 p = center + r * rng.unit_vector();
      EXPECT_LE(closest_point(c.capsule, c.pose, p).signed_distance, 1e-4);
      // Tight: the sphere point farthest from the axis is on the surface.
    }
  }
  const Sphere s = Sphere::create(Real(1)).value();
  const Motion m{Transform{Vec3(0), kIdentityQuat}, Transform{Vec3(0, 0, 2), glm::angleAxis(Real(1), Vec3(1, 0, 0))}};
  const PlacedCapsule c = swept_sphere(s, m).value();
  EXPECT_NEAR(c.capsule.half_length(), 1, 1e-6);
  EXPECT_NEAR(c.pose.position.z, 1, 1e-6);
  EXPECT_FALSE(swept_sphere(Vec3(0), Vec3(1), Real(0)).ok());
  {
    test::ScopedNoFpTraps no_traps;
    EXPECT_FALSE(swept_sphere(Vec3(std::numeric_limits<Real>::quiet_NaN()), Vec3(1), Real(1)).ok());
  }
}

TEST(MovementBounds, TranslatedBoxSweepVolumeAnalytic) {
  test::Random rng(13);
  const Box box = Box::create(Vec3(1)).value();
  for (int i = 0; i < 50; ++i) {
    const Vec3 d = rng.vec3(Real(-3), Real(3));
    const Transform start{rng.vec3(Real(-2), Real(2)), kIdentityQuat};
    const Motion m{start, Transform{start.position + d, kIdentityQuat}};
    const ConvexHull swept = swept_box(box, m).value();
    const Real expected = 8 + 4 * (std::abs(d.x) + std::abs(d.y) + std::abs(d.z));
    EXPECT_NEAR(swept.mass_properties().volume, expected, 1e-3 * expected);
  }
}

TEST(MovementBounds, SweptHullContainsSampledPlacements) {
  test::Random rng(17);
  const std::vector<Vec3> dirs = directions(rng);
  for (int trial = 0; trial < 30; ++trial) {
    std::vector<Vec3> cloud;
    for (int i = 0; i < 20; ++i) cloud.push_back(rng.vec3(Real(-1), Real(1)));
    const ConvexHull shape = ConvexHull::create(cloud).value();
    const bool rotate = trial % 2 == 1;
    const Motion m = random_motion(rng, rotate);
    SweepOptions options;
    const ConvexHull swept = swept_hull(shape, m, options).value();
    Real radius = 0;
    for (const Vec3& v : shape.vertices()) radius = std::max(radius, glm::length(v));
    const Real angle = m.rotation_angle();
    const int n = std::max(1, int(std::ceil(angle / options.max_angle_step)));
    const Real step = angle / Real(n);
    const Real growth = rotate ? std::sqrt(Real(3)) * radius * step * step / 8 : Real(0);
    const int samples = 256;
    std::vector<Real> best(dirs.size(), -kRealMax);
    for (int k = 0; k <= samples; ++k) {
      const Transform pose = m.at(Real(k) / Real(samples));
      for (const Vec3& v : shape.vertices()) {
        const Vec3 p = pose.apply(v);
        EXPECT_TRUE(swept.contains(p)) << "trial " << trial << " k " << k;
        for (std::size_t j = 0; j < dirs.size(); ++j) best[j] = std::max(best[j], glm::dot(p, dirs[j]));
      }
    }
    // Tight: the hull's support exceeds the sampled one by at most the stated growth (plus
    // the sampling's own chord error, far smaller with 256 samples).
    for (std::size_t j = 0; j < dirs.size(); ++j) {
      const Real hull_support = glm::dot(swept.support(dirs[j]), dirs[j]);
      EXPECT_GE(hull_support, best[j] - 1e-4);
      EXPECT_LE(hull_support, best[j] + growth + radius * angle * angle / (8 * samples * samples) + 1e-3)
          << "rotate " << rotate;
    }
  }
  SweepOptions bad;
  bad.max_angle_step = 0;
  const std::array<Vec3, 4> tet{Vec3(0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
  EXPECT_FALSE(swept_hull(tet, Motion{}, bad).ok());
}

}  // namespace test_movement_bounds
}  // namespace proxima
