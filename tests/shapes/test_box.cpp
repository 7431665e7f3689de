// Box: every member checked against references the box does not compute itself: its 8
// corners and a grid over its 6 faces (support, world box, closest point), the implicit
// test max |p_i| / h_i <= 1 (contains, ray marching), closed-form and grid-integrated mass
// properties.
#include <gtest/gtest.h>

#include <proxima/core/tolerance.hpp>
#include <proxima/shapes/box.hpp>
#include <proxima/shapes/placed.hpp>

#include <array>
#include <vector>

#include "shapes/shape_test_util.hpp"
#include "support/random.hpp"

namespace proxima {
namespace test_box {

using test::precision_tolerance;

Box make(const Vec3& h) { return Box::create(h).value(); }

std::array<Vec3, 8> corners(const Vec3& h) {
  std::array<Vec3, 8> c;
  for (int i = 0; i < 8; ++i) {
    c[static_cast<std::size_t>(i)] = Vec3(i & 1 ? h.x : -h.x, i & 2 ? h.y : -h.y, i & 4 ? h.z : -h.z);
  }
  return c;
}

auto implicit_inside(const Vec3& h) {
  return [h](const Vec3& p) {
    return std::max({std::abs(p.x) / h.x, std::abs(p.y) / h.y, std::abs(p.z) / h.z}) <= Real(1);
  };
}

Vec3 random_half_extents(test::Random& rng, Real scale) { return rng.in_box(Vec3(Real(0.2)), Vec3(Real(2))) * scale; }

TEST(Box, CreateValidatesEachHalfExtent) {
  test::expect_positive_field_validated([](Real x) { return Box::create(Vec3(x, 1, 1)); }, "half_extents.x");
  test::expect_positive_field_validated([](Real y) { return Box::create(Vec3(1, y, 1)); }, "half_extents.y");
  test::expect_positive_field_validated([](Real z) { return Box::create(Vec3(1, 1, z)); }, "half_extents.z");
  EXPECT_TRUE(Box::create(Vec3(Real(1e-20), 1, kMaxCoordinate)).ok());
}

TEST(Box, Accessors) {
  const Box b = make(Vec3(1, 2, 3));
  EXPECT_EQ(Box::kType, ShapeType::Box);
  EXPECT_EQ(b.half_extents(), Vec3(1, 2, 3));
  EXPECT_EQ(b.core_radius(), Real(0));
  EXPECT_EQ(b.core_support(Vec3(1, -1, 1)), b.support(Vec3(1, -1, 1)));
}

TEST(Box, SupportIsTheBestCorner) {
  test::Random rng(201);
  for (const Real s : test::scales()) {
    for (int k = 0; k < 20; ++k) {
      const Vec3 h = random_half_extents(rng, s);
      const Box b = make(h);
      const auto cs = corners(h);
      for (int i = 0; i < 200; ++i) {
        const Vec3 d = rng.unit_vector();
        const Vec3 sp = b.support(d);
        Real best = -kRealMax;
        for (const Vec3& c : cs) best = std::max(best, glm::dot(c, d));
        EXPECT_EQ(glm::dot(sp, d), best);
        EXPECT_TRUE(std::find(cs.begin(), cs.end(), sp) != cs.end());
      }
    }
  }
}

TEST(Box, SupportMatchesSurfaceSamples) {
  test::Random rng(202);
  for (const Real s : test::scales()) {
    const Vec3 h = random_half_extents(rng, s);
    Real res = Real(0);
    const auto samples = test::box_surface_samples(h, 20, res);
    test::check_support_against_samples(make(h), samples, Real(0), precision_tolerance(Real(4) * s), rng, 300);
  }
}

TEST(Box, SupportWithZeroComponentsAndZeroDirection) {
  const Box b = make(Vec3(1, 2, 3));
  EXPECT_EQ(b.support(Vec3(0)), Vec3(1, 2, 3));
  EXPECT_EQ(b.support(Vec3(-1, 0, 0)), Vec3(-1, 2, 3));
  EXPECT_EQ(b.support(Vec3(0, Real(-0.0), -1)), Vec3(1, 2, -3));
  const Real tiny = std::numeric_limits<Real>::denorm_min();
  EXPECT_EQ(b.support(Vec3(-tiny, tiny, -tiny)), Vec3(-1, 2, -3));
}

TEST(Box, LocalBox) {
  const Box b = make(Vec3(1, 2, 3));
  EXPECT_EQ(b.local_aabb().min, Vec3(-1, -2, -3));
  EXPECT_EQ(b.local_aabb().max, Vec3(1, 2, 3));
}

TEST(Box, WorldBoxIsTheBoxOfTheTransformedCorners) {
  test::Random rng(203);
  for (const Real s : test::scales()) {
    for (int i = 0; i < 300; ++i) {
      const Vec3 h = random_half_extents(rng, s);
      const Transform pose = rng.pose(Real(10) * s);
      const Aabb box = make(h).world_aabb(pose);
      Aabb ref = Aabb::empty();
      for (const Vec3& c : corners(h)) ref.grow(pose.apply(c));
      test::expect_vec_near(box.min, ref.min, precision_tolerance(Real(20) * s));
      test::expect_vec_near(box.max, ref.max, precision_tolerance(Real(20) * s));
    }
  }
}

TEST(Box, WorldBoxMatchesSurfaceSamples) {
  test::Random rng(204);
  for (const Real s : test::scales()) {
    const Vec3 h = random_half_extents(rng, s);
    Real res = Real(0);
    const auto samples = test::box_surface_samples(h, 10, res);
    // The corners are samples, so the sample box is exact: resolution 0.
    test::check_world_aabb_against_samples(make(h), samples, Real(0), precision_tolerance(Real(20) * s), rng, 50,
                                           Real(10) * s);
  }
}

TEST(Box, WorldBoxFarFromOrigin) {
  test::Random rng(205);
  const Vec3 h(Real(0.5), Real(1), Real(2));
  const Box b = make(h);
  for (int i = 0; i < 100; ++i) {
    const Transform pose{rng.vec3(Real(-1e4), Real(1e4)), rng.rotation()};
    const Aabb box = b.world_aabb(pose);
    Aabb ref = Aabb::empty();
    for (const Vec3& c : corners(h)) ref.grow(pose.apply(c));
    test::expect_vec_near(box.min, ref.min, precision_tolerance(Real(2e4)));
    test::expect_vec_near(box.max, ref.max, precision_tolerance(Real(2e4)));
  }
}

TEST(Box, ContainsMatchesImplicitFunction) {
  test::Random rng(206);
  for (const Real s : test::scales()) {
    const Vec3 h = random_half_extents(rng, s);
    const Box b = make(h);
    const auto inside = implicit_inside(h);
    int in = 0;
    for (int i = 0; i < 20000; ++i) {
      const Vec3 p = rng.vec3(Real(-1.5), Real(1.5)) * h;
      EXPECT_EQ(b.contains(p), inside(p));
      in += inside(p) ? 1 : 0;
    }
    EXPECT_GT(in, 4000);
    // The boundary counts: corners, edge and face points.
    for (const Vec3& c : corners(h)) EXPECT_TRUE(b.contains(c));
    EXPECT_TRUE(b.contains(Vec3(h.x, 0, 0)));
    EXPECT_TRUE(b.contains(Vec3(-h.x, h.y, 0)));
    EXPECT_FALSE(b.contains(Vec3(h.x * Real(1.001), 0, 0)));
  }
}

TEST(Box, ClosestPointMatchesBruteForce) {
  test::Random rng(207);
  for (const Real s : test::scales()) {
    const Vec3 h = random_half_extents(rng, s);
    Real res = Real(0);
    const auto samples = test::box_surface_samples(h, 50, res);
    const Aabb region{-Real(2) * h, Real(2) * h};
    test::check_closest_point_solid(make(h), samples, res, precision_tolerance(Real(8) * s), implicit_inside(h), region,
                                    rng, 500);
  }
}

TEST(Box, ClosestPointAnalyticAndDegenerate) {
  const Box b = make(Vec3(1, 2, 3));
  const Real tol = precision_tolerance(Real(8));
  // Outside a face, an edge, a corner.
  SurfacePoint sp = b.closest_point(Vec3(5, 0, 0));
  test::expect_vec_near(sp.point, Vec3(1, 0, 0), tol);
  test::expect_vec_near(sp.normal, Vec3(1, 0, 0), tol);
  EXPECT_NEAR(sp.signed_distance, Real(4), tol);
  sp = b.closest_point(Vec3(4, 6, 0));
  test::expect_vec_near(sp.point, Vec3(1, 2, 0), tol);
  test::expect_vec_near(sp.normal, Vec3(Real(0.6), Real(0.8), 0), tol);
  EXPECT_NEAR(sp.signed_distance, Real(5), tol);
  sp = b.closest_point(Vec3(-2, -3, -4));
  test::expect_vec_near(sp.point, Vec3(-1, -2, -3), tol);
  EXPECT_NEAR(sp.signed_distance, std::sqrt(Real(3)), tol);
  // Inside: nearest face is -x at distance 0.25.
  sp = b.closest_point(Vec3(Real(-0.75), Real(0.5), Real(1)));
  test::expect_vec_near(sp.point, Vec3(-1, Real(0.5), 1), tol);
  test::expect_vec_near(sp.normal, Vec3(-1, 0, 0), tol);
  EXPECT_NEAR(sp.signed_distance, Real(-0.25), tol);
  // The centre of a cube: every face is nearest; a unit normal and distance -h.
  const Box cube = make(Vec3(2));
  sp = cube.closest_point(Vec3(0));
  EXPECT_NEAR(glm::length(sp.normal), Real(1), tol);
  EXPECT_EQ(sp.signed_distance, Real(-2));
  EXPECT_TRUE(cube.contains(sp.point));
  EXPECT_NEAR(test::max_abs(sp.point), Real(2), tol);
  // On a face, an edge and a corner: distance 0, unit normal, the point itself.
  for (const Vec3& q : {Vec3(1, 0, 0), Vec3(1, 2, 0), Vec3(1, -2, 3), Vec3(-1, -2, -3)}) {
    sp = b.closest_point(q);
    EXPECT_EQ(sp.signed_distance, Real(0));
    EXPECT_EQ(sp.point, q);
    EXPECT_NEAR(glm::length(sp.normal), Real(1), tol);
    EXPECT_TRUE(test::all_finite(sp.normal));
  }
  // One ulp outside a face, and outside an edge: a positive distance and a unit normal.
  sp = b.closest_point(Vec3(std::nextafter(Real(1), Real(2)), Real(0.5), 0));
  EXPECT_GT(sp.signed_distance, Real(0));
  test::expect_vec_near(sp.normal, Vec3(1, 0, 0), tol);
  sp = b.closest_point(Vec3(std::nextafter(Real(1), Real(2)), std::nextafter(Real(2), Real(3)), 0));
  EXPECT_GT(sp.signed_distance, Real(0));
  EXPECT_NEAR(glm::length(sp.normal), Real(1), tol);
}

TEST(Box, RaycastMatchesMarching) {
  test::Random rng(208);
  for (const Real s : test::scales()) {
    const Vec3 h = random_half_extents(rng, s);
    const Aabb region{Vec3(Real(-4) * s), Vec3(Real(4) * s)};
    test::check_raycast_solid(make(h), implicit_inside(h), region, precision_tolerance(Real(16) * s, Real(256)), rng,
                              2000);
  }
}

TEST(Box, RaycastAnalyticCases) {
  const Box b = make(Vec3(1, 2, 3));
  const Real tol = precision_tolerance(Real(8), Real(16));
  // Axis-aligned rays (zero direction components), t in units of |direction|.
  auto hit = b.raycast(Ray{Vec3(-5, 0, 0), Vec3(4, 0, 0)}, Real(10));
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->t, Real(1), tol);
  test::expect_vec_near(hit->normal, Vec3(-1, 0, 0), tol);
  hit = b.raycast(Ray{Vec3(0, 0, 9), Vec3(0, 0, -1)}, Real(10));
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->t, Real(6), tol);
  test::expect_vec_near(hit->normal, Vec3(0, 0, 1), tol);
  // Too short, pointing away, passing beside.
  EXPECT_FALSE(b.raycast(Ray{Vec3(-5, 0, 0), Vec3(1, 0, 0)}, Real(3.9)));
  EXPECT_FALSE(b.raycast(Ray{Vec3(-5, 0, 0), Vec3(-1, 0, 0)}, Real(100)));
  EXPECT_FALSE(b.raycast(Ray{Vec3(-5, Real(2.5), 0), Vec3(1, 0, 0)}, Real(100)));
  // Through an edge and a corner exactly: a touching hit.
  hit = b.raycast(Ray{Vec3(-5, 2, 0), Vec3(1, 0, 0)}, Real(100));
  if (hit) {
    EXPECT_NEAR(hit->t, Real(4), tol);
  }
  hit = b.raycast(Ray{Vec3(-4, -5, -6), Vec3(1, 1, 1)}, Real(100));
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->t, Real(3), tol);
  test::expect_vec_near(hit->point, Vec3(-1, -2, -3), tol);
  // Origin inside: t = 0 and normal -direction/|direction|; on the surface counts as inside.
  hit = b.raycast(Ray{Vec3(Real(0.5), 1, 2), Vec3(0, 2, 0)}, Real(10));
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->t, Real(0));
  test::expect_vec_near(hit->normal, Vec3(0, -1, 0), tol);
  hit = b.raycast(Ray{Vec3(1, 0, 0), Vec3(1, 0, 0)}, Real(10));
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->t, Real(0));
  // Zero direction.
  EXPECT_TRUE(b.raycast(Ray{Vec3(0), Vec3(0)}, Real(1)));
  EXPECT_FALSE(b.raycast(Ray{Vec3(5, 0, 0), Vec3(0)}, Real(1)));
  // Unbounded max_t.
  hit = b.raycast(Ray{Vec3(0, 10, 0), Vec3(0, -1, 0)}, std::numeric_limits<Real>::max());
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->t, Real(8), tol);
}

