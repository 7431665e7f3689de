// Ray casts against the geometric primitives: analytic answers and named regression cases
// (touching, parallel, along an axis, through an apex, on the surface, zero direction,
// max_t = 0, huge / tiny scales, far from the origin, non-finite input).
#include <gtest/gtest.h>

#include <proxima/core/tolerance.hpp>
#include <proxima/geometry/raycast.hpp>

#include <array>
#include <cmath>
#include <limits>

#include "support/random.hpp"

namespace proxima::geometry {
namespace test_raycast_primitives {

constexpr Real kInf = std::numeric_limits<Real>::infinity();
constexpr Real kNaN = std::numeric_limits<Real>::quiet_NaN();
// Relative accuracy expected of a well-conditioned cast: a few hundred ulp.
constexpr Real kTol = Real(256) * kEpsilon;

void expect_vec_near(const Vec3& a, const Vec3& b, Real tol) {
  EXPECT_NEAR(a.x, b.x, tol) << "(" << a.x << ", " << a.y << ", " << a.z << ") vs (" << b.x << ", " << b.y << ", "
                             << b.z << ")";
  EXPECT_NEAR(a.y, b.y, tol);
  EXPECT_NEAR(a.z, b.z, tol);
}

// Checks a hit: parameter, unit normal, point = origin + t direction.
void expect_hit(const std::optional<RayHit>& hit, const Ray& ray, Real t, const Vec3& normal, Real scale = 1) {
  ASSERT_TRUE(hit.has_value());
  EXPECT_NEAR(hit->t, t, kTol * std::max(Real(1), std::abs(t)));
  expect_vec_near(hit->normal, normal, kTol * 4);
  EXPECT_NEAR(glm::length(hit->normal), Real(1), kTol);
  const Real pscale = std::max(scale, std::abs(hit->t) * glm::length(ray.direction)) +
                      std::max({std::abs(ray.origin.x), std::abs(ray.origin.y), std::abs(ray.origin.z)});
  expect_vec_near(hit->point, ray.at(hit->t), kTol * pscale);
}

// The inside answer: t = 0, point = origin, normal = -direction / |direction|.
void expect_inside(const std::optional<RayHit>& hit, const Ray& ray) {
  ASSERT_TRUE(hit.has_value());
  EXPECT_EQ(hit->t, Real(0));
  EXPECT_EQ(hit->point, ray.origin);
  expect_vec_near(hit->normal, -glm::normalize(ray.direction), kTol);
}

// ---------------------------------------------------------------------------------------
// Sphere

TEST(RaySphere, HitFromOutsideInUnitsOfDirection) {
  const Ray ray{{-5, 0, 0}, {1, 0, 0}};
  expect_hit(ray_sphere(ray, kInf, Vec3(0), 2), ray, 3, {-1, 0, 0});
  const Ray fast{{-5, 0, 0}, {4, 0, 0}};
  expect_hit(ray_sphere(fast, kInf, Vec3(0), 2), fast, Real(0.75), {-1, 0, 0});
  // Off-centre: enters at (-sqrt(3), 1, 0) for radius 2.
  const Ray off{{-5, 1, 0}, {1, 0, 0}};
  expect_hit(ray_sphere(off, kInf, Vec3(0), 2), off, 5 - std::sqrt(Real(3)), {-std::sqrt(Real(3)) / 2, Real(0.5), 0});
}

TEST(RaySphere, MissesBesideBehindAndBeyondMaxT) {
  EXPECT_FALSE(ray_sphere({{-5, 3, 0}, {1, 0, 0}}, kInf, Vec3(0), 2));
  EXPECT_FALSE(ray_sphere({{5, 0, 0}, {1, 0, 0}}, kInf, Vec3(0), 2));
  EXPECT_FALSE(ray_sphere({{-5, 0, 0}, {1, 0, 0}}, Real(2.99), Vec3(0), 2));
  EXPECT_TRUE(ray_sphere({{-5, 0, 0}, {1, 0, 0}}, Real(3), Vec3(0), 2));
  EXPECT_FALSE(ray_sphere({{-5, 0, 0}, {1, 0, 0}}, Real(-1), Vec3(0), 2));
}

TEST(RaySphere, GrazingTouchesTheClosedSolid) {
  const Ray ray{{-5, 2, 0}, {1, 0, 0}};
  expect_hit(ray_sphere(ray, kInf, Vec3(0), 2), ray, 5, {0, 1, 0});
  EXPECT_FALSE(ray_sphere({{-5, Real(2) * (1 + 4 * kEpsilon), 0}, {1, 0, 0}}, kInf, Vec3(0), 2));
}

TEST(RaySphere, InsideOnSurfaceZeroDirectionAndZeroMaxT) {
  const Ray inside{{Real(0.5), 0, 0}, {0, 3, 0}};
  expect_inside(ray_sphere(inside, kInf, Vec3(0), 2), inside);
  expect_inside(ray_sphere(inside, 0, Vec3(0), 2), inside);
  // Origin exactly on the surface belongs to the closed solid, whichever the direction.
  const Ray out{{2, 0, 0}, {1, 0, 0}};
  expect_inside(ray_sphere(out, kInf, Vec3(0), 2), out);
  const Ray in{{0, -2, 0}, {0, 1, 0}};
  expect_inside(ray_sphere(in, kInf, Vec3(0), 2), in);
  // Zero direction: only an inside origin hits.
  const auto zero = ray_sphere({{1, 0, 0}, Vec3(0)}, kInf, Vec3(0), 2);
  ASSERT_TRUE(zero);
  EXPECT_EQ(zero->t, Real(0));
  EXPECT_NEAR(glm::length(zero->normal), Real(1), kTol);
  EXPECT_FALSE(ray_sphere({{3, 0, 0}, Vec3(0)}, kInf, Vec3(0), 2));
  EXPECT_FALSE(ray_sphere({{-5, 0, 0}, {1, 0, 0}}, 0, Vec3(0), 2));
}

TEST(RaySphere, HugeTinyAndFarFromOrigin) {
  for (const Real s : {Real(1e-4), Real(1e4)}) {
    const Ray ray{{-5 * s, s, 0}, {s, 0, 0}};
    const auto hit = ray_sphere(ray, kInf, Vec3(0), 2 * s);
    expect_hit(hit, ray, 5 - std::sqrt(Real(3)), {-std::sqrt(Real(3)) / 2, Real(0.5), 0}, s);
  }
  // Sphere 1e4 from the origin, ray from 1000 away: the quadratic never sees 1e8-sized terms.
  const Vec3 c(1e4, -1e4, 1e4);
  const Ray ray{c + Vec3(-1000, Real(0.5), 0), {1, 0, 0}};
  const auto hit = ray_sphere(ray, kInf, c, 1);
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->t, 1000 - std::sqrt(Real(0.75)), kTol * 1000);
  expect_vec_near(hit->normal, {-std::sqrt(Real(0.75)), Real(0.5), 0}, kTol * 1000);
  // Grazing at 1000 units: just inside and just outside.
  EXPECT_TRUE(ray_sphere({c + Vec3(-1000, Real(0.999), 0), {1, 0, 0}}, kInf, c, 1));
  EXPECT_FALSE(ray_sphere({c + Vec3(-1000, Real(1.001), 0), {1, 0, 0}}, kInf, c, 1));
}

TEST(RaySphere, CancellationSafeNearRoot) {
  // Origin 1e-3 outside a sphere of radius 1e3: the entry distance is tiny beside the
  // far root; the stable form keeps its relative accuracy.
  const Real r = 1000;
  const Ray ray{{0, 0, r + Real(1e-3) * r}, {0, 0, -1}};
  const auto hit = ray_sphere(ray, kInf, Vec3(0), r);
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->t, Real(1e-3) * r, Real(1e-3) * r * kTol * 16);
}

