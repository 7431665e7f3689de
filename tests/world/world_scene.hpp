#pragma once
// Random collision worlds for the world tests: a seeded mix of spheres, capsules, boxes,
// hulls and compounds moving in a cube over a static mesh floor and a static half-space,
// and the brute-force reference of a step (every pair of live objects through the narrow
// phase, no broad phase, no cache).
#include <gtest/gtest.h>

#include <proxima/narrowphase/narrowphase.hpp>
#include <proxima/world/collision_world.hpp>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>
#include <support/random.hpp>
#include <vector>

namespace proxima::test {

/// Half the edge of the random scenes' cube.
inline constexpr Real kExtent = Real(6);

/// The placement at (x, y, z), unrotated.
inline Transform at(Real x, Real y = 0, Real z = 0) { return Transform{Vec3(x, y, z), kIdentityQuat}; }

/// A moving sphere of radius `r` at `pose`.
inline ObjectDesc ball(const Transform& pose, Real r = Real(0.5)) {
  ObjectDesc d;
  d.geometry = *Sphere::create(r);
  d.pose = pose;
  return d;
}

/// A new world with `settings` (which must be valid).
inline CollisionWorld make_world(const WorldSettings& settings = {}) {
  return std::move(CollisionWorld::create(settings)).value();
}

/// A random convex or compound geometry of size about `size`.
inline Shape random_geometry(Random& rng, Real size) {
  const int kind = rng.integer(0, 4);
  if (kind == 0) return *Sphere::create(rng.uniform(Real(0.3), Real(1)) * size);
  // Each draw in a statement of its own, in the order GCC evaluated the call arguments they
  // replace (right to left), so that a seed names the same scene with every compiler.
  if (kind == 1) {
    const Real half_length = rng.uniform(Real(0.2), Real(0.8)) * size;
    const Real radius = rng.uniform(Real(0.2), Real(0.5)) * size;
    return *Capsule::create(radius, half_length);
  }
  if (kind == 2) {
    const Real z = rng.uniform(Real(0.2), Real(0.8)) * size;
    const Real y = rng.uniform(Real(0.2), Real(0.8)) * size;
    const Real x = rng.uniform(Real(0.2), Real(0.8)) * size;
    return *Box::create(Vec3(x, y, z));
  }
  if (kind == 3) {
    std::vector<Vec3> points;
    for (int k = 0; k < 12; ++k) points.push_back(rng.in_ball(size));
    auto hull = ConvexHull::create(points);
    if (hull) return *hull;
    return *Sphere::create(size * Real(0.5));
  }
  std::vector<CompoundChild> children;
  children.push_back({*Sphere::create(Real(0.4) * size), Transform{Vec3(Real(0.5) * size, 0, 0), kIdentityQuat}});
  children.push_back({*Box::create(Vec3(Real(0.3) * size)), Transform{Vec3(-Real(0.5) * size, 0, 0), rng.rotation()}});
  return *Compound::create(std::move(children));
}

/// A bumpy open mesh floor over [-extent, extent]^2 near z = 0 (n x n cells).
inline TriangleMesh floor_mesh(Real extent, int n) {
  IndexedMesh m;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const Real x = -extent + Real(2) * extent * Real(i) / Real(n);
      const Real y = -extent + Real(2) * extent * Real(j) / Real(n);
      m.vertices.push_back(Vec3(x, y, Real(0.3) * std::sin(x) * std::cos(y)));
    }
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const std::uint32_t a = std::uint32_t(j * (n + 1) + i), b = a + 1, c = a + std::uint32_t(n) + 2,
                          d = a + std::uint32_t(n) + 1;
      m.triangles.push_back({a, b, c});
      m.triangles.push_back({a, c, d});
    }
  return *TriangleMesh::create(std::move(m));
}

/// One moving object of a random scene: its handle and velocities.
struct Mover {
  ObjectHandle handle;
  Vec3 velocity{Real(0)};
  Vec3 angular{Real(0)};
};

