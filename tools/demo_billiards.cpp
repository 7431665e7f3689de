#include "demo_billiards.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <memory>
#include <ostream>
#include <stdexcept>
#include <string>

#include "svg_writer.hpp"
#include "world_picture.hpp"

namespace proxima::tool {

namespace {

// Ball colours by number (0 is the cue ball); 9..15 are the stripes of 1..7.
const char* ball_colour(int ball) {
  static const char* const kSolids[] = {"#f4f1e6", "#f2c200", "#1f4fd1", "#d42020", "#6a2c91",
                                        "#f07d00", "#8be36b", "#8b1a1a", "#111111"};
  return kSolids[ball <= 8 ? ball : ball - 8];
}

std::string format(const char* pattern, double a) {
  char buffer[64];
  std::snprintf(buffer, sizeof(buffer), pattern, a);
  return buffer;
}

}  // namespace

std::string render_billiards_svg(const BilliardTable& table) {
  const BilliardConfig& c = table.config();
  const double scale = 400.0;  // pixels per metre
  const double rail = 36.0;    // cushion and wooden rail, pixels
  const double margin = 12.0;
  const double length = static_cast<double>(c.table_length);
  const double width = static_cast<double>(c.table_width);
  const double r = static_cast<double>(c.ball_radius) * scale;
  const double left = margin + rail;
  const double top = margin + rail;
  const double legend = 44.0;
  auto to_svg = [&](const Vec3& p) {
    return SvgPoint{left + (static_cast<double>(p.x) + 0.5 * length) * scale,
                    top + (0.5 * width - static_cast<double>(p.y)) * scale};
  };

  SvgWriter svg(2.0 * (margin + rail) + length * scale, 2.0 * (margin + rail) + width * scale + legend);
  svg.rect(margin, margin, 2.0 * rail + length * scale, 2.0 * rail + width * scale, "#5b3a1e", "none", 0.0, 14.0);
  svg.rect(left - 8.0, top - 8.0, length * scale + 16.0, width * scale + 16.0, "#1b5e37");
  svg.rect(left, top, length * scale, width * scale, "#23784a");
  // Head string and foot spot, as drawn on a real cloth.
  svg.line(to_svg(Vec3(Real(-0.25) * c.table_length, Real(-0.5) * c.table_width, 0)),
           to_svg(Vec3(Real(-0.25) * c.table_length, Real(0.5) * c.table_width, 0)), "#3f9465", 1.0);
  const SvgPoint foot = to_svg(Vec3(Real(0.25) * c.table_length, 0, 0));
  svg.circle(foot.x, foot.y, 2.0, "#3f9465");

  // Starting positions, faint.
  for (int b = 0; b < BilliardTable::kBallCount; ++b) {
    const SvgPoint p = to_svg(table.trajectories()[b].front());
    svg.circle(p.x, p.y, r, ball_colour(b), "#000000", 0.5, 0.35);
  }
  // Trajectories: one polyline per ball.
  for (int b = 0; b < BilliardTable::kBallCount; ++b) {
    std::vector<SvgPoint> points;
    for (const Vec3& q : table.trajectories()[b]) points.push_back(to_svg(q));
    if (points.size() == 1) points.push_back(points.front());
    svg.begin_group("ball " + std::to_string(b) + (b == 0 ? " (cue)" : ""));
    svg.polyline(points, ball_colour(b), 1.6, 0.9, b >= 9 ? "6 3" : "");
    svg.end_group();
  }
  // Contact points.
  for (const BilliardContact& contact : table.contacts()) {
    const SvgPoint p = to_svg(contact.point);
    if (contact.other >= 0) {
      svg.circle(p.x, p.y, 2.2, "#ffffff", "#000000", 0.6, 0.9);
    } else {
      svg.circle(p.x, p.y, 2.2, "#ffd54a", "#000000", 0.6, 0.9);
    }
  }
  // Final positions with their numbers.
  for (int b = 0; b < BilliardTable::kBallCount; ++b) {
    const SvgPoint p = to_svg(table.positions()[b]);
    svg.circle(p.x, p.y, r, ball_colour(b), "#000000", 1.0);
    if (b >= 9) svg.circle(p.x, p.y, 0.55 * r, "#f4f1e6");
    if (b > 0) {
      svg.text(p.x, p.y + 0.35 * r, std::to_string(b), r, b == 8 || (b >= 2 && b <= 4) ? "#ffffff" : "#000000",
               "middle");
    }
  }
  const BilliardStats& s = table.stats();
  const double bottom = 2.0 * (margin + rail) + width * scale;
  svg.text(margin, bottom + 18.0,
           "Proxima billiard break on the collision world: " + std::to_string(BilliardTable::kBallCount) + " balls, " +
               std::to_string(s.frames) + " frames at " + format("%g", c.frame_rate) + " Hz, seed " +
               std::to_string(c.seed),
           14.0, "#222222");
  svg.text(margin, bottom + 36.0,
           std::to_string(s.ball_collisions) + " ball-ball collisions (white), " +
               std::to_string(s.cushion_collisions) + " cushion collisions (yellow), " + std::to_string(s.impacts) +
               " impacts and " + std::to_string(s.begin_events) + " begin events from the collision world",
           12.0, "#444444");
  return svg.str();
}

namespace {

/// The playing surface (a felt rectangle at z = 0) and its cushions' edges, for the PNG: the
/// cushions are half-spaces, which a picture seen from above shows edge-on.
DrawBuffer table_drawing(const BilliardConfig& config) {
  const Real x = Real(0.5) * config.table_length, y = Real(0.5) * config.table_width;
  const Vec3 c[4] = {{-x, -y, 0}, {x, -y, 0}, {x, y, 0}, {-x, y, 0}};
  const Rgba felt{34, 110, 62, 255}, cushion{120, 72, 40, 255};
  const DrawTag user{DrawLayer::User, 0};
  DrawBuffer buffer;
  const DrawTriangle surface[2] = {{c[0], c[1], c[2], felt, user}, {c[0], c[2], c[3], felt, user}};
  buffer.draw_triangles(surface);
  DrawLine edges[4];
  for (int i = 0; i < 4; ++i) edges[i] = {c[i], c[(i + 1) % 4], cushion, user};
  buffer.draw_lines(edges);
  return buffer;
}

}  // namespace

int run_billiards_demo(const DemoOptions& options, std::ostream& out, std::ostream& err) {
  std::unique_ptr<BilliardTable> owned;
  try {
    owned = std::make_unique<BilliardTable>(options.config);
  } catch (const std::invalid_argument& e) {
    err << "proxima demo: " << e.what() << "\n";
    return 2;
  }
  BilliardTable& table = *owned;
  const double energy_start = table.kinetic_energy();
  double total_ms = 0.0;
  double max_ms = 0.0;
  const int png_frame = std::min(options.png_frame, options.config.frames - 1);
  for (int f = 0; f < options.config.frames; ++f) {
    const auto t0 = std::chrono::steady_clock::now();
    table.step();
    const auto t1 = std::chrono::steady_clock::now();
    const double ms = std::chrono::duration<double, std::milli>(t1 - t0).count();
    total_ms += ms;
    max_ms = std::max(max_ms, ms);
    if (f == png_frame && !options.png_path.empty()) {
      RenderOptions picture;
      picture.view = RenderView::Top;
      const DrawBuffer felt = table_drawing(table.config());
      if (auto e = write_world_picture(table.world(), options.png_path, picture, std::nullopt, &felt)) {
        err << "proxima demo: " << e->what() << "\n";
        return 1;
      }
    }
  }

  const BilliardStats& s = table.stats();
  if (!options.quiet) {
    const double frames = static_cast<double>(std::max<std::uint64_t>(s.frames, 1));
    const auto count = [](std::uint64_t n) { return static_cast<unsigned long long>(n); };
    char line[256];
    std::snprintf(line, sizeof(line),
                  "proxima demo: billiard break, %d balls, %d cushions, %llu frames at %g Hz (%.2f s), seed %llu\n",
                  BilliardTable::kBallCount, BilliardTable::kCushionCount, count(s.frames), options.config.frame_rate,
                  static_cast<double>(s.frames) / options.config.frame_rate, count(options.config.seed));
    out << line;
    std::snprintf(line, sizeof(line),
                  "collision world: %zu objects (balls: moving spheres, ccd bullet; cushions: static half-spaces), "
                  "broad phase \"%s\", %llu steps (%d per frame)\n",
                  table.world().size(), options.config.broadphase.c_str(), count(s.steps), options.config.substeps);
    out << line;
    std::snprintf(
        line, sizeof(line), "events: %llu impacts (continuous), %llu begin, %llu persist, %llu end; %llu callbacks\n",
        count(s.impacts), count(s.begin_events), count(s.persist_events), count(s.end_events), count(s.callbacks));
    out << line;
    std::snprintf(line, sizeof(line), "collisions resolved: %llu ball-ball, %llu ball-cushion\n",
                  count(s.ball_collisions), count(s.cushion_collisions));
    out << line;
    std::snprintf(line, sizeof(line), "time per frame: mean %.4f ms (world steps %.4f ms), max %.4f ms\n",
                  total_ms / frames, 1e3 * s.step_seconds / frames, max_ms);
    out << line;
    std::snprintf(line, sizeof(line), "kinetic energy: %.4f -> %.4f J/kg\n", energy_start, table.kinetic_energy());
    out << line;
  }
  if (!options.svg_path.empty()) {
    if (!write_file(options.svg_path, render_billiards_svg(table))) {
      err << "proxima demo: cannot write " << options.svg_path << "\n";
      return 1;
    }
    if (!options.quiet) out << "picture: " << options.svg_path << "\n";
  }
  if (!options.png_path.empty() && png_frame >= 0 && !options.quiet) {
    out << "frame " << png_frame << " drawn by proxima render: " << options.png_path << "\n";
  }
  return 0;
}

}  // namespace proxima::tool