// ---------------------------------------------------------------------------------------
// Axis-aligned and oriented box

const Aabb kUnitBox{Vec3(-1), Vec3(1)};

TEST(RayAabb, EachFaceWithExactPoint) {
  for (int axis = 0; axis < 3; ++axis) {
    for (const Real side : {Real(-1), Real(1)}) {
      Vec3 o(Real(0.25), Real(-0.5), Real(0.125));
      o[axis] = 3 * side;
      Vec3 d(0);
      d[axis] = -2 * side;
      Vec3 n(0);
      n[axis] = side;
      const Ray ray{o, d};
      const auto hit = ray_aabb(ray, kInf, kUnitBox);
      expect_hit(hit, ray, 1, n);
      EXPECT_EQ(hit->point[axis], side);  // exactly on the face
    }
  }
}

TEST(RayAabb, ParallelToAFace) {
  // Lying exactly in the face plane y = 1: the closed box is hit.
  const Ray on{{-3, 1, 0}, {1, 0, 0}};
  expect_hit(ray_aabb(on, kInf, kUnitBox), on, 2, {-1, 0, 0});
  // Along an edge.
  const Ray edge{{-3, 1, -1}, {1, 0, 0}};
  EXPECT_NEAR(ray_aabb(edge, kInf, kUnitBox)->t, Real(2), kTol);
  // Just above the face, or parallel outside: miss.
  EXPECT_FALSE(ray_aabb({{-3, Real(1) + 2 * kEpsilon, 0}, {1, 0, 0}}, kInf, kUnitBox));
  EXPECT_FALSE(ray_aabb({{-3, 2, 0}, {1, 0, 0}}, kInf, kUnitBox));
  // Negative zero components change nothing.
  const Ray nz{{-3, 0, 0}, {1, -Real(0), -Real(0)}};
  expect_hit(ray_aabb(nz, kInf, kUnitBox), nz, 2, {-1, 0, 0});
}

TEST(RayAabb, CornerHitAndTinyDirectionComponentThroughAFacePlane) {
  const Ray corner{{-2, -2, -2}, {1, 1, 1}};
  const auto hit = ray_aabb(corner, kInf, kUnitBox);
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->t, Real(1), kTol);
  EXPECT_NEAR(glm::dot(hit->normal, Vec3(-1)), Real(1), kTol);  // one of the three faces
  // Origin in the plane y = -1 with a denormal y component: (face - origin) = 0 divided,
  // never multiplied by an infinite reciprocal.
  const Real tiny = std::numeric_limits<Real>::denorm_min();
  const Ray ray{{-3, -1, 0}, {1, tiny, 0}};
  expect_hit(ray_aabb(ray, kInf, kUnitBox), ray, 2, {-1, 0, 0});
  // Leaving the face plane, however slowly: outside the closed box for every t > 0.
  EXPECT_FALSE(ray_aabb({{-3, -1, 0}, {1, -tiny, 0}}, kInf, kUnitBox));
}

TEST(RayAabb, InsideOnSurfaceZeroDirectionFlatAndEmptyBoxes) {
  const Ray inside{{Real(0.5), 0, 0}, {0, 0, 3}};
  expect_inside(ray_aabb(inside, kInf, kUnitBox), inside);
  expect_inside(ray_aabb(inside, 0, kUnitBox), inside);
  const Ray on{{1, 0, 0}, {1, 0, 0}};
  expect_inside(ray_aabb(on, kInf, kUnitBox), on);
  ASSERT_TRUE(ray_aabb({Vec3(0), Vec3(0)}, kInf, kUnitBox));
  EXPECT_FALSE(ray_aabb({Vec3(2), Vec3(0)}, kInf, kUnitBox));
  EXPECT_FALSE(ray_aabb({{-3, 0, 0}, {1, 0, 0}}, 0, kUnitBox));
  const Aabb flat{{-1, -1, 0}, {1, 1, 0}};
  const Ray through{{0.5, 0.5, 4}, {0, 0, -2}};
  expect_hit(ray_aabb(through, kInf, flat), through, 2, {0, 0, 1});
  EXPECT_FALSE(ray_aabb(through, kInf, Aabb::empty()));
}

