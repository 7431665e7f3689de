#pragma once
// The 2D platformer scene of `proxima demo-platformer`, run on d2::CollisionWorld: a tiled
// ground (a chain of 1 m tiles with a slope and a ledge), a thin wall, a box-shaped player
// that walks right under gravity and is kept out of the ground by the world's manifolds, and
// fast projectiles fired at the wall that the world's continuous detection stops. The same
// scene runs with continuous detection off to show what it prevents.
#include <proxima/d2/collision_world.hpp>
#include <proxima/d2/sprite_mask.hpp>
#include <proxima/d2/sprite_overlap.hpp>
#include <proxima/debug/draw_world_2d.hpp>

#include <functional>
#include <span>
#include <vector>

namespace proxima::tool {

/// Settings of the platformer run.
struct PlatformerConfig {
  int frames = 480;                                  ///< frames at 60 Hz
  int projectiles = 12;                              ///< projectiles fired, spread over the run
  double projectile_speed = 300;                     ///< m/s
  double walk_speed = 6;                             ///< the player's walking speed, m/s
  d2::CcdMode projectile_ccd = d2::CcdMode::Bullet;  ///< Off shows the tunnelling
};

/// A projectile's flight: where it was fired, where it ended, and whether the world stopped it.
struct ProjectileTrack {
  Vec2 start{Real(0)};     ///< muzzle, world frame
  Vec2 end{Real(0)};       ///< its last position (the impact when stopped)
  bool stopped = false;    ///< held at its time of impact on the wall
  bool tunnelled = false;  ///< passed the wall's line without being stopped
};

/// Two sprites flying at each other in screen pixels (y down): a ring moving right and a
/// spinning cross moving left, 1 pixel per frame each; their overlap is pixel-perfect (the
/// cross turned by W9's rule), their bounding rectangles meet earlier.
struct SpriteEncounter {
  d2::SpriteMask ring = d2::SpriteMask::create(1, 1).value();   ///< sprite A (32 x 32 ring)
  d2::SpriteMask cross = d2::SpriteMask::create(1, 1).value();  ///< sprite B (32 x 32 cross, turned)
  int start_a = 0;                                              ///< A's x at frame 0 (pixels); A is at start_a + frame
  int start_b = 0;                                              ///< B's x at frame 0; B is at start_b - frame
  int row = 0;                                                  ///< both sprites' y (pixels)
  double spin_degrees = 0;                                      ///< B's turn per frame (clockwise on screen)
  int rectangles_frame = -1;                                    ///< first frame whose bounding rectangles overlap
  int pixels_frame = -1;                                        ///< first frame with a common set pixel
  std::uint64_t pixels = 0;                                     ///< common pixels at that frame
  d2::PixelPoint first_pixel{};                                 ///< the first common pixel (smallest y, then x)
  /// B's placement at a frame.
  d2::TurnedPlacement placement_b(int frame) const;
};

/// What the run did.
struct PlatformerRun {
  PlatformerConfig config;
  std::vector<Vec2> ground;   ///< the ground chain's points
  Vec2 wall_bottom{Real(0)};  ///< the wall's segment
  Vec2 wall_top{Real(0)};
  std::vector<d2::Pose> player_trail;  ///< the player's pose every frame
  Vec2 player_half_extents{Real(0)};
  std::vector<ProjectileTrack> projectiles;
  int ground_contacts = 0;  ///< player–ground manifolds over the run
  int catches = 0;          ///< of them, normals that push the player backwards or sideways (normal.y < 0.7)
  int steps = 0;            ///< world steps
  SpriteEncounter sprites;  ///< the pixel-perfect sprite pair
};

/// Called after each frame's step and collision response: the frame (0, 1, ...), the world
/// (the ground, the wall, the player, the projectiles added so far) and the run so far (the
/// player's trail and the projectiles' tracks up to this frame).
using PlatformerFrameObserver =
    std::function<void(int frame, const d2::CollisionWorld& world, const PlatformerRun& run)>;

/// Runs the scene, calling `observer` (when set) after every frame.
PlatformerRun run_platformer(const PlatformerConfig& config, const PlatformerFrameObserver& observer = {});

}  // namespace proxima::tool
