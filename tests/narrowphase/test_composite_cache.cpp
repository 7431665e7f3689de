// The PairCache warm start of pairs with a mesh or compound side: along smooth trajectories
// that approach, touch, cross and leave, the warm intersect and distance answer exactly
// what the cold ones answer (reference: the same query without a cache), for every kind of
// composite pair in both orders; the cache names the parts that answered; a cache holding
// parts of another pair (indices out of range, or in range but unrelated) changes nothing.
#include <gtest/gtest.h>

#include <proxima/narrowphase/narrowphase.hpp>
#include <proxima/shapes/shape.hpp>

#include <cmath>
#include <string>
#include <vector>

#include "support/solid_test_meshes.hpp"

namespace proxima {
namespace test_composite_cache {

struct Scene {
  TriangleMesh sphere_mesh;
  TriangleMesh torus;
  Compound compound;
  Box box;
  Capsule capsule;
};

Scene make_scene() {
  std::vector<CompoundChild> inner;
  inner.push_back({Sphere::create(Real(0.3)).value(), Transform{Vec3(0, 0.6, 0), Quat(1, 0, 0, 0)}});
  inner.push_back({Box::create(Vec3(0.2, 0.1, 0.3)).value(), Transform{Vec3(0, -0.6, 0), Quat(1, 0, 0, 0)}});
  const TriangleMesh small = TriangleMesh::create(test::icosphere_mesh(1, Real(0.35))).value();
  std::vector<CompoundChild> kids;
  for (int k = 0; k < 6; ++k) {
    const Real x = Real(-1.5) + Real(0.6) * Real(k);
    const Transform at{Vec3(x, Real(0.2) * Real(k % 2), 0), glm::angleAxis(Real(0.3) * Real(k), Vec3(0, 0, 1))};
    if (k % 3 == 0) kids.push_back({Capsule::create(Real(0.2), Real(0.3)).value(), at});
    if (k % 3 == 1) kids.push_back({small, at});
    if (k % 3 == 2) kids.push_back({Compound::create(inner).value(), at});
  }
  return Scene{TriangleMesh::create(test::icosphere_mesh(3, Real(1))).value(),
               TriangleMesh::create(test::torus_mesh(Real(1.2), Real(0.35), 24, 12)).value(),
               Compound::create(std::move(kids)).value(), Box::create(Vec3(0.4, 0.3, 0.2)).value(),
               Capsule::create(Real(0.25), Real(0.5)).value()};
}

// Frame k of a path that passes B through A and out again, turning slowly.
Transform path(int k, int frames) {
  const Real s = Real(k) / Real(frames);
  const Vec3 at(Real(-3.5) + Real(7) * s, Real(0.3) * std::sin(Real(6) * s), Real(0.2) * std::cos(Real(4) * s));
  return Transform{at, glm::angleAxis(Real(2) * s, glm::normalize(Vec3(0.3, 1, 0.5)))};
}

// The part of a result that the cache must name on one side.
std::uint32_t part_of(ShapeRef s, const SubShapeId& sub) {
  return s.type() == ShapeType::Compound ? sub.child : sub.triangle;
}

void check_pair(ShapeRef a, ShapeRef b, const std::string& name) {
  constexpr int kFrames = 160;
  const Transform pose_a{Vec3(0.1, -0.05, 0), glm::angleAxis(Real(0.4), Vec3(1, 0, 0))};
  PairCache boolean_cache;
  PairCache distance_cache;
  int hits = 0;
  for (int k = 0; k <= kFrames; ++k) {
    SCOPED_TRACE(name + " frame " + std::to_string(k));
    const Transform pose_b = path(k, kFrames);
    const bool cold_hit = intersect(a, pose_a, b, pose_b);
    EXPECT_EQ(intersect(a, pose_a, b, pose_b, {}, &boolean_cache), cold_hit);
    hits += cold_hit ? 1 : 0;
    const DistanceResult cold = distance(a, pose_a, b, pose_b);
    const DistanceResult warm = distance(a, pose_a, b, pose_b, {}, &distance_cache);
    EXPECT_EQ(warm.signed_distance, cold.signed_distance);
    EXPECT_EQ(warm.status, cold.status);
    if (!is_convex(a.type())) {
      EXPECT_EQ(distance_cache.part_a, part_of(a, warm.sub_a));
    }
    if (!is_convex(b.type())) {
      EXPECT_EQ(distance_cache.part_b, part_of(b, warm.sub_b));
    }
  }
  EXPECT_GT(hits, 5) << name << ": the path must cross A";
  EXPECT_LT(hits, kFrames - 5) << name << ": the path must leave A";
}

TEST(CompositeCache, WarmAnswersEqualColdForEveryCompositeKind) {
  const Scene s = make_scene();
  check_pair(s.sphere_mesh, s.box, "mesh-box");
  check_pair(s.capsule, s.torus, "capsule-mesh");
  check_pair(s.sphere_mesh, s.torus, "mesh-mesh");
  check_pair(s.compound, s.box, "compound-box");
  check_pair(s.capsule, s.compound, "capsule-compound");
  check_pair(s.compound, s.compound, "compound-compound");
  check_pair(s.torus, s.compound, "mesh-compound");
  check_pair(s.compound, s.sphere_mesh, "compound-mesh");
}

TEST(CompositeCache, PartsOfAnotherPairChangeNothing) {
  const Scene s = make_scene();
  const Transform pose_a{};
  const std::vector<std::pair<ShapeRef, ShapeRef>> pairs{
      {s.sphere_mesh, s.box}, {s.sphere_mesh, s.torus}, {s.compound, s.capsule}, {s.compound, s.compound}};
  for (const auto& [a, b] : pairs) {
    for (int k = 0; k <= 40; ++k) {
      const Transform pose_b = path(k, 40);
      for (const std::uint32_t part : {0u, 3u, 17u, 123456u, kNoIndex - 1}) {
        PairCache cache;
        cache.part_a = part;
        cache.part_b = part;
        EXPECT_EQ(intersect(a, pose_a, b, pose_b, {}, &cache), intersect(a, pose_a, b, pose_b)) << k << " " << part;
        cache.part_a = part;
        cache.part_b = part;
        EXPECT_EQ(distance(a, pose_a, b, pose_b, {}, &cache).signed_distance,
                  distance(a, pose_a, b, pose_b).signed_distance)
            << k << " " << part;
      }
    }
  }
}

TEST(CompositeCache, TouchingPairIsRemembered) {
  const Scene s = make_scene();
  PairCache cache;
  const Transform pose_b{Vec3(0, 0, Real(1.1)), Quat(1, 0, 0, 0)};
  ASSERT_TRUE(intersect(s.sphere_mesh, Transform{}, s.box, pose_b, {}, &cache));
  ASSERT_NE(cache.part_a, kNoIndex);
  EXPECT_EQ(cache.part_b, kNoIndex);
  // The remembered triangle itself touches the box.
  const std::array<Vec3, 3> v = s.sphere_mesh.triangle(cache.part_a);
  EXPECT_TRUE(intersect(Triangle::create(v[0], v[1], v[2]).value(), Transform{}, s.box, pose_b));
}

}  // namespace test_composite_cache
}  // namespace proxima