TEST(RayAabb, HugeTinyAndFarFromOrigin) {
  for (const Real s : {Real(1e-4), Real(1e4)}) {
    const Aabb box{Vec3(-s), Vec3(s)};
    const Ray ray{{-3 * s, Real(0.5) * s, 0}, {s, 0, 0}};
    expect_hit(ray_aabb(ray, kInf, box), ray, 2, {-1, 0, 0}, s);
  }
  const Vec3 c(1e4, -1e4, 1e4);
  const Aabb box{c - Vec3(1), c + Vec3(1)};
  const Ray ray{c + Vec3(Real(0.5), -100, Real(0.25)), {0, 1, 0}};
  const auto hit = ray_aabb(ray, kInf, box);
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->t, Real(99), kTol * 1e4);
  expect_vec_near(hit->normal, {0, -1, 0}, 0);
}

TEST(RayObb, RotatedBoxAgainstAnalyticAnswers) {
  // Box rotated 30 degrees about z, centred at (5, 1, 0); a ray along the rotated x axis
  // from outside hits the -x face head on.
  const Real ang = kPi / 6;
  const Mat3 axes(Vec3(std::cos(ang), std::sin(ang), 0), Vec3(-std::sin(ang), std::cos(ang), 0), Vec3(0, 0, 1));
  const Vec3 c(5, 1, 0);
  const Vec3 h(2, 1, Real(0.5));
  const Ray ray{c - Real(7) * axes[0] + Real(0.3) * axes[1], Real(2) * axes[0]};
  expect_hit(ray_obb(ray, kInf, c, axes, h), ray, Real(2.5), -axes[0], 5);
  // 45 degrees: a ray along world x through the centre meets the vertical edge.
  const Real q = kPi / 4;
  const Mat3 diamond(Vec3(std::cos(q), std::sin(q), 0), Vec3(-std::sin(q), std::cos(q), 0), Vec3(0, 0, 1));
  const auto edge = ray_obb({{0, 0, 0}, {1, 0, 0}}, kInf, {5, 0, 0}, diamond, Vec3(1));
  ASSERT_TRUE(edge);
  EXPECT_NEAR(edge->t, 5 - std::sqrt(Real(2)), kTol * 5);
  EXPECT_NEAR(edge->normal.x, -std::sqrt(Real(0.5)), kTol * 5);
  // Inside, miss, negative half extent.
  const Ray inside{c, {0, 1, 0}};
  expect_inside(ray_obb(inside, kInf, c, axes, h), inside);
  EXPECT_FALSE(ray_obb({{0, 10, 0}, {1, 0, 0}}, kInf, c, axes, h));
  EXPECT_FALSE(ray_obb(ray, kInf, c, axes, Vec3(2, -1, 1)));
}

// ---------------------------------------------------------------------------------------
// Capsule

const Vec3 kP0(0, 0, -1);
const Vec3 kP1(0, 0, 1);

TEST(RayCapsule, BodyAndHemispheres) {
  const Ray side{{-3, 0, 0}, {1, 0, 0}};
  expect_hit(ray_capsule(side, kInf, kP0, kP1, Real(0.5)), side, Real(2.5), {-1, 0, 0});
  // Beside the top hemisphere: enters at x = -0.4 (0.3-0.4-0.5 triangle).
  const Ray cap{{-3, 0, Real(1.3)}, {1, 0, 0}};
  expect_hit(ray_capsule(cap, kInf, kP0, kP1, Real(0.5)), cap, Real(2.6), {Real(-0.8), 0, Real(0.6)});
  EXPECT_FALSE(ray_capsule({{-3, 0, Real(1.6)}, {1, 0, 0}}, kInf, kP0, kP1, Real(0.5)));
  // Tangent to the body: touches at x = 0.
  const Ray tangent{{-3, Real(0.5), 0}, {1, 0, 0}};
  expect_hit(ray_capsule(tangent, kInf, kP0, kP1, Real(0.5)), tangent, 3, {0, 1, 0});
}

TEST(RayCapsule, AlongTheAxis) {
  const Ray axis{{0, 0, -5}, {0, 0, 2}};
  expect_hit(ray_capsule(axis, kInf, kP0, kP1, Real(0.5)), axis, Real(1.75), {0, 0, -1});
  const Ray off{{Real(0.3), 0, 5}, {0, 0, -1}};
  expect_hit(ray_capsule(off, kInf, kP0, kP1, Real(0.5)), off, Real(3.6), {Real(0.6), 0, Real(0.8)});
  // On the lateral surface, parallel to the axis: touches the bottom hemisphere's equator.
  const Ray rim{{Real(0.5), 0, -5}, {0, 0, 1}};
  expect_hit(ray_capsule(rim, kInf, kP0, kP1, Real(0.5)), rim, 4, {1, 0, 0});
}

TEST(RayCapsule, ZeroLengthIsASphereAndInsideCases) {
  test::Random rng(11);
  for (int i = 0; i < 200; ++i) {
    const Vec3 c = rng.vec3(-2, 2);
    const Ray ray{rng.vec3(-5, 5), rng.vec3(-2, 2)};
    const auto a = ray_capsule(ray, kInf, c, c, Real(1.5));
    const auto b = ray_sphere(ray, kInf, c, Real(1.5));
    ASSERT_EQ(a.has_value(), b.has_value());
    if (a) {
      EXPECT_EQ(a->t, b->t);
      expect_vec_near(a->normal, b->normal, kTol);
    }
  }
  const Ray inside{{Real(0.2), 0, Real(1.2)}, {1, 0, 0}};
  expect_inside(ray_capsule(inside, kInf, kP0, kP1, Real(0.5)), inside);
  const Ray surface{{0, 0, Real(1.5)}, {0, 0, 1}};
  expect_inside(ray_capsule(surface, kInf, kP0, kP1, Real(0.5)), surface);
  EXPECT_TRUE(ray_capsule({Vec3(0), Vec3(0)}, kInf, kP0, kP1, Real(0.5)));
  EXPECT_FALSE(ray_capsule({Vec3(1), Vec3(0)}, kInf, kP0, kP1, Real(0.5)));
}

