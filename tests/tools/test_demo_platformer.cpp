// The platformer demo on the 2D world: the player crosses every tile seam without a contact
// normal that pushes it back or sideways, continuous detection stops every projectile at the
// wall's line (checked against the wall's analytic position), the discrete run lets them
// through, and the picture is written.
#include <gtest/gtest.h>

#include <filesystem>
#include <sstream>

#include "d2/sprite_reference.hpp"
#include "demo_platformer.hpp"

namespace proxima::tool {
namespace {

TEST(DemoPlatformer, ContinuousDetectionStopsEveryProjectileAndTheGroundNeverCatches) {
  PlatformerConfig config;
  const PlatformerRun run = run_platformer(config);
  EXPECT_EQ(run.steps, config.frames);
  EXPECT_EQ(run.catches, 0);
  EXPECT_GT(run.ground_contacts, config.frames);
  // The player walked past the plateau and the drop, and stands on the ground (within the
  // step's gravity sink) at the end.
  const d2::Pose last = run.player_trail.back();
  EXPECT_GT(last.position.x, Real(45));
  EXPECT_NEAR(last.position.y, run.player_half_extents.y, Real(0.01));
  ASSERT_EQ(static_cast<int>(run.projectiles.size()), config.projectiles);
  for (const ProjectileTrack& t : run.projectiles) {
    EXPECT_TRUE(t.stopped);
    EXPECT_FALSE(t.tunnelled);
    // Held where its surface touches the wall's line: centre 0.05 before x = 50.
    EXPECT_NEAR(t.end.x, run.wall_bottom.x - Real(0.05), Real(2e-3));
  }
}

TEST(DemoPlatformer, TheSpritesMeetAtTheFirstFrameWithACommonPixel) {
  const SpriteEncounter e = run_platformer(PlatformerConfig{}).sprites;
  ASSERT_GT(e.pixels_frame, 0);
  EXPECT_LE(e.rectangles_frame, e.pixels_frame);
  // W9's rule written literally (tests/d2/sprite_reference.hpp): no common pixel the frame
  // before, the same count and first pixel at the frame.
  const auto at = [&](int frame) {
    return test::reference_turned(e.ring, {e.start_a + frame, e.row}, e.cross, {e.start_b - frame, e.row},
                                  e.spin_degrees * frame, 1.0);
  };
  EXPECT_EQ(at(e.pixels_frame - 1).count, 0u);
  const d2::SpriteOverlap hit = at(e.pixels_frame);
  EXPECT_EQ(hit.count, e.pixels);
  ASSERT_TRUE(hit.first.has_value());
  EXPECT_EQ(hit.first->x, e.first_pixel.x);
  EXPECT_EQ(hit.first->y, e.first_pixel.y);
}

TEST(DemoPlatformer, WithoutContinuousDetectionTheProjectilesTunnel) {
  PlatformerConfig config;
  config.projectile_ccd = d2::CcdMode::Off;
  const PlatformerRun run = run_platformer(config);
  for (const ProjectileTrack& t : run.projectiles) EXPECT_TRUE(t.tunnelled);
}

TEST(DemoPlatformer, WritesItsPicture) {
  const std::filesystem::path svg = std::filesystem::temp_directory_path() / "proxima-test-platformer.svg";
  PlatformerDemoOptions options;
  options.svg_path = svg.string();
  std::ostringstream out, err;
  ASSERT_EQ(run_platformer_demo(options, out, err), 0) << err.str();
  EXPECT_NE(out.str().find("12 of 12 projectiles stopped"), std::string::npos) << out.str();
  EXPECT_GT(std::filesystem::file_size(svg), 1000u);
  std::filesystem::remove(svg);
}

}  // namespace
}  // namespace proxima::tool
