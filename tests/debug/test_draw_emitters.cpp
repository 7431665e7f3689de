// The emitters checked against what they draw: BVH boxes at level k are the hierarchy's own
// nodes at depth k (found here by a recursive walk), the dynamic tree's leaves are its fat
// boxes, a manifold gives two markers per point, a sweep places the tessellation where the
// motion says, a ray ends at its hit, a world draws each object in its kind's colour.
#include <gtest/gtest.h>

#include <proxima/broadphase/dynamic_aabb_tree.hpp>
#include <proxima/ccd/time_of_impact.hpp>
#include <proxima/debug/draw_contacts.hpp>
#include <proxima/debug/draw_rays.hpp>
#include <proxima/debug/draw_shapes.hpp>
#include <proxima/debug/draw_sweeps.hpp>
#include <proxima/debug/draw_world.hpp>
#include <proxima/narrowphase/narrowphase.hpp>
#include <proxima/shapes/shape.hpp>

#include <algorithm>
#include <map>
#include <support/solid_test_meshes.hpp>
#include <vector>

namespace proxima::test_draw_emitters {

using namespace proxima::debug;

/// Node boxes by depth, by recursion from the root (independent of the emitter's stack).
void collect(const Bvh& bvh, std::uint32_t index, int depth, std::map<int, std::vector<Aabb>>& out) {
  const BvhNode& node = bvh.nodes()[index];
  out[depth].push_back(node.bounds());
  if (node.is_leaf()) return;
  collect(bvh, node.first, depth + 1, out);
  collect(bvh, node.first + 1, depth + 1, out);
}

bool same_box(const DrawBox& drawn, const Aabb& box, const Transform& pose) {
  return glm::length(drawn.center - pose.apply(box.center())) < Real(1e-4) &&
         glm::length(drawn.half_extents - box.half_extents()) < Real(1e-5) &&
         std::abs(glm::dot(drawn.rotation, pose.rotation)) > Real(1 - 1e-6);
}

TEST(DrawEmitters, BvhBoxesAtEachLevelAreTheNodes) {
  const TriangleMesh mesh = TriangleMesh::create(test::icosphere_mesh(2, Real(1))).value();
  const Transform pose{Vec3(1, 2, 3), glm::normalize(Quat(0.9f, 0.1f, 0.3f, -0.2f))};
  std::map<int, std::vector<Aabb>> expected;
  collect(mesh.bvh(), 0, 0, expected);
  ASSERT_GT(expected.size(), 3u);
  DrawBuffer buffer;
  draw_shape_bvh(buffer, mesh, pose);
  std::size_t total = 0;
  for (const auto& [level, boxes] : expected) {
    total += boxes.size();
    std::vector<DrawBox> drawn;
    for (const DrawBox& b : buffer.boxes) {
      if (b.tag == DrawTag{DrawLayer::Bvh, static_cast<std::uint16_t>(level)}) drawn.push_back(b);
    }
    ASSERT_EQ(drawn.size(), boxes.size()) << "level " << level;
    for (const Aabb& box : boxes) {
      EXPECT_TRUE(std::any_of(drawn.begin(), drawn.end(), [&](const DrawBox& d) { return same_box(d, box, pose); }))
          << "level " << level;
    }
  }
  EXPECT_EQ(buffer.boxes.size(), total);
  DrawBuffer two;
  draw_bvh(two, mesh.bvh(), pose, 2, 2);
  EXPECT_EQ(two.boxes.size(), expected[2].size());
}

TEST(DrawEmitters, DynamicTreeLeavesAreFatBoxes) {
  DynamicAabbTree tree;
  for (ProxyId id = 0; id < 20; ++id) {
    const Vec3 c(Real(id % 5) * 3, Real(id / 5) * 3, 0);
    ASSERT_EQ(tree.insert(id, Aabb{c - Vec3(1), c + Vec3(1)}, id % 3 ? ProxyKind::Moving : ProxyKind::Static),
              BroadPhaseStatus::Ok);
  }
  DrawBuffer buffer;
  draw_broadphase(buffer, tree);
  EXPECT_EQ(buffer.boxes.size(), tree.node_count());
  std::size_t roots = 0;
  for (const DrawBox& b : buffer.boxes) {
    EXPECT_EQ(b.tag.layer, DrawLayer::BroadPhase);
    roots += b.tag.level == 0;
  }
  EXPECT_EQ(roots, 2u);  // one moving tree, one static tree
  for (ProxyId id = 0; id < 20; ++id) {
    const Aabb fat = tree.fat_box(id);
    EXPECT_TRUE(std::any_of(buffer.boxes.begin(), buffer.boxes.end(), [&](const DrawBox& d) {
      return same_box(d, fat, Transform{});
    })) << id;
  }
}

TEST(DrawEmitters, ManifoldGivesTwoMarkersPerPoint) {
  const Box box = Box::create(Vec3(1)).value();
  const Transform a{}, b{Vec3(0, 0, Real(1.9)), kIdentityQuat};
  const ContactManifold manifold = collide(box, a, box, b);
  ASSERT_EQ(manifold.count, 4);
  DrawBuffer buffer;
  draw_manifold(buffer, manifold);
  EXPECT_EQ(buffer.points.size(), 8u);
  EXPECT_EQ(buffer.lines.size(), 8u);
  EXPECT_EQ(buffer.texts.size(), 4u);
  for (int i = 0; i < 4; ++i) {
    const ContactPoint& p = manifold.points[std::size_t(i)];
    EXPECT_EQ(buffer.points[2 * std::size_t(i)].position, p.point_a);
    EXPECT_EQ(buffer.points[2 * std::size_t(i) + 1].position, p.point_b);
    const DrawLine& normal = buffer.lines[2 * std::size_t(i) + 1];
    EXPECT_EQ(normal.tag.layer, DrawLayer::Normals);
    EXPECT_NEAR(glm::length(normal.to - normal.from), 0.25, 1e-6);
    EXPECT_NEAR(glm::dot(glm::normalize(normal.to - normal.from), manifold.normal), 1.0, 1e-5);
    EXPECT_NE(buffer.texts[std::size_t(i)].text.find("depth=0.1"), std::string::npos);
  }
}

TEST(DrawEmitters, SweepPlacesTheShapeAtTheImpactTime) {
  const Sphere ball = Sphere::create(Real(0.5)).value();
  const Box wall = Box::create(Vec3(0.1, 2, 2)).value();
  const Motion motion_a{Transform{Vec3(-3, 0, 0), kIdentityQuat}, Transform{Vec3(3, 0, 0), kIdentityQuat}};
  const Motion motion_b = Motion::stationary(Transform{});
  const ToiResult toi = time_of_impact(ball, motion_a, wall, motion_b).value();
  ASSERT_EQ(toi.status, CcdStatus::Hit);
  EXPECT_NEAR(toi.toi, (3 - 0.6) / 6, 1e-3);
  DrawBuffer buffer;
  draw_time_of_impact(buffer, ball, motion_a, wall, motion_b, toi);
  const std::size_t n_ball = tessellate(ball).triangle_count(), n_wall = tessellate(wall).triangle_count();
  ASSERT_EQ(buffer.triangles.size(), 3 * n_ball + 3 * n_wall);
  // The ball's copy at the impact time: the second of its three, centred on the motion's pose.
  Vec3 centre(0);
  for (std::size_t i = n_ball; i < 2 * n_ball; ++i) centre += (buffer.triangles[i].a) / Real(n_ball);
  EXPECT_NEAR(centre.x, -3 + 6 * toi.toi, 0.05);
  EXPECT_EQ(buffer.points.size(), 1u);
  EXPECT_NEAR(buffer.points[0].position.x, -0.1, 1e-3);
  // Two paths of 16 lines and the normal; the first path runs from t = 0 to t = 1.
  ASSERT_EQ(buffer.lines.size(), 2 * 16u + 1u);
  EXPECT_EQ(buffer.lines[0].from, motion_a.at(0).position);
  EXPECT_EQ(buffer.lines[15].to, motion_a.at(1).position);
}

TEST(DrawEmitters, RayEndsAtItsHit) {
  const Sphere ball = Sphere::create(Real(1)).value();
  const Ray ray{Vec3(-5, 0, 0), Vec3(1, 0, 0)};
  DrawBuffer hit_buffer;
  draw_ray(hit_buffer, ray, Real(100), ball.raycast(ray, Real(100)));
  ASSERT_EQ(hit_buffer.lines.size(), 2u);
  EXPECT_NEAR(hit_buffer.lines[0].to.x, -1, 1e-5);
  ASSERT_EQ(hit_buffer.points.size(), 1u);
  EXPECT_NEAR(hit_buffer.lines[1].to.x, -1.25, 1e-5);  // the normal, outward
  DrawBuffer miss_buffer;
  draw_ray(miss_buffer, Ray{Vec3(-5, 3, 0), Vec3(2, 0, 0)}, Real(4), std::nullopt);
  ASSERT_EQ(miss_buffer.lines.size(), 1u);
  EXPECT_EQ(miss_buffer.lines[0].to, Vec3(3, 3, 0));
  EXPECT_TRUE(miss_buffer.points.empty());
}

TEST(DrawEmitters, WorldObjectsInTheirKindsColours) {
  CollisionWorld world = CollisionWorld::create().value();
  ObjectDesc ground;
  ground.geometry = Box::create(Vec3(5, 5, 0.5)).value();
  ground.kind = ObjectKind::Static;
  ObjectDesc ball;
  ball.geometry = Sphere::create(Real(0.5)).value();
  ball.pose.position = Vec3(0, 0, 0.9f);
  ObjectDesc sensor;
  sensor.geometry = Box::create(Vec3(1)).value();
  sensor.pose.position = Vec3(4, 0, 2);
  sensor.sensor = true;
  ASSERT_TRUE(world.add(ground).ok());
  ASSERT_TRUE(world.add(ball).ok());
  ASSERT_TRUE(world.add(sensor).ok());
  ASSERT_FALSE(world.step(Real(1.0 / 60)));
  ASSERT_EQ(world.contacts().size(), 1u);
  DrawBuffer buffer;
  WorldDrawOptions options;
  options.bounds = true;
  draw_world(buffer, world, options);
  const std::size_t n_box = 12, n_ball = tessellate(*Sphere::create(Real(0.5))).triangle_count();
  ASSERT_EQ(buffer.triangles.size(), n_box + n_ball + n_box);
  EXPECT_EQ(buffer.triangles[0].color, object_color(ground));
  EXPECT_EQ(buffer.triangles[n_box].color, object_color(ball));
  EXPECT_EQ(buffer.triangles.back().color, object_color(sensor));
  EXPECT_NE(object_color(ground), object_color(ball));
  EXPECT_EQ(object_color(sensor).a, 96);
  ObjectDesc other_layer = ball;
  other_layer.filter.layer = 4;
  EXPECT_NE(object_color(other_layer), object_color(ball));
  EXPECT_EQ(buffer.boxes.size(), 3u);
  EXPECT_EQ(buffer.points.size(), 2 * std::size_t(world.contacts()[0].count));
}

}  // namespace proxima::test_draw_emitters