TEST(RayCapsule, HugeTinyAndFar) {
  for (const Real s : {Real(1e-4), Real(1e4)}) {
    const Ray cap{{-3 * s, 0, Real(1.3) * s}, {s, 0, 0}};
    expect_hit(ray_capsule(cap, kInf, kP0 * s, kP1 * s, Real(0.5) * s), cap, Real(2.6), {Real(-0.8), 0, Real(0.6)}, s);
  }
  const Vec3 c(-1e4, 1e4, 1e4);
  const Ray cap{c + Vec3(-3, 0, Real(1.3)), {1, 0, 0}};
  const auto hit = ray_capsule(cap, kInf, c + kP0, c + kP1, Real(0.5));
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->t, Real(2.6), kTol * 100);
}

// ---------------------------------------------------------------------------------------
// Cylinder

TEST(RayCylinder, SideCapsAndSlantedEntry) {
  const Ray side{{-3, 0, 0}, {1, 0, 0}};
  expect_hit(ray_cylinder(side, kInf, kP0, kP1, Real(0.5)), side, Real(2.5), {-1, 0, 0});
  const Ray top{{Real(0.1), Real(0.1), 5}, {0, 0, -2}};
  expect_hit(ray_cylinder(top, kInf, kP0, kP1, Real(0.5)), top, 2, {0, 0, 1});
  const Ray slant{{0, 0, 3}, {Real(0.1), 0, -1}};
  expect_hit(ray_cylinder(slant, kInf, kP0, kP1, Real(0.5)), slant, 2, {0, 0, 1});
  EXPECT_FALSE(ray_cylinder({{-3, 0, Real(1.01)}, {1, 0, 0}}, kInf, kP0, kP1, Real(0.5)));
  // Edge of the cap (the rim), touched by a ray lying in the cap plane.
  const Ray rim{{-3, 0, 1}, {1, 0, 0}};
  EXPECT_NEAR(ray_cylinder(rim, kInf, kP0, kP1, Real(0.5))->t, Real(2.5), kTol);
}

TEST(RayCylinder, AlongTheAxis) {
  const Ray axis{{0, 0, -5}, {0, 0, 1}};
  expect_hit(ray_cylinder(axis, kInf, kP0, kP1, Real(0.5)), axis, 4, {0, 0, -1});
  const Ray off{{Real(0.3), Real(-0.2), -5}, {0, 0, 1}};
  expect_hit(ray_cylinder(off, kInf, kP0, kP1, Real(0.5)), off, 4, {0, 0, -1});
  // On the lateral surface exactly (closed solid): meets the rim.
  const Ray on{{Real(0.5), 0, -5}, {0, 0, 1}};
  expect_hit(ray_cylinder(on, kInf, kP0, kP1, Real(0.5)), on, 4, {0, 0, -1});
  EXPECT_FALSE(ray_cylinder({{Real(0.51), 0, -5}, {0, 0, 1}}, kInf, kP0, kP1, Real(0.5)));
  // Reversed axis (p0 above p1) gives the same answers.
  expect_hit(ray_cylinder(axis, kInf, kP1, kP0, Real(0.5)), axis, 4, {0, 0, -1});
}

TEST(RayCylinder, InsideDegenerateAndScales) {
  const Ray inside{{0, Real(0.2), Real(0.9)}, {0, 1, 1}};
  expect_inside(ray_cylinder(inside, kInf, kP0, kP1, Real(0.5)), inside);
  const Ray on_cap{{0, 0, 1}, {0, 0, 1}};
  expect_inside(ray_cylinder(on_cap, kInf, kP0, kP1, Real(0.5)), on_cap);
  EXPECT_FALSE(ray_cylinder({{-3, 0, 0}, {1, 0, 0}}, kInf, kP0, kP0, Real(0.5)));  // p0 == p1
  EXPECT_FALSE(ray_cylinder({{-3, 0, 0}, {1, 0, 0}}, kInf, kP0, kP1, Real(0)));
  for (const Real s : {Real(1e-4), Real(1e4)}) {
    const Ray top{{Real(0.1) * s, Real(0.1) * s, 5 * s}, {0, 0, -2 * s}};
    expect_hit(ray_cylinder(top, kInf, kP0 * s, kP1 * s, Real(0.5) * s), top, 2, {0, 0, 1}, s);
  }
  const Vec3 c(1e4, 1e4, -1e4);
  const Ray side{c + Vec3(-3, 0, 0), {1, 0, 0}};
  EXPECT_NEAR(ray_cylinder(side, kInf, c + kP0, c + kP1, Real(0.5))->t, Real(2.5), kTol * 100);
}

// ---------------------------------------------------------------------------------------
// Cone: apex (0, 0, 1), base centre (0, 0, -1), base radius 1 (radius 0.5 at z = 0).

const Vec3 kApex(0, 0, 1);
const Vec3 kBase(0, 0, -1);

TEST(RayCone, SideBaseAndApex) {
  const Real cos_a = 2 / std::sqrt(Real(5));
  const Real sin_a = 1 / std::sqrt(Real(5));
  const Ray side{{-3, 0, 0}, {1, 0, 0}};
  expect_hit(ray_cone(side, kInf, kApex, kBase, 1), side, Real(2.5), {-cos_a, 0, sin_a});
  const Ray base{{Real(0.2), 0, -3}, {0, 0, 1}};
  expect_hit(ray_cone(base, kInf, kApex, kBase, 1), base, 2, {0, 0, -1});
  // Along the axis from above: through the apex.
  const Ray down{{0, 0, 3}, {0, 0, -1}};
  expect_hit(ray_cone(down, kInf, kApex, kBase, 1), down, 2, {0, 0, 1});
  EXPECT_FALSE(ray_cone({{-3, 0, Real(1.01)}, {1, 0, 0}}, kInf, kApex, kBase, 1));
}

