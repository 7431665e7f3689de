// `proxima render` on a known capture: a moving box resting on a static box, seen from
// above by the capture's own orthographic camera, so that where everything lands is known
// here without the renderer (pixel = centre + world xy * pixels per unit). The box's colour
// appears inside its outline, the ground's grey between the two outlines, the background
// outside, the contact markers' red at the contact points' pixels; the SVG holds a path per
// visible face; the CLI writes a PNG of the asked size and names a bad frame or file.
#include <gtest/gtest.h>

#include <proxima/debug/capture_recorder.hpp>
#include <proxima/debug/draw_world.hpp>

#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

#include "capture_render.hpp"
#include "cli_run.hpp"

namespace proxima::test_render {

constexpr int kSize = 200;
constexpr double kPixelsPerUnit = kSize / 5.0;  // ortho_height 5

/// The capture: ground box [-2, 2]^2 x [-0.5, 0.5], box [-0.5, 0.5]^2 around z = 0.95.
std::string capture_text() {
  CollisionWorld world = CollisionWorld::create().value();
  ObjectDesc ground;
  ground.geometry = Box::create(Vec3(2, 2, 0.5)).value();
  ground.kind = ObjectKind::Static;
  ObjectDesc box;
  box.geometry = Box::create(Vec3(0.5)).value();
  box.pose.position = Vec3(0, 0, 0.95f);
  EXPECT_TRUE(world.add(ground).ok());
  EXPECT_TRUE(world.add(box).ok());
  EXPECT_FALSE(world.step(Real(0.02)));
  std::ostringstream out;
  debug::CaptureOptions options;
  options.camera = debug::CaptureCamera{Vec3(0, 0, 10), Vec3(0), Vec3(0, 1, 0), Real(0), Real(5)};
  debug::CaptureRecorder recorder(out, options);
  EXPECT_FALSE(recorder.record_step(world, Real(0.02)));
  return out.str();
}

tool::Capture capture() {
  std::istringstream in(capture_text());
  return tool::read_capture(in).value();
}

int px(double x) { return static_cast<int>(kSize / 2.0 + x * kPixelsPerUnit); }
int py(double y) { return static_cast<int>(kSize / 2.0 - y * kPixelsPerUnit); }

bool bluish(Rgba c) { return c.b > c.r + 60 && c.b > c.g + 30; }
bool greyish(Rgba c) { return std::abs(c.r - c.g) < 8 && std::abs(c.g - c.b) < 8 && c.r > 80; }
bool red(Rgba c) { return c.r > 200 && c.g < 90 && c.b < 90; }

TEST(Render, ObjectsLandWhereTheCameraPutsThem) {
  tool::RenderOptions options;
  options.width = options.height = kSize;
  const Result<tool::Image> image = tool::render_image(capture(), 0, options);
  ASSERT_TRUE(image.ok()) << image.error().what();
  const tool::Image& im = image.value();
  ASSERT_EQ(im.width, kSize);
  // The moving box's colour inside its outline (away from the contact markers).
  EXPECT_TRUE(bluish(im.at(px(0.2), py(-0.1)))) << int(im.at(px(0.2), py(-0.1)).b);
  EXPECT_TRUE(bluish(im.at(px(-0.3), py(0.25))));
  // The ground's grey between the outlines, the background outside them.
  EXPECT_TRUE(greyish(im.at(px(1.5), py(1.5))));
  EXPECT_TRUE(greyish(im.at(px(-1.2), py(-0.4))));
  EXPECT_EQ(im.at(px(2.3), py(2.3)), options.background);
  EXPECT_EQ(im.at(3, 3), options.background);
  // A contact marker at each corner of the box's bottom face.
  for (const double sx : {-0.5, 0.5}) {
    for (const double sy : {-0.5, 0.5}) {
      bool found = false;
      for (int dy = -2; dy <= 2; ++dy) {
        for (int dx = -2; dx <= 2; ++dx) found = found || red(im.at(px(sx) + dx, py(sy) + dy));
      }
      EXPECT_TRUE(found) << sx << " " << sy;
    }
  }
  // Without the contacts layer no marker is drawn.
  options.layers = {"shapes"};
  const tool::Image shapes_only = tool::render_image(capture(), 0, options).value();
  for (const Rgba& c : shapes_only.pixels) ASSERT_FALSE(red(c));
}

TEST(Render, DefaultCameraCentresTheScene) {
  tool::RenderOptions options;
  options.width = 160;
  options.height = 120;
  options.capture_camera = false;
  const tool::Image im = tool::render_image(capture(), 0, options).value();
  EXPECT_FALSE(im.at(80, 60) == options.background);
  EXPECT_EQ(im.at(1, 1), options.background);
  EXPECT_EQ(im.at(158, 118), options.background);
  EXPECT_FALSE(tool::render_image(capture(), 1, options).ok());
}

TEST(Render, SvgHoldsTheFaces) {
  const std::string path = testing::TempDir() + "render_test.svg";
  tool::RenderOptions options;
  options.width = options.height = kSize;
  options.layers = {"shapes"};
  ASSERT_FALSE(tool::render_file(capture(), 0, options, path));
  std::ifstream in(path);
  const std::string svg((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(svg.rfind("<?xml", 0), 0u);
  EXPECT_NE(svg.find("<svg"), std::string::npos);
  EXPECT_NE(svg.find("</svg>"), std::string::npos);
  std::size_t paths = 0;
  for (std::size_t at = svg.find("<path"); at != std::string::npos; at = svg.find("<path", at + 1)) ++paths;
  // Seen from above: the two top faces, two triangles each, plus the background.
  EXPECT_GE(paths, 4u);
  const auto wrong = tool::render_file(capture(), 0, options, testing::TempDir() + "x.jpg");
  ASSERT_TRUE(wrong.has_value());
  EXPECT_EQ(wrong->field, "output");
}

TEST(Render, CliWritesAPngOfTheAskedSize) {
  const std::string dir = testing::TempDir();
  std::ofstream(dir + "render_cli.jsonl") << capture_text();
  const test::CliRun run = test::run_cli("render '" + dir + "render_cli.jsonl' --frame 0 --width 120 --height 90 -o '" +
                                         dir + "render_cli.png'");
  ASSERT_EQ(run.status, 0);
  std::ifstream png(dir + "render_cli.png", std::ios::binary);
  std::string head(24, '\0');
  png.read(head.data(), 24);
  ASSERT_EQ(head.substr(1, 3), "PNG");
  const auto be32 = [&](std::size_t at) {
    return (std::uint32_t(std::uint8_t(head[at])) << 24) | (std::uint32_t(std::uint8_t(head[at + 1])) << 16) |
           (std::uint32_t(std::uint8_t(head[at + 2])) << 8) | std::uint32_t(std::uint8_t(head[at + 3]));
  };
  EXPECT_EQ(be32(16), 120u);  // IHDR width, then height
  EXPECT_EQ(be32(20), 90u);
  const test::CliRun bad_frame =
      test::run_cli("render '" + dir + "render_cli.jsonl' --frame 3 -o '" + dir + "x.png' 2>&1");
  EXPECT_EQ(bad_frame.status, 1);
  EXPECT_NE(bad_frame.output.find("frame"), std::string::npos);
  std::ofstream(dir + "render_bad.jsonl") << capture_text().substr(0, 200);
  const test::CliRun bad_file = test::run_cli("render '" + dir + "render_bad.jsonl' -o '" + dir + "x.png' 2>&1");
  EXPECT_EQ(bad_file.status, 1);
  EXPECT_NE(bad_file.output.find("line 2"), std::string::npos) << bad_file.output;
}

TEST(Render, BilliardsDemoWritesItsPng) {
  const std::string png = testing::TempDir() + "render_demo.png";
  std::remove(png.c_str());
  const test::CliRun run = test::run_cli("demo -q --frames 8 --png-frame 5 --svg '' --png '" + png + "'");
  ASSERT_EQ(run.status, 0);
  std::ifstream in(png, std::ios::binary);
  std::string head(4, '\0');
  in.read(head.data(), 4);
  EXPECT_EQ(head.substr(1, 3), "PNG");
}

TEST(Render, TunnellingDemoWritesAPngOfTheContinuousRun) {
  const std::string png = testing::TempDir() + "render_tunnelling.png";
  std::remove(png.c_str());
  const test::CliRun run =
      test::run_cli("demo-tunnelling -q --frames 20 --bullets 6 --png-frame 12 --svg '' --png '" + png + "'");
  ASSERT_EQ(run.status, 0);
  std::ifstream in(png, std::ios::binary);
  std::string head(24, '\0');
  in.read(head.data(), 24);
  ASSERT_EQ(head.substr(1, 3), "PNG");
  const auto be32 = [&](std::size_t at) {
    return (unsigned(static_cast<unsigned char>(head[at])) << 24) |
           (unsigned(static_cast<unsigned char>(head[at + 1])) << 16) |
           (unsigned(static_cast<unsigned char>(head[at + 2])) << 8) |
           unsigned(static_cast<unsigned char>(head[at + 3]));
  };
  EXPECT_EQ(be32(16), 800u);  // IHDR width and height: the renderer's defaults
  EXPECT_EQ(be32(20), 600u);
}

}  // namespace proxima::test_render
