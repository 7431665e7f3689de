#include "platformer_scene.hpp"

#include <cmath>
#include <string>
#include <vector>

namespace proxima::tool {

namespace {

constexpr Real kDt = Real(1) / Real(60);
constexpr Real kGravity = Real(-9.81);

/// The ground: 1 m tiles from x = 60 down to x = 0 (right to left, so the solid side is
/// below), a slope up from x = 20 to a plateau at 1.5 m from x = 25, a drop back to the
/// ground at x = 40.
std::vector<Vec2> ground_points() {
  std::vector<Vec2> points;
  for (int i = 60; i >= 0; --i) {
    const Real x = static_cast<Real>(i);
    Real y = Real(0);
    if (x >= 20 && x <= 25) y = Real(0.3) * (x - 20);
    if (x > 25 && x < 40) y = Real(1.5);
    points.push_back({x, y});
  }
  return points;
}

/// The player's position correction and velocity change from its manifolds: the deepest
/// point of each manifold pushes it out along the normal, by what earlier pushes have not
/// already done; velocity into a normal is removed.
void resolve_player(const d2::CollisionWorld& world, d2::ObjectHandle player, Vec2& position, Vec2& velocity,
                    PlatformerRun& run) {
  Vec2 push(Real(0));
  for (const d2::WorldManifold& wm : world.manifolds()) {
    const bool is_a = wm.pair.a == player, is_b = wm.pair.b == player;
    if (!is_a && !is_b) continue;
    const Vec2 n = is_b ? wm.manifold.normal : -wm.manifold.normal;  // from the ground to the player
    Real depth = Real(0);
    for (int k = 0; k < wm.manifold.count; ++k) depth = std::max(depth, wm.manifold.points[k].depth);
    ++run.ground_contacts;
    run.catches += n.y < Real(0.7);
    const Real extra = depth - glm::dot(push, n);
    if (extra > Real(0)) push += extra * n;
    const Real into = glm::dot(velocity, n);
    if (into < Real(0)) velocity -= into * n;
  }
  position += push;
}

d2::SpriteMask mask_where(int w, int h, bool (*set)(int, int)) {
  std::vector<std::string> rows;
  for (int y = 0; y < h; ++y) {
    std::string row;
    for (int x = 0; x < w; ++x) row += set(x, y) ? '1' : '0';
    rows.push_back(row);
  }
  return d2::SpriteMask::from_rows(rows).value();
}

/// The ring and the spinning cross, run frame by frame until the pixels meet.
SpriteEncounter run_sprites(int frames) {
  SpriteEncounter e;
  e.ring = mask_where(32, 32, [](int x, int y) {
    const double r = std::hypot(x + 0.5 - 16, y + 0.5 - 16);
    return r <= 15.5 && r >= 11.5;
  });
  e.cross = mask_where(32, 32, [](int x, int y) { return (x >= 13 && x < 19) || (y >= 13 && y < 19); });
  e.start_a = 0;
  e.start_b = 160;
  e.row = 20;
  e.spin_degrees = 7;
  for (int frame = 0; frame < frames && e.pixels_frame < 0; ++frame) {
    const d2::PixelPoint a{e.start_a + frame, e.row};
    const d2::TurnedPlacement b = e.placement_b(frame);
    const d2::PixelRect ra{a.x, a.y, a.x + 32, a.y + 32};
    const bool rectangles = !d2::intersection(ra, d2::turned_bounds(e.cross, b)).is_empty();
    if (rectangles && e.rectangles_frame < 0) e.rectangles_frame = frame;
    const d2::SpriteOverlap o = d2::sprite_overlap(e.ring, a, e.cross, b);
    if (o.overlap) {
      e.pixels_frame = frame;
      e.pixels = o.count;
      e.first_pixel = *o.first;
    }
  }
  return e;
}

}  // namespace

d2::TurnedPlacement SpriteEncounter::placement_b(int frame) const {
  return d2::TurnedPlacement::create({start_b - frame, row}, spin_degrees * frame, 1.0).value();
}

PlatformerRun run_platformer(const PlatformerConfig& config, const PlatformerFrameObserver& observer) {
  PlatformerRun run;
  run.config = config;
  run.ground = ground_points();
  run.wall_bottom = {Real(50), Real(0)};
  run.wall_top = {Real(50), Real(8)};
  run.player_half_extents = {Real(0.4), Real(0.5)};
  d2::CollisionWorld world = d2::CollisionWorld::create().value();
  const auto add = [&](const d2::ObjectDesc& desc) { return world.add(desc).value(); };
  add({d2::Chain::create(run.ground, false).value(), d2::Pose::identity(), d2::ObjectKind::Static});
  // Layers: 1 ground, 2 player, 4 projectiles, 8 wall. The player walks on the ground and
  // through the wall (a doorway); projectiles meet the ground and the wall, not the player.
  d2::ObjectDesc wall{d2::Segment::create(run.wall_bottom, run.wall_top).value(), d2::Pose::identity(),
                      d2::ObjectKind::Static};
  wall.filter = {8, ~0ull, 0};
  add(wall);
  d2::ObjectDesc player_desc{d2::Polygon::box(run.player_half_extents.x, run.player_half_extents.y).value(),
                             d2::Pose::from({Real(2), Real(0.5)}, 0)};
  player_desc.filter = {2, 1, 0};
  const d2::ObjectHandle player = add(player_desc);
  Vec2 position = player_desc.pose.position, velocity(static_cast<Real>(config.walk_speed), 0);
  std::vector<d2::ObjectHandle> shots;
  std::vector<Vec2> shot_velocity;
  const int every = config.projectiles > 0 ? std::max(1, config.frames / (config.projectiles + 1)) : config.frames + 1;
  for (int frame = 0; frame < config.frames; ++frame) {
    if (frame % every == every - 1 && static_cast<int>(shots.size()) < config.projectiles) {
      const Vec2 muzzle(Real(5), Real(2) + Real(0.4) * static_cast<Real>(shots.size() % 10));
      d2::ObjectDesc shot{d2::Circle::create(Real(0.05)).value(), d2::Pose::from(muzzle, 0)};
      shot.ccd = config.projectile_ccd;
      shot.filter = {4, 1 | 8, 0};
      shots.push_back(add(shot));
      shot_velocity.push_back({static_cast<Real>(config.projectile_speed), Real(-2)});
      run.projectiles.push_back({muzzle, muzzle, false, false});
    }
    velocity.x = static_cast<Real>(config.walk_speed);  // the player keeps walking
    velocity.y += kGravity * kDt;
    position += kDt * velocity;
    world.move(player, d2::Pose::from(position, 0));
    for (std::size_t s = 0; s < shots.size(); ++s) {
      if (run.projectiles[s].stopped) continue;
      run.projectiles[s].end += kDt * shot_velocity[s];
      world.move(shots[s], d2::Pose::from(run.projectiles[s].end, 0));
    }
    world.step();
    ++run.steps;
    for (const d2::ImpactEvent& hit : world.events().impacts) {
      for (std::size_t s = 0; s < shots.size(); ++s) {
        if (hit.a != shots[s]) continue;
        ProjectileTrack& track = run.projectiles[s];
        track.end = track.end - (Real(1) - hit.toi) * kDt * shot_velocity[s];
        track.stopped = true;
        world.teleport(shots[s], d2::Pose::from(track.end, 0));
      }
    }
    resolve_player(world, player, position, velocity, run);
    world.teleport(player, d2::Pose::from(position, 0));
    run.player_trail.push_back(d2::Pose::from(position, 0));
    if (observer) observer(frame, world, run);
  }
  for (ProjectileTrack& track : run.projectiles) track.tunnelled = !track.stopped && track.end.x > run.wall_bottom.x;
  run.sprites = run_sprites(config.frames);
  return run;
}

}  // namespace proxima::tool
