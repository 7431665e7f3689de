// The platformer demo on the 2D world: the player crosses every tile seam without a contact
// normal that pushes it back or sideways, continuous detection stops every projectile at the
// wall's line (checked against the wall's analytic position), the discrete run lets them
// through, and the pictures are written: the PNG drawn by `proxima render`'s renderer from
// the 2D world's draw stream shows, through the demo's known camera (20 pixels per metre,
// the view centred on (30, 4)), the player's colour where the run puts the player, the
// background below the ground and a stopped projectile's green track.
#include <gtest/gtest.h>

#include <filesystem>
#include <memory>
#include <png.h>
#include <sstream>
#include <vector>

#include "capture_render.hpp"
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
  options.png_path = "";
  std::ostringstream out, err;
  ASSERT_EQ(run_platformer_demo(options, out, err), 0) << err.str();
  EXPECT_NE(out.str().find("12 of 12 projectiles stopped"), std::string::npos) << out.str();
  EXPECT_GT(std::filesystem::file_size(svg), 1000u);
  std::filesystem::remove(svg);
}

/// An RGBA picture read back with libpng.
struct PlatformerPicture {
  int width = 0;
  int height = 0;
  std::vector<unsigned char> rgba;
  /// The pixel under world point (x, y) through the demo's camera.
  Rgba at_world(double x, double y) const {
    const int px = static_cast<int>(620 + 20 * (x - 30)), py = static_cast<int>(110 - 20 * (y - 4));
    const std::size_t i = 4 * (static_cast<std::size_t>(py) * static_cast<std::size_t>(width) + std::size_t(px));
    return Rgba{rgba[i], rgba[i + 1], rgba[i + 2], rgba[i + 3]};
  }
};

PlatformerPicture read_platformer_png(const std::string& path) {
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  PlatformerPicture picture;
  if (png_image_begin_read_from_file(&image, path.c_str()) == 0) return picture;
  const std::unique_ptr<png_image, void (*)(png_imagep)> guard(&image, png_image_free);
  image.format = PNG_FORMAT_RGBA;
  picture.rgba.resize(PNG_IMAGE_SIZE(image));
  if (png_image_finish_read(&image, nullptr, picture.rgba.data(), 0, nullptr) == 0) return picture;
  picture.width = static_cast<int>(image.width);
  picture.height = static_cast<int>(image.height);
  return picture;
}

TEST(DemoPlatformer, PngShowsTheWorldFromAbove) {
  const std::filesystem::path png = std::filesystem::temp_directory_path() / "proxima-test-platformer.png";
  std::filesystem::remove(png);
  PlatformerDemoOptions options;
  options.svg_path = "";
  options.png_path = png.string();
  options.png_frame = 200;
  options.quiet = true;
  std::ostringstream out, err;
  ASSERT_EQ(run_platformer_demo(options, out, err), 0) << err.str();
  EXPECT_TRUE(out.str().empty());
  const PlatformerPicture picture = read_platformer_png(png.string());
  ASSERT_EQ(picture.width, 1240);
  ASSERT_EQ(picture.height, 220);
  const PlatformerRun run = run_platformer(PlatformerConfig{});
  const Vec2 player = run.player_trail[200].position;
  const Rgba moving_layer_2{230, 150, 50, 255};  // debug::object_color of a moving object on layer 2
  // Inside the player's top fan triangle (off the diagonals, where two triangles' edges
  // blend), clear of its outline and of the contact markers at its bottom.
  EXPECT_EQ(picture.at_world(player.x - 0.1, player.y + 0.3), moving_layer_2);
  const Rgba background = RenderOptions{}.background;
  EXPECT_EQ(picture.at_world(10, -0.5), background);
  // The first projectile's track, stopped at the wall: green (60, 200, 90) near its middle.
  const ProjectileTrack& first = run.projectiles[0];
  ASSERT_TRUE(first.stopped);
  const double mx = (first.start.x + first.end.x) / 2, my = (first.start.y + first.end.y) / 2;
  bool green = false;
  for (int dy = -1; dy <= 1; ++dy) {
    const Rgba c = picture.at_world(mx, my + dy * 0.05);
    green = green || (c.g > c.r + 30 && c.g > c.b + 30);  // partly covered: blended
  }
  EXPECT_TRUE(green);
  std::filesystem::remove(png);
}

}  // namespace
}  // namespace proxima::tool
