#include "demo_platformer.hpp"

#include <cstdio>
#include <ostream>

#include "svg_writer.hpp"

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
  std::snprintf(title, sizeof(title), "discrete detection: %d of %d projectiles passed through the wall (dashed)",
                count_tunnelled(discrete), static_cast<int>(discrete.projectiles.size()));
  draw_run(svg, discrete, kPanel + 10, title);
  return svg.str();
}

std::string platformer_report(const PlatformerRun& continuous, const PlatformerRun& discrete) {
  char text[512];
  std::snprintf(
      text, sizeof(text),
      "platformer: %d frames, ground of %zu tiles (chain with ghost vertices), player %d ground contacts, %d catches\n"
      "  continuous: %d of %d projectiles stopped at the wall, %d tunnelled\n"
      "  discrete:   %d of %d projectiles stopped, %d tunnelled\n",
      continuous.steps, continuous.ground.size() - 1, continuous.ground_contacts, continuous.catches,
      count_stopped(continuous), static_cast<int>(continuous.projectiles.size()), count_tunnelled(continuous),
      count_stopped(discrete), static_cast<int>(discrete.projectiles.size()), count_tunnelled(discrete));
  return text;
}

int run_platformer_demo(const PlatformerDemoOptions& options, std::ostream& out, std::ostream& err) {
  PlatformerConfig config = options.config;
  config.projectile_ccd = d2::CcdMode::Bullet;
  const PlatformerRun continuous = run_platformer(config);
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
  return 0;
}

}  // namespace proxima::tool