TEST(Box, PlacedQueriesMatchLocalOnes) {
  test::Random rng(209);
  const Vec3 h(1, 2, Real(0.5));
  const Box b = make(h);
  for (int i = 0; i < 500; ++i) {
    const Transform pose = rng.pose(Real(20));
    const Vec3 local_q = rng.vec3(Real(-3), Real(3));
    const Vec3 q = pose.apply(local_q);
    const Real tol = precision_tolerance(Real(40), Real(32));
    const SurfacePoint w = closest_point(b, pose, q);
    const SurfacePoint l = b.closest_point(local_q);
    EXPECT_NEAR(w.signed_distance, l.signed_distance, tol);
    test::expect_vec_near(w.point, pose.apply(l.point), tol);
    if (std::abs(glm::length(l.point - local_q)) > tol) {
      EXPECT_EQ(contains(b, pose, q), implicit_inside(h)(local_q));
    }
    const Vec3 d = rng.unit_vector();
    test::expect_vec_near(support(b, pose, d), pose.apply(b.support(pose.inverse_apply_vector(d))), tol);
    const Ray ray{q, pose.position - q};
    const auto hit = raycast(b, pose, ray, Real(1));
    ASSERT_TRUE(hit);  // the centre is inside, so the segment to it always hits
    EXPECT_TRUE(b.contains(pose.inverse_apply(hit->point)) ||
                std::abs(b.closest_point(pose.inverse_apply(hit->point)).signed_distance) <= tol);
  }
}

