/// @file test_sprite_chains.cpp
/// A sprite in the rigid world: its outline chains enclose the set pixels (point tests against
/// the mask), collide from outside (and from inside a hole), stop rays at the pixels' edges,
/// and work as a static object of the 2D world.

#include <gtest/gtest.h>

#include <proxima/d2/collision_world.hpp>
#include <proxima/d2/narrowphase.hpp>
#include <proxima/d2/sprite_chains.hpp>

#include <string>
#include <vector>

namespace proxima::d2 {
namespace {

SpriteMask ring_mask() {
  // A 12 x 12 square ring, 3 pixels thick, hole 6 x 6.
  std::vector<std::string> rows;
  for (int y = 0; y < 12; ++y) {
    std::string row;
    for (int x = 0; x < 12; ++x) row += (x >= 3 && x < 9 && y >= 3 && y < 9) ? '0' : '1';
    rows.push_back(row);
  }
  return SpriteMask::from_rows(rows).value();
}

/// Winding number of point q about a closed chain (non-zero inside).
int winding(const Chain& chain, const Vec2& q) {
  int w = 0;
  const auto& p = chain.points();
  for (std::size_t i = 0; i < p.size(); ++i) {
    const Vec2 a = p[i] - q, b = p[(i + 1) % p.size()] - q;
    if (a.y <= 0 && b.y > 0 && cross(a, b) > 0) ++w;
    if (a.y > 0 && b.y <= 0 && cross(a, b) < 0) --w;
  }
  return w;
}

TEST(SpriteChains, TheChainsEncloseExactlyTheSetPixels) {
  const SpriteMask mask = ring_mask();
  const std::vector<Chain> chains = sprite_chains(mask, 0, Real(0.5)).value();
  ASSERT_EQ(chains.size(), 2u);  // the outer boundary and the hole
  for (int y = 0; y < 12; ++y) {
    for (int x = 0; x < 12; ++x) {
      // Pixel (x, y)'s centre in the body frame: centred, y up, half a unit per pixel.
      const Vec2 c((static_cast<Real>(x) + Real(0.5) - 6) * Real(0.5),
                   (6 - static_cast<Real>(y) - Real(0.5)) * Real(0.5));
      int w = 0;
      for (const Chain& chain : chains) w += winding(chain, c);
      EXPECT_EQ(w != 0, mask.get(x, y)) << x << "," << y;
    }
  }
}

TEST(SpriteChains, CollideFromOutsideAndFromInsideTheHole) {
  const std::vector<Chain> chains = sprite_chains(ring_mask(), 0, Real(1)).value();
  const Shape ball = Circle::create(Real(0.5)).value();
  int outside = 0, inside = 0;
  for (const Chain& chain : chains) {
    const Shape shape = chain;
    // A ball resting 0.1 deep on the sprite's top edge (y = 6): normal up.
    const Manifold top = collide(shape, Pose::identity(), ball, Pose::from({0, Real(6.4)}, 0));
    if (top.count > 0) {
      EXPECT_NEAR(top.normal.y, Real(1), Real(1e-5));
      EXPECT_NEAR(top.points[0].depth, Real(0.1), Real(1e-5));
      ++outside;
    }
    // A ball in the hole touching its floor (y = -3 from inside): normal up as well.
    const Manifold hole = collide(shape, Pose::identity(), ball, Pose::from({0, Real(-2.6)}, 0));
    if (hole.count > 0) {
      EXPECT_NEAR(hole.normal.y, Real(1), Real(1e-5));
      ++inside;
    }
  }
  EXPECT_EQ(outside, 1);
  EXPECT_EQ(inside, 1);
}

TEST(SpriteChains, ASpriteIsAStaticObjectOfTheWorld) {
  CollisionWorld world = CollisionWorld::create().value();
  const std::vector<Chain> chains = sprite_chains(ring_mask(), 0.5, Real(1)).value();
  for (const Chain& chain : chains) {
    ASSERT_TRUE(world.add({chain, Pose::from({Real(10), 0}, Real(0.3)), ObjectKind::Static}).ok());
  }
  // A ray from the far left along the sprite's centre line stops at its outer left edge.
  const auto hit = world.raycast({{Real(-20), 0}, {Real(1), 0}}, Real(100));
  ASSERT_TRUE(hit.has_value());
  const Pose pose = Pose::from({Real(10), 0}, Real(0.3));
  const Vec2 local = pose.inverse_apply(hit->hit.point);
  EXPECT_NEAR(local.x, Real(-6), Real(0.51));  // the left edge, within the simplification
  const ObjectHandle ball = world
                                .add({Circle::create(Real(0.4)).value(),
                                      Pose::from({Real(-20), 0}, 0),
                                      ObjectKind::Moving,
                                      {},
                                      false,
                                      CcdMode::Bullet})
                                .value();
  world.step();
  world.move(ball, Pose::from({Real(30), 0}, 0));  // through the whole sprite in one step
  world.step();
  ASSERT_EQ(world.events().impacts.size(), 1u);
  EXPECT_LT(world.events().impacts[0].toi, Real(0.5));
}

TEST(SpriteChains, BadInputNamesTheField) {
  EXPECT_EQ(sprite_chains(ring_mask(), 0, Real(0)).error().field, "pixel_size");
  EXPECT_TRUE(sprite_chains(SpriteMask::create(4, 4).value(), 0, Real(1)).value().empty());
}

}  // namespace
}  // namespace proxima::d2