TEST(RayCone, ThroughTheApexObliquely) {
  // Direction within the opening angle (slope 0.1 < 0.5): enters at the apex.
  const Ray ray{{Real(-0.2), 0, 3}, {Real(0.1), 0, -1}};
  const auto hit = ray_cone(ray, kInf, kApex, kBase, 1);
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->t, Real(2), kTol * 4);
  EXPECT_LT(glm::dot(hit->normal, ray.direction), Real(0));
  // Parallel to a generator line, 0.1 inside it: the quadratic degenerates to a linear
  // equation; enters the opposite side at z = 0.9.
  const Real cos_a = 2 / std::sqrt(Real(5));
  const Real sin_a = 1 / std::sqrt(Real(5));
  const Ray gen{{Real(-0.6), 0, 2}, {Real(0.5), 0, -1}};
  expect_hit(ray_cone(gen, kInf, kApex, kBase, 1), gen, Real(1.1), {-cos_a, 0, sin_a});
  // Beyond the apex, outside the opening angle: the mirror nappe is not part of the solid.
  EXPECT_FALSE(ray_cone({{-3, 0, Real(1.5)}, {1, 0, 0}}, kInf, kApex, kBase, 1));
  EXPECT_FALSE(ray_cone({{0, 0, 5}, {0, 0, 1}}, kInf, kApex, kBase, 1));
}

TEST(RayCone, InsideDegenerateAndScales) {
  const Ray inside{{0, 0, 0}, {1, 2, 3}};
  expect_inside(ray_cone(inside, kInf, kApex, kBase, 1), inside);
  const Ray apex{kApex, {0, 0, 1}};
  expect_inside(ray_cone(apex, kInf, kApex, kBase, 1), apex);
  EXPECT_FALSE(ray_cone({{-3, 0, 0}, {1, 0, 0}}, kInf, kApex, kApex, 1));
  const Real cos_a = 2 / std::sqrt(Real(5));
  const Real sin_a = 1 / std::sqrt(Real(5));
  for (const Real s : {Real(1e-4), Real(1e4)}) {
    const Ray side{{-3 * s, 0, 0}, {s, 0, 0}};
    expect_hit(ray_cone(side, kInf, kApex * s, kBase * s, s), side, Real(2.5), {-cos_a, 0, sin_a}, s);
  }
  const Vec3 c(1e4, -1e4, -1e4);
  const Ray side{c + Vec3(-3, 0, 0), {1, 0, 0}};
  const auto hit = ray_cone(side, kInf, c + kApex, c + kBase, 1);
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->t, Real(2.5), kTol * 100);
  // A ray from far away (10^4 units) to the side of the cone.
  const Ray far{{-1e4, 0, 0}, {1, 0, 0}};
  EXPECT_NEAR(ray_cone(far, kInf, kApex, kBase, 1)->t, Real(1e4 - 0.5), kTol * 1e4);
}

// ---------------------------------------------------------------------------------------
// Plane and half-space: z = 1 (n = +z, d = 1).

TEST(RayPlane, BothSidesParallelAndInPlane) {
  const Vec3 n(0, 0, 1);
  const Ray above{{0, 0, 5}, {0, 0, -2}};
  expect_hit(ray_plane(above, kInf, n, 1), above, 2, {0, 0, 1});
  const Ray below{{3, 0, -1}, {0, 0, 1}};
  expect_hit(ray_plane(below, kInf, n, 1), below, 2, {0, 0, -1});
  EXPECT_FALSE(ray_plane({{0, 0, 5}, {0, 0, 1}}, kInf, n, 1));
  EXPECT_FALSE(ray_plane({{0, 0, 5}, {1, 0, 0}}, kInf, n, 1));
  EXPECT_FALSE(ray_plane(above, Real(1.5), n, 1));
  const auto in = ray_plane({{1, 2, 1}, {1, 0, 0}}, kInf, n, 1);
  ASSERT_TRUE(in);
  EXPECT_EQ(in->t, Real(0));
  EXPECT_NEAR(std::abs(in->normal.z), Real(1), kTol);
  // A non-unit normal describes the same plane when the offset is scaled alike.
  expect_hit(ray_plane(above, kInf, Vec3(0, 0, 4), 4), above, 2, {0, 0, 1});
  EXPECT_FALSE(ray_plane(above, kInf, Vec3(0), 0));
}

TEST(RayHalfspace, InsideOutsideAndParallel) {
  const Vec3 n(0, 0, 1);
  const Ray above{{0, 0, 5}, {0, 0, -1}};
  expect_hit(ray_halfspace(above, kInf, n, 1), above, 4, {0, 0, 1});
  const Ray inside{{0, 0, 0}, {0, 0, 1}};
  expect_inside(ray_halfspace(inside, kInf, n, 1), inside);
  const Ray on{{0, 0, 1}, {1, 0, 0}};
  expect_inside(ray_halfspace(on, kInf, n, 1), on);
  EXPECT_FALSE(ray_halfspace({{0, 0, 5}, {0, 0, 1}}, kInf, n, 1));
  EXPECT_FALSE(ray_halfspace({{0, 0, 5}, {1, 0, 0}}, kInf, n, 1));
  EXPECT_FALSE(ray_halfspace(above, Real(3.9), n, 1));
  EXPECT_TRUE(ray_halfspace({Vec3(0), Vec3(0)}, kInf, n, 1));
  EXPECT_FALSE(ray_halfspace({Vec3(5), Vec3(0)}, kInf, n, 1));
  // Tilted, far from the origin.
  const Vec3 tilted = glm::normalize(Vec3(1, 1, 0));
  const Real offset = glm::dot(tilted, Vec3(1e4, 1e4, 0));
  const Ray far{{2e4, 1e4, 0}, {-1, 0, 0}};
  const auto hit = ray_halfspace(far, kInf, tilted, offset);
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->t, Real(1e4), kTol * 1e4);
}