/// A random scene in `world`: `count` moving objects in [-extent, extent]^3 with random
/// velocities, a static mesh floor at z = -extent and a static half-space below it.
inline std::vector<Mover> populate(CollisionWorld& world, Random& rng, int count, Real extent) {
  ObjectDesc floor;
  floor.geometry = floor_mesh(extent, 8);
  floor.kind = ObjectKind::Static;
  floor.pose = Transform{Vec3(0, 0, -extent), kIdentityQuat};
  EXPECT_TRUE(world.add(floor).ok());
  ObjectDesc ground;
  ground.geometry = *HalfSpace::create(Vec3(0, 0, 1), -extent - Real(0.5));
  ground.kind = ObjectKind::Static;
  EXPECT_TRUE(world.add(ground).ok());
  std::vector<Mover> movers;
  for (int k = 0; k < count; ++k) {
    ObjectDesc d;
    d.geometry = random_geometry(rng, Real(1));
    d.pose = Transform{rng.vec3(-extent, extent), rng.rotation()};
    d.user_data = std::uint64_t(k);
    auto h = world.add(d);
    EXPECT_TRUE(h.ok());
    movers.push_back({*h, rng.vec3(Real(-0.3), Real(0.3)), rng.vec3(Real(-0.2), Real(0.2))});
  }
  return movers;
}

/// Moves every mover by one step of its velocities (folded back into the cube).
inline void advance(CollisionWorld& world, std::vector<Mover>& movers, Real extent) {
  for (Mover& m : movers) {
    Transform p = world.pose(m.handle);
    p.position += m.velocity;
    for (int a = 0; a < 3; ++a)
      if (std::abs(p.position[a]) > extent) m.velocity[a] = -m.velocity[a];
    p.rotation = glm::normalize(
        glm::angleAxis(glm::length(m.angular), glm::length(m.angular) > 0 ? glm::normalize(m.angular) : Vec3(0, 0, 1)) *
        p.rotation);
    ASSERT_FALSE(world.move(m.handle, p).has_value());
  }
}

/// The reference pair set: every pair of live objects (not both static, filters allowing)
/// whose geometries the narrow phase's intersect says touch within `contact_distance`.
inline std::vector<ObjectPair> brute_force_pairs(const CollisionWorld& world, Real contact_distance) {
  std::vector<ObjectPair> out;
  const std::vector<ObjectHandle> all = world.objects();
  PairRequest request;
  request.contact_distance = contact_distance;
  for (std::size_t i = 0; i < all.size(); ++i) {
    const ObjectDesc a = *world.object(all[i]);
    for (std::size_t j = i + 1; j < all.size(); ++j) {
      const ObjectDesc b = *world.object(all[j]);
      if (a.kind == ObjectKind::Static && b.kind == ObjectKind::Static) continue;
      if (!can_collide(a.filter, b.filter)) continue;
      if (intersect(a.geometry, a.pose, b.geometry, b.pose, request)) out.push_back({all[i], all[j]});
    }
  }
  return out;
}

/// The touching pairs of the world after its last step.
inline std::vector<ObjectPair> world_pairs(const CollisionWorld& world) {
  std::vector<ObjectPair> out;
  for (const WorldManifold& m : world.contacts()) out.push_back(m.pair);
  return out;
}

/// The pairs of a contact event array.
inline std::vector<ObjectPair> pairs_of(const std::vector<ContactEvent>& events) {
  std::vector<ObjectPair> out;
  for (const ContactEvent& e : events) out.push_back(e.pair);
  return out;
}

/// Sorted set difference a \ b.
inline std::vector<ObjectPair> minus(const std::vector<ObjectPair>& a, const std::vector<ObjectPair>& b) {
  std::vector<ObjectPair> out;
  std::set_difference(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(out));
  return out;
}

/// Text of a pair list ("(3,17) (5,9)") for failure messages.
inline std::string pair_text(const std::vector<ObjectPair>& pairs) {
  std::ostringstream out;
  for (const ObjectPair& p : pairs) out << '(' << p.a.index << ',' << p.b.index << ") ";
  return out.str();
}

/// A single-thread executor that runs every item as a call of its own, last item first: a
/// split and an order no thread pool gives, for the tests that the answer depends on neither.
class ReverseExecutor final : public Executor {
 public:
  /// Always 1.
  std::size_t concurrency() const override { return 1; }
  /// task(i, i + 1) for i = count - 1 down to 0.
  void run(std::size_t count, RangeTask task) override {
    for (std::size_t i = count; i > 0; --i) task(i - 1, i);
  }
};

/// Sorted set intersection.
inline std::vector<ObjectPair> common(const std::vector<ObjectPair>& a, const std::vector<ObjectPair>& b) {
  std::vector<ObjectPair> out;
  std::set_intersection(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(out));
  return out;
}

}  // namespace proxima::test
