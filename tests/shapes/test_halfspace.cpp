// HalfSpace: every member checked against references the half-space does not compute
// itself: the implicit test n . x <= d with the caller's unnormalised n and d (contains,
// ray marching, closest point), exhaustive search over the vertices of the clipped cube
// (support), and boxes derived by hand for exactly axis-aligned normals.
#include <gtest/gtest.h>

#include <proxima/core/tolerance.hpp>
#include <proxima/shapes/halfspace.hpp>
#include <proxima/shapes/placed.hpp>
#include <proxima/shapes/sphere.hpp>

#include <vector>

#include "shapes/shape_test_util.hpp"
#include "support/random.hpp"

namespace proxima {
namespace test_halfspace {

using test::precision_tolerance;

HalfSpace make(const Vec3& n, Real d) { return HalfSpace::create(n, d).value(); }

// The vertices of {x : n . x <= d} clipped to the cube |x|_inf <= e: the cube corners
// inside and the crossings of the plane with the 12 cube edges (computed in double).
std::vector<Vec3> clipped_cube_vertices(const Vec3& n, Real d, Real e) {
  std::vector<Vec3> out;
  auto value = [&](const double p[3]) { return n.x * p[0] + n.y * p[1] + n.z * p[2] - static_cast<double>(d); };
  for (int i = 0; i < 8; ++i) {
    const double c[3] = {i & 1 ? double(e) : -double(e), i & 2 ? double(e) : -double(e),
                         i & 4 ? double(e) : -double(e)};
    if (value(c) <= 0.0) out.emplace_back(static_cast<Real>(c[0]), static_cast<Real>(c[1]), static_cast<Real>(c[2]));
    // Edges from this corner towards +axis neighbours.
    for (int a = 0; a < 3; ++a) {
      if (i & (1 << a)) continue;
      double c2[3] = {c[0], c[1], c[2]};
      c2[a] = e;
      const double v0 = value(c);
      const double v1 = value(c2);
      if ((v0 < 0.0 && v1 > 0.0) || (v0 > 0.0 && v1 < 0.0)) {
        const double t = v0 / (v0 - v1);
        double p[3] = {c[0], c[1], c[2]};
        p[a] = c[a] + t * (c2[a] - c[a]);
        out.emplace_back(static_cast<Real>(p[0]), static_cast<Real>(p[1]), static_cast<Real>(p[2]));
      }
    }
  }
  return out;
}

TEST(HalfSpace, CreateValidatesNormalAndOffset) {
  test::expect_vector_field_finite_validated([](const Vec3& n) { return HalfSpace::create(n, 1); }, Vec3(0, 0, 1),
                                             "normal");
  test::expect_error(HalfSpace::create(Vec3(0), 1), ErrorCode::Degenerate, "normal");
  test::expect_error(HalfSpace::create(Vec3(Real(-0.0), 0, Real(0.0)), 1), ErrorCode::Degenerate, "normal");
  test::ScopedNoFpTraps no_traps;
  test::expect_error(HalfSpace::create(Vec3(0, 1, 0), test::nan_value()), ErrorCode::NotFinite, "offset");
  test::expect_error(HalfSpace::create(Vec3(0, 1, 0), -test::inf_value()), ErrorCode::NotFinite, "offset");
  test::expect_error(HalfSpace::create(Vec3(0, 1, 0), kMaxCoordinate * 2), ErrorCode::OutOfRange, "offset");
  // The offset divided by a tiny normal's length leaves the supported range.
  const Real tiny = test::kFloat ? Real(1e-30) : Real(1e-200);
  test::expect_error(HalfSpace::create(Vec3(tiny, 0, 0), kMaxCoordinate / 2), ErrorCode::OutOfRange, "offset");
  // The normal is checked before the offset.
  test::expect_error(HalfSpace::create(Vec3(0), test::nan_value()), ErrorCode::Degenerate, "normal");
}

TEST(HalfSpace, CreateNormalisesNormalAndOffset) {
  HalfSpace h = make(Vec3(0, 0, 2), 4);
  EXPECT_EQ(h.normal(), Vec3(0, 0, 1));
  EXPECT_EQ(h.offset(), Real(2));
  h = make(Vec3(3, 0, -4), 10);
  test::expect_vec_near(h.normal(), Vec3(Real(0.6), 0, Real(-0.8)), precision_tolerance(Real(1), Real(4)));
  EXPECT_NEAR(h.offset(), Real(2), precision_tolerance(Real(2), Real(4)));
  // Tiny, denormal and huge normals normalise without under- or overflow.
  const Real denorm = std::numeric_limits<Real>::denorm_min();
  h = make(Vec3(denorm, 0, 0), 0);
  EXPECT_EQ(h.normal(), Vec3(1, 0, 0));
  EXPECT_EQ(h.offset(), Real(0));
  h = make(Vec3(kMaxCoordinate, kMaxCoordinate, 0), kMaxCoordinate);
  test::expect_vec_near(h.normal(), Vec3(Real(1) / std::sqrt(Real(2)), Real(1) / std::sqrt(Real(2)), 0),
                        precision_tolerance(Real(1), Real(4)));
  EXPECT_NEAR(h.offset(), Real(1) / std::sqrt(Real(2)), precision_tolerance(Real(1), Real(4)));
  EXPECT_EQ(HalfSpace::kType, ShapeType::HalfSpace);
  EXPECT_EQ(h.core_radius(), Real(0));
}

TEST(HalfSpace, ContainsMatchesImplicitFunction) {
  test::Random rng(601);
  for (int k = 0; k < 50; ++k) {
    const Vec3 n = rng.vec3(Real(-3), Real(3));
    if (glm::length(n) < Real(0.1)) continue;
    const Real d = rng.uniform(Real(-5), Real(5));
    const HalfSpace h = make(n, d);
    EXPECT_NEAR(glm::length(h.normal()), Real(1), precision_tolerance(Real(1), Real(4)));
    for (int i = 0; i < 400; ++i) {
      const Vec3 p = rng.vec3(Real(-10), Real(10));
      // The caller's unnormalised form, evaluated in double.
      const double f = double(n.x) * p.x + double(n.y) * p.y + double(n.z) * p.z - d;
      if (std::abs(f) <= 1e-3) continue;
      EXPECT_EQ(h.contains(p), f <= 0.0);
    }
  }
  // The boundary counts as inside.
  const HalfSpace floor = make(Vec3(0, 0, 1), 0);
  EXPECT_TRUE(floor.contains(Vec3(5, -7, 0)));
  EXPECT_TRUE(floor.contains(Vec3(0, 0, -1e6)));
  EXPECT_FALSE(floor.contains(Vec3(0, 0, Real(1e-6))));
}

TEST(HalfSpace, ClosestPointIsTheProjection) {
  test::Random rng(602);
  for (int k = 0; k < 2000; ++k) {
    const Vec3 n = rng.vec3(Real(-3), Real(3));
    if (glm::length(n) < Real(0.1)) continue;
    const Real d = rng.uniform(Real(-5), Real(5));
    const HalfSpace h = make(n, d);
    const Vec3 p = rng.vec3(Real(-10), Real(10));
    const SurfacePoint sp = h.closest_point(p);
    const double len = std::sqrt(double(n.x) * n.x + double(n.y) * n.y + double(n.z) * n.z);
    const double dist = (double(n.x) * p.x + double(n.y) * p.y + double(n.z) * p.z - d) / len;
    const Real tol = precision_tolerance(Real(40), Real(16));
    EXPECT_NEAR(sp.signed_distance, dist, tol);
    // The point lies on the plane, at |signed distance| from p, along the normal.
    const double on_plane = (double(n.x) * sp.point.x + double(n.y) * sp.point.y + double(n.z) * sp.point.z - d) / len;
    EXPECT_NEAR(on_plane, 0.0, tol);
    EXPECT_NEAR(glm::length(p - sp.point), std::abs(sp.signed_distance), tol);
    test::expect_vec_near(sp.normal, h.normal(), Real(0));
    if (std::abs(dist) > 1e-3) {
      EXPECT_EQ(sp.signed_distance < 0, h.contains(p));
    }
  }
}

TEST(HalfSpace, SupportSolvesTheClippedLinearProgramme) {
  test::Random rng(603);
  const Real e = HalfSpace::kSupportExtent;
  for (int k = 0; k < 3000; ++k) {
    Vec3 n = rng.unit_vector();
    // Some normals and directions with exact zeros, some directions along +-n.
    if (k % 5 == 1) n[k % 3] = 0;
    if (k % 7 == 2) n = Vec3(k % 2 ? Real(1) : Real(-1), 0, 0);
    const Real d = rng.uniform(Real(-2), Real(2)) * (k % 3 == 0 ? e : Real(10));
    const HalfSpace h = make(n, d);
    Vec3 dir = rng.unit_vector();
    if (k % 11 == 3) dir = h.normal();
    if (k % 11 == 4) dir = -h.normal();
    if (k % 13 == 5) dir[k % 3] = 0;
    const Real extent = std::max(e, std::abs(h.offset()));
    const Vec3 s = h.support(dir);
    const auto verts = clipped_cube_vertices(h.normal(), h.offset(), extent);
    ASSERT_FALSE(verts.empty());
    const Real best = test::max_dot(verts, dir);
    const Real tol = precision_tolerance(Real(4) * extent, Real(16));
    EXPECT_NEAR(glm::dot(s, dir), best, tol) << "case " << k;
    // The answer is a point of the clipped half-space.
    EXPECT_LE(test::max_abs(s), extent);
    EXPECT_LE(glm::dot(h.normal(), s) - h.offset(), tol) << "case " << k;
    EXPECT_EQ(h.core_support(dir), s);
  }
}

TEST(HalfSpace, SupportDegenerateDirections) {
  const HalfSpace h = make(Vec3(1, 2, 3), 1);
  for (const Vec3& d : {Vec3(0), Vec3(std::numeric_limits<Real>::denorm_min(), 0, 0),
                        Vec3(kRealMax, -kRealMax, kRealMax), Vec3(0, 0, Real(-0.0))}) {
    const Vec3 s = h.support(d);
    EXPECT_TRUE(test::all_finite(s));
    EXPECT_LE(glm::dot(h.normal(), s) - h.offset(), precision_tolerance(HalfSpace::kSupportExtent * 4, Real(16)));
  }
  // A floor: the support points away from the floor's top face go to the cube's corners.
  const HalfSpace floor = make(Vec3(0, 0, 1), 0);
  EXPECT_EQ(floor.support(Vec3(1, 1, -1)),
            Vec3(HalfSpace::kSupportExtent, HalfSpace::kSupportExtent, -HalfSpace::kSupportExtent));
  EXPECT_EQ(floor.support(Vec3(1, -1, 1)), Vec3(HalfSpace::kSupportExtent, -HalfSpace::kSupportExtent, 0));
  // A plane beyond the cube: the cube grows to reach it.
  const HalfSpace deep = make(Vec3(0, 0, 1), -HalfSpace::kSupportExtent * 3);
  EXPECT_EQ(deep.support(Vec3(0, 0, 1)).z, -HalfSpace::kSupportExtent * 3);
}

TEST(HalfSpace, LocalBoxIsBoundedOnlyAlongAnExactAxisNormal) {
  Aabb b = make(Vec3(0, 0, 1), 3).local_aabb();
  EXPECT_EQ(b.max, Vec3(kRealMax, kRealMax, 3));
  EXPECT_EQ(b.min, Vec3(-kRealMax));
  b = make(Vec3(0, -2, 0), 4).local_aabb();  // y >= -2
  EXPECT_EQ(b.min, Vec3(-kRealMax, -2, -kRealMax));
  EXPECT_EQ(b.max, Vec3(kRealMax));
  b = make(Vec3(1, 1, 0), 3).local_aabb();
  EXPECT_EQ(b.min, Vec3(-kRealMax));
  EXPECT_EQ(b.max, Vec3(kRealMax));
  EXPECT_TRUE(b.is_valid());
}

TEST(HalfSpace, WorldBoxIsFiniteAndContainsTheSolid) {
  test::Random rng(604);
  for (int k = 0; k < 500; ++k) {
    Vec3 n = k % 4 == 0 ? Vec3(0, 0, 1) : rng.unit_vector();
    const HalfSpace h = make(n, rng.uniform(Real(-5), Real(5)));
    Transform pose = rng.pose(Real(100));
    if (k % 8 == 0) pose.rotation = kIdentityQuat;
    const Aabb box = h.world_aabb(pose);
    ASSERT_TRUE(test::all_finite(box.min) && test::all_finite(box.max));
    ASSERT_TRUE(box.is_valid());
    // Points of the solid (sampled in a 200-cube around the pose) are in the box.
    for (int i = 0; i < 50; ++i) {
      const Vec3 local = rng.vec3(Real(-100), Real(100));
      if (!h.contains(local)) continue;
      const Vec3 w = pose.apply(local);
      for (int a = 0; a < 3; ++a) {
        EXPECT_LE(box.min[a], w[a] + precision_tolerance(Real(300)));
        EXPECT_GE(box.max[a], w[a] - precision_tolerance(Real(300)));
      }
    }
  }
}

TEST(HalfSpace, WorldBoxOfExactAxisPoses) {
  // Translation only: the floor z <= 1 moved by (5, 6, 7) is z <= 8.
  const HalfSpace floor = make(Vec3(0, 0, 1), 1);
  Aabb b = floor.world_aabb(Transform{Vec3(5, 6, 7), kIdentityQuat});
  EXPECT_EQ(b.max, Vec3(kRealMax, kRealMax, 8));
  EXPECT_EQ(b.min, Vec3(-kRealMax));
  // Half a turn about z (exact quaternion): x <= 2 becomes x >= 8 after moving by 10 in x.
  const HalfSpace wall = make(Vec3(1, 0, 0), 2);
  b = wall.world_aabb(Transform{Vec3(10, 0, 0), Quat(0, 0, 0, 1)});
  EXPECT_EQ(b.min, Vec3(8, -kRealMax, -kRealMax));
  EXPECT_EQ(b.max, Vec3(kRealMax));
  // A rotation that leaves the normal oblique: unbounded on every axis, never inf.
  b = floor.world_aabb(Transform{Vec3(1, 2, 3), glm::angleAxis(Real(0.3), glm::normalize(Vec3(1, 1, 0)))});
  EXPECT_EQ(b.min, Vec3(-kRealMax));
  EXPECT_EQ(b.max, Vec3(kRealMax));
  // A plane far away and a pose far away stay finite.
  const HalfSpace far = make(Vec3(0, -1, 0), kMaxCoordinate);
  b = far.world_aabb(Transform{Vec3(0, -kMaxCoordinate, 0), kIdentityQuat});
  EXPECT_TRUE(test::all_finite(b.min) && test::all_finite(b.max));
  EXPECT_EQ(b.min.y, -kMaxCoordinate * 2);
}

auto implicit_inside(const Vec3& n, Real d) {
  return [n, d](const Vec3& p) { return double(n.x) * p.x + double(n.y) * p.y + double(n.z) * p.z <= double(d); };
}

TEST(HalfSpace, RaycastMatchesMarching) {
  test::Random rng(605);
  for (const Real s : test::scales()) {
    for (int k = 0; k < 10; ++k) {
      const Vec3 n = rng.vector_of_length(Real(0.5), Real(2));
      const Real d = rng.uniform(Real(-0.5), Real(0.5)) * s;
      const Aabb region{Vec3(Real(-2) * s), Vec3(Real(2) * s)};
      test::check_raycast_solid(make(n, d), implicit_inside(n, d), region, precision_tolerance(Real(16) * s, Real(256)),
                                rng, 300);
    }
  }
}

// The sweep above as the sanitizer build (clang) drew it while its draws were arguments of
// one call, evaluated left to right there (the normal's direction before its length, a
// point's x before its y and z). Every ray agrees with the march; one half-space leaves fewer
// rays missing than the sweep's floor asks, a property of where it lies, not of the answers.
TEST(HalfSpace, RaycastMatchesMarchingOnTheLeftToRightDraws) {
  test::Random rng(605);
  for (const Real s : test::scales()) {
    for (int k = 0; k < 10; ++k) {
      const Vec3 direction = rng.unit_vector();
      const Vec3 n = direction * rng.uniform(Real(0.5), Real(2));
      const Real d = rng.uniform(Real(-0.5), Real(0.5)) * s;
      const Aabb region{Vec3(Real(-2) * s), Vec3(Real(2) * s)};
      test::RaycastCounts counts;
      test::raycast_against_marching(make(n, d), implicit_inside(n, d), region,
                                     precision_tolerance(Real(16) * s, Real(256)), rng, 300, test::DrawOrder::XFirst,
                                     counts);
      if (s == Real(1e4) && k == 8) {
        // The case under the sweep's coverage floor (more than 30 misses of 300): this
        // half-space holds the region's centre and its plane lies 4,900 beyond it (of a
        // half-width of 20,000), so the rays aimed at the middle mostly enter it.
        EXPECT_EQ(counts.misses, 27);
      }
    }
  }
}

TEST(HalfSpace, RaycastAnalyticCases) {
  const HalfSpace floor = make(Vec3(0, 0, 1), 1);
  const Real tol = precision_tolerance(Real(10), Real(16));
  auto hit = floor.raycast(Ray{Vec3(3, 4, 10), Vec3(0, 0, -3)}, Real(10));
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->t, Real(3), tol);
  test::expect_vec_near(hit->normal, Vec3(0, 0, 1), tol);
  test::expect_vec_near(hit->point, Vec3(3, 4, 1), tol);
  // Parallel above, away, too short.
  EXPECT_FALSE(floor.raycast(Ray{Vec3(0, 0, 2), Vec3(1, 0, 0)}, Real(100)));
  EXPECT_FALSE(floor.raycast(Ray{Vec3(0, 0, 2), Vec3(0, 0, 1)}, Real(100)));
  EXPECT_FALSE(floor.raycast(Ray{Vec3(0, 0, 2), Vec3(0, 0, -1)}, Real(0.5)));
  // Inside and on the boundary: t = 0.
  hit = floor.raycast(Ray{Vec3(0, 0, 1), Vec3(1, 0, 0)}, Real(100));
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->t, Real(0));
  test::expect_vec_near(hit->normal, Vec3(-1, 0, 0), tol);
  // Zero direction.
  EXPECT_TRUE(floor.raycast(Ray{Vec3(0, 0, -5), Vec3(0)}, Real(1)));
  EXPECT_FALSE(floor.raycast(Ray{Vec3(0, 0, 5), Vec3(0)}, Real(1)));
  // Unbounded max_t and grazing directions.
  hit = floor.raycast(Ray{Vec3(0, 0, 2), Vec3(1, 0, Real(-1e-6))}, std::numeric_limits<Real>::max());
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->t, Real(1e6), Real(1e6) * precision_tolerance(Real(1), Real(16)));
}

