#include "demo_platformer.hpp"

#include <proxima/debug/draw_shapes_2d.hpp>

#include <algorithm>
#include <cstdio>
#include <optional>
#include <ostream>

#include "svg_writer.hpp"
#include "world_picture.hpp"

namespace proxima::tool {

namespace {

constexpr double kScale = 16.0;  // pixels per metre
constexpr double kWidth = 66.0 * kScale;
constexpr double kPanel = 11.0 * kScale;  // one run's height

SvgPoint to_svg(const Vec2& p, double panel_top) {
  return {(static_cast<double>(p.x) + 3.0) * kScale, panel_top + kPanel - (static_cast<double>(p.y) + 1.5) * kScale};
}

void draw_run(SvgWriter& svg, const PlatformerRun& run, double top, const char* title) {
  svg.text(8, top + 16, title, 13);
  std::vector<SvgPoint> ground;
  for (const Vec2& p : run.ground) ground.push_back(to_svg(p, top));
  svg.polyline(ground, "#4a3b2a", 3);
  for (const Vec2& p : run.ground) svg.circle(to_svg(p, top).x, to_svg(p, top).y, 1.5, "#4a3b2a");  // tile seams
  svg.line(to_svg(run.wall_bottom, top), to_svg(run.wall_top, top), "#555", 3);
  const Vec2 h = run.player_half_extents;
  for (std::size_t f = 0; f < run.player_trail.size(); f += 10) {
    const Vec2 c = run.player_trail[f].position;
    const SvgPoint corner = to_svg({c.x - h.x, c.y + h.y}, top);
    svg.rect(corner.x, corner.y, 2 * h.x * kScale, 2 * h.y * kScale, "#3b7dd8", "#1d4f99", 0.5);
  }
  for (const ProjectileTrack& t : run.projectiles) {
    const char* colour = t.tunnelled ? "#d62728" : "#2ca02c";
    svg.polyline({to_svg(t.start, top), to_svg(t.end, top)}, colour, 1.2, 0.9, t.tunnelled ? "4 3" : "");
    if (t.stopped) svg.circle(to_svg(t.end, top).x, to_svg(t.end, top).y, 3, colour);
  }
}

int count_stopped(const PlatformerRun& run) {
  int n = 0;
  for (const ProjectileTrack& t : run.projectiles) n += t.stopped;
  return n;
}

int count_tunnelled(const PlatformerRun& run) {
  int n = 0;
  for (const ProjectileTrack& t : run.projectiles) n += t.tunnelled;
  return n;
}

/// The sprite pair at its first pixel contact, in the sky of the panel: a screen pixel is
/// 0.1 m, the sprites' pixel row 0 at 10.5 m; the ring's set pixels blue, the turned cross's
/// (each of its pixels drawn where W9's rule puts its centre) orange, the first common pixel red.
void draw_sprites(SvgWriter& svg, const SpriteEncounter& e, double top) {
  if (e.pixels_frame < 0) return;
  constexpr double kPixel = 0.1;
  const auto at = [&](double px, double py) { return to_svg({Real(px * kPixel), Real(10.5 - py * kPixel)}, top); };
  const double side = kPixel * kScale;
  for (int y = 0; y < e.ring.height(); ++y) {
    for (int x = 0; x < e.ring.width(); ++x) {
      if (!e.ring.get(x, y)) continue;
      const SvgPoint p = at(e.start_a + e.pixels_frame + x, e.row + y);
      svg.rect(p.x, p.y, side, side, "#3b7dd8");
    }
  }
  const d2::TurnedPlacement b = e.placement_b(e.pixels_frame);
  const double cx = static_cast<double>(b.position().x) + e.cross.width() / 2.0;
  const double cy = static_cast<double>(b.position().y) + e.cross.height() / 2.0;
  for (int v = 0; v < e.cross.height(); ++v) {
    for (int u = 0; u < e.cross.width(); ++u) {
      if (!e.cross.get(u, v)) continue;
      const double lu = u + 0.5 - e.cross.width() / 2.0, lv = v + 0.5 - e.cross.height() / 2.0;
      const double dx = b.scale() * (b.cos() * lu - b.sin() * lv), dy = b.scale() * (b.sin() * lu + b.cos() * lv);
      const SvgPoint p = at(cx + dx - 0.5, cy + dy - 0.5);
      svg.rect(p.x, p.y, side, side, "#ff7f0e", "none", 0, 0);
    }
  }
  const SvgPoint f = at(static_cast<double>(e.first_pixel.x), static_cast<double>(e.first_pixel.y));
  svg.rect(f.x, f.y, side, side, "#d62728");
  char label[160];
  std::snprintf(label, sizeof(label),
                "sprites: rectangles meet at frame %d, pixels at frame %d (%llu common, first in red)",
                e.rectangles_frame, e.pixels_frame, static_cast<unsigned long long>(e.pixels));
  const SvgPoint l = at(static_cast<double>(e.start_b - e.pixels_frame) + 40, static_cast<double>(e.row) + 18);
  svg.text(l.x, l.y, label, 11, "#444");
}

}  // namespace

std::string render_platformer_svg(const PlatformerRun& continuous, const PlatformerRun& discrete) {
  SvgWriter svg(kWidth, 2 * kPanel + 10);
  svg.rect(0, 0, kWidth, 2 * kPanel + 10, "#fbfaf6");
  char title[160];
  std::snprintf(
      title, sizeof(title),
      "continuous detection: %d of %d projectiles stopped at the wall; the player on a ground of %zu tiles: %d catches",
      count_stopped(continuous), static_cast<int>(continuous.projectiles.size()), continuous.ground.size() - 1,
      continuous.catches);
  draw_run(svg, continuous, 0, title);
  draw_sprites(svg, continuous.sprites, 0);
  std::snprintf(title, sizeof(title), "discrete detection: %d of %d projectiles passed through the wall (dashed)",
                count_tunnelled(discrete), static_cast<int>(discrete.projectiles.size()));
  draw_run(svg, discrete, kPanel + 10, title);
  return svg.str();
}

DrawBuffer platformer_overlay(const PlatformerRun& run) {
  DrawBuffer draw;
  debug::Shape2DDrawOptions outline;
  outline.fill = false;
  outline.layer = DrawLayer::User;
  const d2::Shape player = d2::Polygon::box(run.player_half_extents.x, run.player_half_extents.y).value();
  for (std::size_t f = 0; f < run.player_trail.size(); f += 10) {
    debug::draw_shape_2d(draw, player, run.player_trail[f], Rgba{255, 190, 110, 200}, outline);
  }
  std::vector<DrawLine> tracks;
  for (const ProjectileTrack& t : run.projectiles) {
    const bool through = !t.stopped && t.end.x > run.wall_bottom.x;
    const Rgba color = t.stopped ? Rgba{60, 200, 90, 255} : through ? Rgba{230, 60, 50, 255} : Rgba{240, 210, 60, 255};
    tracks.push_back({debug::plane_point(t.start), debug::plane_point(t.end), color, DrawTag{DrawLayer::Sweeps, 0}});
  }
  draw.draw_lines(tracks);
  char title[160];
  std::snprintf(
      title, sizeof(title), "frame %d: the 2D world drawn by proxima render - %d of %d projectiles stopped at the wall",
      static_cast<int>(run.player_trail.size()) - 1, count_stopped(run), static_cast<int>(run.projectiles.size()));
  const DrawText label{Vec3(Real(-0.5), Real(8.8), Real(0)), title, Rgba{230, 230, 230, 255},
                       DrawTag{DrawLayer::Text, 0}};
  draw.draw_texts({&label, 1});
  return draw;
}

debug::CaptureOptions platformer_capture() {
  debug::CaptureOptions capture;
  capture.camera = debug::CaptureCamera{Vec3(Real(30), Real(4), Real(20)), Vec3(Real(30), Real(4), Real(0)),
                                        Vec3(Real(0), Real(1), Real(0)), Real(0), Real(11)};
  capture.contact.labels = false;
  capture.contact.normal_length = Real(0.5);
  return capture;
}

std::string platformer_report(const PlatformerRun& continuous, const PlatformerRun& discrete) {
  char text[512];
  std::snprintf(
      text, sizeof(text),
      "platformer: %d frames, ground of %zu tiles (chain with ghost vertices), player %d ground contacts, %d catches\n"
      "  continuous: %d of %d projectiles stopped at the wall, %d tunnelled\n"
      "  discrete:   %d of %d projectiles stopped, %d tunnelled\n"
      "  sprites: bounding rectangles meet at frame %d, the pixels at frame %d (%llu common pixels)\n",
      continuous.steps, continuous.ground.size() - 1, continuous.ground_contacts, continuous.catches,
      count_stopped(continuous), static_cast<int>(continuous.projectiles.size()), count_tunnelled(continuous),
      count_stopped(discrete), static_cast<int>(discrete.projectiles.size()), count_tunnelled(discrete),
      continuous.sprites.rectangles_frame, continuous.sprites.pixels_frame,
      static_cast<unsigned long long>(continuous.sprites.pixels));
  return text;
}

int run_platformer_demo(const PlatformerDemoOptions& options, std::ostream& out, std::ostream& err) {
  PlatformerConfig config = options.config;
  config.projectile_ccd = d2::CcdMode::Bullet;
  const int png_frame = std::clamp(options.png_frame, 0, std::max(config.frames - 1, 0));
  std::optional<Error> picture_error;
  const PlatformerRun continuous =
      run_platformer(config, [&](int frame, const d2::CollisionWorld& world, const PlatformerRun& run) {
        if (frame != png_frame || options.png_path.empty()) return;
        RenderOptions picture;
        picture.width = 1240;
        picture.height = 220;
        const DrawBuffer overlay = platformer_overlay(run);
        picture_error = write_world_picture_2d(world, options.png_path, picture, platformer_capture(), &overlay);
      });
  if (picture_error) {
    err << "proxima demo-platformer: " << picture_error->what() << "\n";
    return 1;
  }
  config.projectile_ccd = d2::CcdMode::Off;
  const PlatformerRun discrete = run_platformer(config);
  if (!options.quiet) out << platformer_report(continuous, discrete);
  if (!options.svg_path.empty()) {
    if (!write_file(options.svg_path, render_platformer_svg(continuous, discrete))) {
      err << "cannot write " << options.svg_path << "\n";
      return 1;
    }
    if (!options.quiet) out << "wrote " << options.svg_path << "\n";
  }
  if (!options.png_path.empty() && !options.quiet) {
    out << "frame " << png_frame << " of the continuous run drawn by proxima render: " << options.png_path << "\n";
  }
  return 0;
}

}  // namespace proxima::tool