// ---------------------------------------------------------------------------------------
// Triangle (0,0,0), (1,0,0), (0,1,0)

const Vec3 kA(0, 0, 0);
const Vec3 kB(1, 0, 0);
const Vec3 kC(0, 1, 0);

TEST(RayTriangle, BothSidesEdgesAndVertices) {
  const Ray above{{Real(0.25), Real(0.25), 1}, {0, 0, -1}};
  expect_hit(ray_triangle(above, kInf, kA, kB, kC), above, 1, {0, 0, 1});
  const Ray below{{Real(0.25), Real(0.25), -2}, {0, 0, 4}};
  expect_hit(ray_triangle(below, kInf, kA, kB, kC), below, Real(0.5), {0, 0, -1});
  // Edges and vertices belong to the triangle.
  for (const Vec3& p : {kA, kB, kC, Vec3(0.5, 0, 0), Vec3(0, 0.5, 0), Vec3(0.5, 0.5, 0)}) {
    const Ray ray{p + Vec3(0, 0, 2), {0, 0, -1}};
    const auto hit = ray_triangle(ray, kInf, kA, kB, kC);
    ASSERT_TRUE(hit) << p.x << " " << p.y;
    EXPECT_EQ(hit->t, Real(2));
  }
  EXPECT_FALSE(ray_triangle({{Real(0.6), Real(0.6), 1}, {0, 0, -1}}, kInf, kA, kB, kC));
  EXPECT_FALSE(ray_triangle({{Real(-0.01), Real(0.5), 1}, {0, 0, -1}}, kInf, kA, kB, kC));
  EXPECT_FALSE(ray_triangle(above, Real(0.99), kA, kB, kC));
  EXPECT_FALSE(ray_triangle({{Real(0.25), Real(0.25), 1}, {0, 0, 1}}, kInf, kA, kB, kC));
}

TEST(RayTriangle, ParallelDegenerateAndZeroDirection) {
  EXPECT_FALSE(ray_triangle({{-1, Real(0.25), 0}, {1, 0, 0}}, kInf, kA, kB, kC));  // in the plane
  EXPECT_FALSE(ray_triangle({{-1, Real(0.25), 1}, {1, 0, 0}}, kInf, kA, kB, kC));
  const Ray down{{Real(0.25), Real(0.25), 1}, {0, 0, -1}};
  EXPECT_FALSE(ray_triangle(down, kInf, kA, kA, kC));
  EXPECT_FALSE(ray_triangle(down, kInf, kA, kA, kA));
  EXPECT_FALSE(ray_triangle({{1, 1, 5}, {0, 0, -1}}, kInf, Vec3(0), Vec3(1, 1, 0), Vec3(2, 2, 0)));
  EXPECT_FALSE(ray_triangle({{1, 1, 5}, {0, -1, -1}}, kInf, Vec3(0), Vec3(1, 1, 1), Vec3(2, 2, 2)));
  EXPECT_FALSE(ray_triangle({{Real(0.25), Real(0.25), 0}, Vec3(0)}, kInf, kA, kB, kC));
  // Origin on the triangle: t = 0.
  const auto on = ray_triangle({{Real(0.25), Real(0.25), 0}, {0, 0, 1}}, kInf, kA, kB, kC);
  ASSERT_TRUE(on);
  EXPECT_EQ(on->t, Real(0));
  EXPECT_NEAR(on->normal.z, Real(-1), kTol);
  EXPECT_TRUE(ray_triangle({{Real(0.25), Real(0.25), 0}, {0, 0, 1}}, 0, kA, kB, kC));
}

TEST(RayTriangle, TinyHugeDirectionsAndFarFromOrigin) {
  // The direction is scaled by a power of two internally: tiny and huge directions give
  // the same hit point.
  for (const Real s : {Real(1e-30), Real(1e-4), Real(1e4), Real(1e30)}) {
    const Ray ray{{Real(0.25), Real(0.25), 1}, {0, 0, -s}};
    const auto hit = ray_triangle(ray, kInf, kA, kB, kC);
    ASSERT_TRUE(hit) << s;
    EXPECT_NEAR(hit->t * s, Real(1), kTol);
    expect_vec_near(hit->point, {Real(0.25), Real(0.25), 0}, kTol);
  }
  for (const Real s : {Real(1e-4), Real(1e4)}) {
    const Ray ray{{Real(0.25) * s, Real(0.25) * s, s}, {0, 0, -2 * s}};
    expect_hit(ray_triangle(ray, kInf, kA * s, kB * s, kC * s), ray, Real(0.5), {0, 0, 1}, s);
  }
  const Vec3 o(1e4, 1e4, -1e4);
  const Ray ray{o + Vec3(Real(0.25), Real(0.25), 3), {0, 0, -1}};
  const auto hit = ray_triangle(ray, kInf, o + kA, o + kB, o + kC);
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->t, Real(3), kTol * 100);
}

TEST(RayTriangle, PreparedRayGivesIdenticalAnswers) {
  test::Random rng(12);
  for (int i = 0; i < 2000; ++i) {
    const Ray ray{rng.vec3(-3, 3), rng.vec3(-2, 2)};
    const TriangleRay prepared = TriangleRay::prepare(ray);
    const Vec3 a = rng.vec3(-1, 1), b = rng.vec3(-1, 1), c = rng.vec3(-1, 1);
    const auto x = ray_triangle(ray, Real(2), a, b, c);
    const auto y = ray_triangle(prepared, Real(2), a, b, c);
    ASSERT_EQ(x.has_value(), y.has_value());
    if (x) {
      EXPECT_EQ(x->t, y->t);
      EXPECT_EQ(x->normal, y->normal);
    }
  }
}