TEST(HalfSpace, PlacedQueries) {
  test::Random rng(606);
  const HalfSpace h = make(Vec3(1, 2, 2), 3);  // normal (1, 2, 2)/3, offset 1
  for (int i = 0; i < 500; ++i) {
    const Transform pose = rng.pose(Real(20));
    const Vec3 q = rng.vec3(Real(-30), Real(30));
    const Vec3 wn = pose.apply_vector(h.normal());
    const Real wd = h.offset() + glm::dot(wn, pose.position);
    const Real tol = precision_tolerance(Real(60), Real(32));
    const SurfacePoint sp = closest_point(h, pose, q);
    EXPECT_NEAR(sp.signed_distance, glm::dot(wn, q) - wd, tol);
    test::expect_vec_near(sp.normal, wn, tol);
    if (std::abs(glm::dot(wn, q) - wd) > tol) {
      EXPECT_EQ(contains(h, pose, q), glm::dot(wn, q) <= wd);
    }
  }
}

template <class T>
concept HasMassProperties = requires(const T& t) {
  t.mass_properties();
};

TEST(HalfSpace, HasNoMassProperties) {
  // Infinite volume: the member does not exist (the CLI reports an error instead).
  static_assert(!HasMassProperties<HalfSpace>);
  static_assert(HasMassProperties<Sphere>);
}

TEST(HalfSpace, NonFiniteQueryInputHasDefinedAnswers) {
  test::exercise_queries_with_non_finite_input(make(Vec3(1, 2, 2), 3));
}

}  // namespace test_halfspace
}  // namespace proxima