TEST(Box, MassPropertiesAnalyticAndIntegrated) {
  test::Random rng(210);
  for (const Real s : {Real(0.01), Real(1), Real(50)}) {
    const Vec3 h = random_half_extents(rng, s);
    const Real density = Real(0.7);
    const MassProperties m = make(h).mass_properties(density);
    const double vol = 8.0 * h.x * h.y * h.z;
    const double mass = density * vol;
    // Inertia of a cuboid of edge lengths a, b, c: m (b^2 + c^2) / 12 on the a axis.
    const double a = 2.0 * h.x;
    const double b = 2.0 * h.y;
    const double c = 2.0 * h.z;
    const double ref[3] = {mass * (b * b + c * c) / 12.0, mass * (a * a + c * c) / 12.0, mass * (a * a + b * b) / 12.0};
    const Real rel = precision_tolerance(Real(1), Real(16));
    EXPECT_NEAR(m.volume, vol, rel * vol);
    EXPECT_NEAR(m.mass, mass, rel * mass);
    EXPECT_EQ(m.centroid, Vec3(0));
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) EXPECT_NEAR(m.inertia[i][j], i == j ? ref[i] : 0.0, rel * ref[i]);
    }
    // Grid integration over a box 10% larger than the solid (110 cells: the faces fall on
    // cell boundaries, so the midpoint rule is exact up to rounding).
    const Aabb region{-h * Real(1.1), h * Real(1.1)};
    const MassProperties grid = test::integrate_mass_on_grid(implicit_inside(h), region, 110, density);
    test::expect_mass_near(m, grid, Real(0.002), Real(0.001) * s);
  }
}

TEST(Box, NonFiniteQueryInputHasDefinedAnswers) { test::exercise_queries_with_non_finite_input(make(Vec3(1, 2, 3))); }

}  // namespace test_box
}  // namespace proxima