// ---------------------------------------------------------------------------------------
// Zero direction and max_t = 0 on every solid: only an inside (or on-surface) origin hits,
// at t = 0.

TEST(RayCastInput, ZeroDirectionAndZeroMaxTOnEverySolid) {
  const Mat3 axes = glm::mat3_cast(glm::angleAxis(Real(0.3), glm::normalize(Vec3(1, 2, 3))));
  auto solids = [&](const Ray& ray, Real max_t) {
    return std::array<std::optional<RayHit>, 8>{
        ray_sphere(ray, max_t, Vec3(0), 1),           ray_aabb(ray, max_t, kUnitBox),
        ray_obb(ray, max_t, Vec3(0), axes, Vec3(1)),  ray_capsule(ray, max_t, kP0, kP1, Real(0.5)),
        ray_capsule(ray, max_t, kP0, kP0, Real(0.5)), ray_cylinder(ray, max_t, kP0, kP1, Real(0.5)),
        ray_cone(ray, max_t, kApex, kBase, 1),        ray_halfspace(ray, max_t, Vec3(0, 0, 1), 1)};
  };
  const Vec3 inside(Real(0.1), Real(-0.05), Real(-0.6));  // inside all eight
  const Vec3 outside(3, -4, 5);
  for (const auto& hit : solids({inside, Vec3(0)}, kInf)) {
    ASSERT_TRUE(hit);
    EXPECT_EQ(hit->t, Real(0));
    EXPECT_EQ(hit->point, inside);
    EXPECT_NEAR(glm::length(hit->normal), Real(1), kTol);
  }
  const Ray moving{inside, {1, 2, -2}};
  for (const auto& hit : solids(moving, 0)) expect_inside(hit, moving);
  int index = 0;
  for (const auto& hit : solids({outside, Vec3(0)}, kInf)) {
    EXPECT_FALSE(hit) << index++;
  }
  // Heading straight for every solid, but with max_t = 0.
  const Vec3 above(Real(0.1), Real(-0.05), 5);
  index = 0;
  for (const auto& hit : solids({above, {0, 0, -1}}, 0)) EXPECT_FALSE(hit) << index++;
  index = 0;
  for (const auto& hit : solids({above, {0, 0, -1}}, kInf)) EXPECT_TRUE(hit) << index++;
  EXPECT_FALSE(ray_plane({above, Vec3(0)}, kInf, Vec3(0, 0, 1), 1));
  EXPECT_FALSE(ray_plane({above, {0, 0, -1}}, 0, Vec3(0, 0, 1), 1));
  EXPECT_FALSE(ray_triangle({above, {0, 0, -1}}, 0, Vec3(-1, -1, 0), Vec3(1, -1, 0), Vec3(0, 1, 0)));
}

// ---------------------------------------------------------------------------------------
// Non-finite input: never a hit, never a crash.

TEST(RayCastInput, NonFiniteQueriesMiss) {
  test::ScopedNoFpTraps no_traps;
  const Vec3 nan3(kNaN);
  const Ray good{{-3, 0, 0}, {1, 0, 0}};
  const Ray bad_o{{kNaN, 0, 0}, {1, 0, 0}};
  const Ray bad_d{{-3, 0, 0}, {1, kNaN, 0}};
  const Ray inf_d{{-3, 0, 0}, {kInf, 0, 0}};
  for (const Ray& ray : {bad_o, bad_d, inf_d}) {
    EXPECT_FALSE(ray_sphere(ray, kInf, Vec3(0), 1));
    EXPECT_FALSE(ray_aabb(ray, kInf, kUnitBox));
    EXPECT_FALSE(ray_obb(ray, kInf, Vec3(0), Mat3(1), Vec3(1)));
    EXPECT_FALSE(ray_capsule(ray, kInf, kP0, kP1, 1));
    EXPECT_FALSE(ray_cylinder(ray, kInf, kP0, kP1, 1));
    EXPECT_FALSE(ray_cone(ray, kInf, kApex, kBase, 1));
    EXPECT_FALSE(ray_plane(ray, kInf, Vec3(1, 0, 0), 0));
    EXPECT_FALSE(ray_halfspace(ray, kInf, Vec3(1, 0, 0), 0));
    EXPECT_FALSE(ray_triangle(ray, kInf, Vec3(0, -1, -1), Vec3(0, 1, -1), Vec3(0, 0, 1)));
  }
  EXPECT_FALSE(ray_sphere(good, kNaN, Vec3(0), 1));
  EXPECT_FALSE(ray_aabb(good, kNaN, kUnitBox));
  EXPECT_FALSE(ray_triangle(good, kNaN, Vec3(0, -1, -1), Vec3(0, 1, -1), Vec3(0, 0, 1)));
  EXPECT_FALSE(ray_sphere(good, kInf, nan3, 1));
  EXPECT_FALSE(ray_sphere(good, kInf, Vec3(0), kNaN));
  EXPECT_FALSE(ray_aabb(good, kInf, Aabb{nan3, Vec3(1)}));
  EXPECT_FALSE(ray_obb(good, kInf, Vec3(0), Mat3(kNaN), Vec3(1)));
  EXPECT_FALSE(ray_capsule(good, kInf, nan3, kP1, 1));
  EXPECT_FALSE(ray_cylinder(good, kInf, kP0, kP1, kNaN));
  EXPECT_FALSE(ray_cone(good, kInf, kApex, nan3, 1));
  EXPECT_FALSE(ray_plane(good, kInf, nan3, 0));
  EXPECT_FALSE(ray_halfspace(good, kInf, Vec3(1, 0, 0), kNaN));
  EXPECT_FALSE(ray_triangle(good, kInf, nan3, Vec3(0, 1, -1), Vec3(0, 0, 1)));
}

TEST(RayCastInput, InfiniteMaxTIsAnUnboundedRay) {
  const Ray ray{{-1e6, 0, 0}, {1, 0, 0}};
  EXPECT_TRUE(ray_sphere(ray, kInf, Vec3(0), 1));
  EXPECT_TRUE(ray_aabb(ray, kInf, kUnitBox));
  EXPECT_TRUE(ray_capsule(ray, kInf, kP0, kP1, 1));
  EXPECT_TRUE(ray_cylinder(ray, kInf, kP0, kP1, 1));
  EXPECT_TRUE(ray_cone(ray, kInf, kApex, kBase, 1));
  EXPECT_TRUE(ray_triangle(ray, kInf, Vec3(0, -1, -1), Vec3(0, 1, -1), Vec3(0, 0, 1)));
  // An infinite max_t with a zero direction never evaluates 0 * inf.
  EXPECT_FALSE(ray_sphere({{5, 0, 0}, Vec3(0)}, kInf, Vec3(0), 1));
  EXPECT_FALSE(ray_plane({{5, 0, 0}, Vec3(0)}, kInf, Vec3(1, 0, 0), 0));
}

// ---------------------------------------------------------------------------------------
// Extreme but valid input (coordinates up to kMaxCoordinate, denormals, zeros, huge and
// tiny directions, infinite max_t): always a defined answer. The floating-point trap of
// the test main turns any NaN into a crash; every hit must be in range with a unit normal.

namespace fuzz {

Real pick(test::Random& rng) {
  // Not static: GCC 12 with -frounding-math (CGAL's flag) miscompiles static arrays of
  // inexact floating-point constants; this keeps the file correct under any flags.
  const Real values[] = {0,
                         std::numeric_limits<Real>::denorm_min(),
                         std::numeric_limits<Real>::min(),
                         Real(1e-30),
                         Real(1e-4),
                         Real(0.5),
                         Real(1),
                         Real(3),
                         Real(1e4),
                         kMaxCoordinate * Real(1e-3),
                         kMaxCoordinate};
  const Real magnitude = values[rng.integer(0, 10)];
  const Real v = magnitude * rng.uniform(Real(0.5), Real(1));
  return rng.integer(0, 1) != 0 ? v : -v;
}

Vec3 pick3(test::Random& rng) {
  // Often reuse one magnitude on all axes, so that vectors are not dominated by one axis.
  if (rng.integer(0, 2) == 0) return rng.unit_vector() * std::abs(pick(rng));
  return {pick(rng), pick(rng), pick(rng)};
}

Real pick_size(test::Random& rng) {
  const Real v = std::abs(pick(rng));
  return v > Real(0) ? v : Real(1);
}

int g_hits = 0;

void check(const std::optional<RayHit>& hit, const Ray& ray, Real max_t, const char* what, int i) {
  if (!hit) return;
  ++g_hits;
  ASSERT_LE(std::abs(ray.origin.x), kMaxCoordinate);  // the generator stays in range
  ASSERT_TRUE(std::isfinite(hit->t) && hit->t >= 0 && hit->t <= max_t) << what << " " << i;
  ASSERT_TRUE(is_finite(hit->point)) << what << " " << i;
  ASSERT_TRUE(is_finite(hit->normal)) << what << " " << i;
  EXPECT_NEAR(glm::length(hit->normal), Real(1), Real(1e-3)) << what << " " << i;
}

}  // namespace fuzz

TEST(RayCastInput, ExtremeValidInputNeverNaN) {
  test::Random rng(13);
  fuzz::g_hits = 0;
  for (int i = 0; i < 20000; ++i) {
    const Ray ray{fuzz::pick3(rng), fuzz::pick3(rng)};
    const Real max_t = rng.integer(0, 3) == 0 ? kInf : std::abs(fuzz::pick(rng));
    const Vec3 p = fuzz::pick3(rng);
    const Vec3 q = rng.integer(0, 3) == 0 ? p : fuzz::pick3(rng);
    const Vec3 w = fuzz::pick3(rng);
    const Real r = fuzz::pick_size(rng);
    const Real hz = rng.integer(0, 5) == 0 ? Real(0) : fuzz::pick_size(rng);
    const Real hy = fuzz::pick_size(rng);
    const Real hx = fuzz::pick_size(rng);
    const Vec3 h(hx, hy, hz);
    const Mat3 axes = glm::mat3_cast(rng.rotation());
    fuzz::check(ray_sphere(ray, max_t, p, r), ray, max_t, "sphere", i);
    fuzz::check(ray_aabb(ray, max_t, Aabb{min(p, q), max(p, q)}), ray, max_t, "aabb", i);
    fuzz::check(ray_obb(ray, max_t, p, axes, h), ray, max_t, "obb", i);
    fuzz::check(ray_capsule(ray, max_t, p, q, r), ray, max_t, "capsule", i);
    fuzz::check(ray_cylinder(ray, max_t, p, q, r), ray, max_t, "cylinder", i);
    fuzz::check(ray_cone(ray, max_t, p, q, r), ray, max_t, "cone", i);
    const Vec3 n = rng.integer(0, 9) == 0 ? Vec3(0) : rng.unit_vector();
    fuzz::check(ray_plane(ray, max_t, n, fuzz::pick(rng)), ray, max_t, "plane", i);
    fuzz::check(ray_halfspace(ray, max_t, n, fuzz::pick(rng)), ray, max_t, "halfspace", i);
    fuzz::check(ray_triangle(ray, max_t, p, q, w), ray, max_t, "triangle", i);
    if (::testing::Test::HasFatalFailure()) return;
  }
  // The sweep reaches the hit paths (not only early rejections).
  EXPECT_GT(fuzz::g_hits, 20000);
  ::testing::Test::RecordProperty("hits", fuzz::g_hits);
}

}  // namespace test_raycast_primitives
}  // namespace proxima::geometry
