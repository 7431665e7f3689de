#include "demo_tunnelling.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

#include "svg_writer.hpp"
#include "world_picture.hpp"

namespace proxima::tool {

namespace {

const char* const kPlateColour = "#3b4a6b";
const char* const kDiscreteColour = "#1f5fbf";
const char* const kContinuousColour = "#2a9d4b";
const char* const kTunnelColour = "#d62828";
const char* const kMissColour = "#9a9a9a";
const char* const kImpactColour = "#ff9f1c";

// The part of segment [a, b] inside the field (Liang-Barsky in the plane z = 0).
std::optional<std::pair<Vec3, Vec3>> clip_to_field(const Vec3& a, const Vec3& b, double half_length,
                                                   double half_width) {
  double t0 = 0.0;
  double t1 = 1.0;
  const double p0[2] = {static_cast<double>(a.x), static_cast<double>(a.y)};
  const double d[2] = {static_cast<double>(b.x - a.x), static_cast<double>(b.y - a.y)};
  const double half[2] = {half_length, half_width};
  for (int axis = 0; axis < 2; ++axis) {
    if (d[axis] == 0.0) {
      if (std::abs(p0[axis]) > half[axis]) return std::nullopt;
      continue;
    }
    double lo = (-half[axis] - p0[axis]) / d[axis];
    double hi = (half[axis] - p0[axis]) / d[axis];
    if (lo > hi) std::swap(lo, hi);
    t0 = std::max(t0, lo);
    t1 = std::min(t1, hi);
    if (t0 > t1) return std::nullopt;
  }
  const Vec3 delta = b - a;
  return std::make_pair(a + delta * static_cast<Real>(t0), a + delta * static_cast<Real>(t1));
}

class PanelDrawer {
 public:
  PanelDrawer(SvgWriter& svg, const TunnellingScene& scene, double left, double top, double scale)
      : svg_(svg), scene_(scene), left_(left), top_(top), scale_(scale) {}

  SvgPoint to_svg(const Vec3& p) const {
    const TunnellingConfig& c = scene_.config();
    return SvgPoint{left_ + (static_cast<double>(p.x) + 0.5 * static_cast<double>(c.field_length)) * scale_,
                    top_ + (0.5 * static_cast<double>(c.field_width) - static_cast<double>(p.y)) * scale_};
  }

  // The plate's outline seen from above, at `time`.
  void plate(int k, double time, const char* fill, double opacity) {
    const TunnellingPlate& p = scene_.plates()[static_cast<std::size_t>(k)];
    const Transform pose = p.pose_at(time);
    const Vec3 h = p.box.half_extents();
    std::vector<SvgPoint> corners;
    for (const auto& [sx, sy] : {std::pair{1, 1}, std::pair{-1, 1}, std::pair{-1, -1}, std::pair{1, -1}}) {
      corners.push_back(to_svg(pose.apply(Vec3(h.x * Real(sx), h.y * Real(sy), Real(0)))));
    }
    svg_.polygon(corners, fill, fill, opacity < 1.0 ? 0.0 : 0.8, opacity);
  }

  // The field, the plates' sweeps (faint discs) and the plates' final poses.
  void background(const std::string& title) {
    const TunnellingConfig& c = scene_.config();
    svg_.text(left_, top_ - 8.0, title, 14.0, "#222222");
    svg_.rect(left_, top_, static_cast<double>(c.field_length) * scale_, static_cast<double>(c.field_width) * scale_,
              "#fbfaf6", "#8a8a8a", 1.0);
    for (const TunnellingPlate& p : scene_.plates()) {
      const SvgPoint centre = to_svg(p.centre);
      const Vec3 h = p.box.half_extents();
      svg_.circle(centre.x, centre.y, std::hypot(static_cast<double>(h.x), static_cast<double>(h.y)) * scale_,
                  kPlateColour, "none", 0.0, 0.07);
    }
  }

  void final_plates() {
    const double end = static_cast<double>(scene_.config().frames) * scene_.frame_time();
    for (int k = 0; k < static_cast<int>(scene_.plates().size()); ++k) plate(k, end, kPlateColour, 1.0);
  }

  // A straight path from `a` to `b`, clipped to the field.
  void path(const Vec3& a, const Vec3& b, const char* colour, double width, const char* dash = "") {
    const TunnellingConfig& c = scene_.config();
    const auto clipped =
        clip_to_field(a, b, 0.5 * static_cast<double>(c.field_length), 0.5 * static_cast<double>(c.field_width));
    if (!clipped) return;
    svg_.polyline({to_svg(clipped->first), to_svg(clipped->second)}, colour, width, 0.9, dash);
  }

  // Dots at the frame poses inside the field.
  void frame_dots(const BulletOutcome& outcome, const char* colour) {
    for (const Vec3& p : outcome.frame_positions) {
      if (scene_.outside_field(p, Real(0))) continue;
      const SvgPoint q = to_svg(p);
      svg_.circle(q.x, q.y, 1.8, colour);
    }
  }

  // The bullet's sphere at `centre`.
  void bullet(const Vec3& centre, Real radius, const char* colour, double fill_opacity) {
    const SvgPoint q = to_svg(centre);
    const double r = static_cast<double>(radius) * scale_;
    svg_.circle(q.x, q.y, r, colour, "none", 0.0, fill_opacity);
    svg_.circle(q.x, q.y, r, "none", colour, 1.0);
  }

  void ring(const Vec3& centre, Real radius, const char* colour) {
    const SvgPoint q = to_svg(centre);
    svg_.circle(q.x, q.y, static_cast<double>(radius) * scale_, "none", colour, 1.2);
  }

  void impact(const Vec3& point) {
    const SvgPoint q = to_svg(point);
    svg_.circle(q.x, q.y, 3.0, kImpactColour, "#000000", 0.7);
  }

  void start(const Vec3& p) {
    const SvgPoint q = to_svg(p);
    svg_.circle(q.x, q.y, 2.0, "#222222");
  }

 private:
  SvgWriter& svg_;
  const TunnellingScene& scene_;
  double left_;
  double top_;
  double scale_;
};

std::string bullet_title(const TunnellingScene& scene, int i, const BulletOutcome& outcome, const char* detector) {
  const TunnellingBullet& b = scene.bullets()[static_cast<std::size_t>(i)];
  char line[256];
  if (outcome.hit) {
    std::snprintf(line, sizeof(line),
                  "bullet %d (radius %.3f m, %.1f m/s, fired at frame %d): %s hit on plate %d at %.4f s", i,
                  static_cast<double>(b.sphere.radius()), static_cast<double>(glm::length(b.velocity)), b.fire_frame,
                  detector, outcome.plate, outcome.time);
  } else {
    std::snprintf(line, sizeof(line), "bullet %d (radius %.3f m, %.1f m/s, fired at frame %d): %s, no hit", i,
                  static_cast<double>(b.sphere.radius()), static_cast<double>(glm::length(b.velocity)), b.fire_frame,
                  detector);
  }
  std::string title = line;
  if (scene.tunnelled(i) && std::string(detector) == "discrete") title += " (tunnelled)";
  return title;
}

// Where a bullet's drawn path ends: its stop, or its last pose (clipped to the field).
Vec3 path_end(const BulletOutcome& outcome, const TunnellingBullet& b) {
  return outcome.frame_positions.empty() && !outcome.hit ? b.start : outcome.stop;
}

}  // namespace

std::string render_tunnelling_svg(const TunnellingScene& scene) {
  const TunnellingConfig& c = scene.config();
  const double scale = 140.0;  // pixels per metre
  const double margin = 16.0;
  const double gap = 28.0;
  const double title = 26.0;
  const double legend = 70.0;
  const double panel_width = static_cast<double>(c.field_length) * scale;
  const double panel_height = static_cast<double>(c.field_width) * scale;
  const double top = margin + title;
  SvgWriter svg(2.0 * margin + 2.0 * panel_width + gap, top + panel_height + legend);
  svg.rect(0.0, 0.0, 2.0 * margin + 2.0 * panel_width + gap, top + panel_height + legend, "#ffffff");

  const int n = static_cast<int>(scene.bullets().size());
  const std::uint64_t discrete_hits = scene.discrete_stats().hits;
  const std::uint64_t continuous_hits = scene.continuous_stats().hits;
  const int tunnelled = scene.tunnelled_count();

  // Left: the discrete run.
  svg.begin_group("discrete panel");
  PanelDrawer left(svg, scene, margin, top, scale);
  left.background("discrete (world, ccd off): contacts at each frame's poses - " + std::to_string(discrete_hits) +
                  " hits, " + std::to_string(tunnelled) + " tunnelled");
  for (int i = 0; i < n; ++i) {
    const BulletOutcome& d = scene.discrete()[static_cast<std::size_t>(i)];
    const BulletOutcome& cc = scene.continuous()[static_cast<std::size_t>(i)];
    if (d.hit) left.plate(d.plate, d.time, kDiscreteColour, 0.25);
    if (scene.tunnelled(i)) left.plate(cc.plate, cc.time, kTunnelColour, 0.25);
  }
  left.final_plates();
  for (int i = 0; i < n; ++i) {
    const TunnellingBullet& b = scene.bullets()[static_cast<std::size_t>(i)];
    const BulletOutcome& d = scene.discrete()[static_cast<std::size_t>(i)];
    const BulletOutcome& cc = scene.continuous()[static_cast<std::size_t>(i)];
    svg.begin_group(bullet_title(scene, i, d, "discrete"));
    if (scene.tunnelled(i)) {
      left.path(b.start, path_end(d, b), kTunnelColour, 1.6, "6 4");
      left.frame_dots(d, kTunnelColour);
      left.ring(cc.stop, b.sphere.radius(), kTunnelColour);
      if (d.hit) left.bullet(d.stop, b.sphere.radius(), kDiscreteColour, 0.45);
    } else if (d.hit) {
      left.path(b.start, d.stop, kDiscreteColour, 1.6);
      left.frame_dots(d, kDiscreteColour);
      left.bullet(d.stop, b.sphere.radius(), kDiscreteColour, 0.45);
    } else {
      left.path(b.start, path_end(d, b), kMissColour, 1.0);
      left.frame_dots(d, kMissColour);
    }
    left.start(b.start);
    svg.end_group();
  }
  svg.end_group();

  // Right: the continuous run.
  svg.begin_group("continuous panel");
  PanelDrawer right(svg, scene, margin + panel_width + gap, top, scale);
  right.background("continuous (world, ccd bullet): impacts over each frame's motion - " +
                   std::to_string(continuous_hits) + " hits");
  for (int i = 0; i < n; ++i) {
    const BulletOutcome& cc = scene.continuous()[static_cast<std::size_t>(i)];
    if (cc.hit) right.plate(cc.plate, cc.time, kContinuousColour, 0.25);
  }
  right.final_plates();
  for (int i = 0; i < n; ++i) {
    const TunnellingBullet& b = scene.bullets()[static_cast<std::size_t>(i)];
    const BulletOutcome& cc = scene.continuous()[static_cast<std::size_t>(i)];
    svg.begin_group(bullet_title(scene, i, cc, "continuous"));
    if (cc.hit) {
      right.path(b.start, cc.stop, kContinuousColour, 1.6);
      right.bullet(cc.stop, b.sphere.radius(), kContinuousColour, 0.35);
      right.impact(cc.point);
    } else {
      right.path(b.start, path_end(cc, b), kMissColour, 1.0);
    }
    right.start(b.start);
    svg.end_group();
  }
  svg.end_group();

  // Legend.
  const double y = top + panel_height;
  char line[512];
  std::snprintf(line, sizeof(line),
                "Proxima tunnelling demo: %d bullets (radius %g-%g m, %g-%g m/s) fired at %zu plates %g cm thick "
                "spinning at 3-7 rad/s; %d frames at %g Hz, seed %llu",
                n, static_cast<double>(c.min_radius), static_cast<double>(c.max_radius),
                static_cast<double>(c.min_speed), static_cast<double>(c.max_speed), scene.plates().size(),
                200.0 * static_cast<double>(c.plate_half_thickness), c.frames, c.frame_rate,
                static_cast<unsigned long long>(c.seed));
  svg.text(margin, y + 20.0, line, 13.0, "#222222");
  std::snprintf(line, sizeof(line),
                "bullets: %d, discrete hits: %llu, continuous hits: %llu, tunnelled: %d. Left: blue stopped at a "
                "frame pose; red dashed through a plate between two frames (dots: frame poses, ring: the missed "
                "contact).",
                n, static_cast<unsigned long long>(discrete_hits), static_cast<unsigned long long>(continuous_hits),
                tunnelled);
  svg.text(margin, y + 38.0, line, 12.0, "#444444");
  svg.text(margin, y + 56.0,
           "Right: green stopped at the time of impact (orange: contact point; tinted plate: its pose then). Grey: "
           "no plate in the way. Faint discs: the plates' sweeps; dark: their final poses.",
           12.0, "#444444");
  return svg.str();
}

std::string tunnelling_report(const TunnellingScene& scene) {
  const TunnellingConfig& c = scene.config();
  const DetectorStats& d = scene.discrete_stats();
  const DetectorStats& cc = scene.continuous_stats();
  auto per_step_us = [](const DetectorStats& s) {
    return s.steps == 0 ? 0.0 : 1e6 * s.seconds / static_cast<double>(s.steps);
  };
  const auto count = [](std::uint64_t v) { return static_cast<unsigned long long>(v); };
  std::string text;
  char line[320];
  std::snprintf(line, sizeof(line),
                "proxima demo-tunnelling: %zu bullets (radius %g-%g m, %g-%g m/s) at %zu spinning plates (half "
                "thickness %g m), %d frames at %g Hz (%.2f s), seed %llu\n",
                scene.bullets().size(), static_cast<double>(c.min_radius), static_cast<double>(c.max_radius),
                static_cast<double>(c.min_speed), static_cast<double>(c.max_speed), scene.plates().size(),
                static_cast<double>(c.plate_half_thickness), c.frames, c.frame_rate,
                static_cast<double>(c.frames) / c.frame_rate, count(c.seed));
  text += line;
  std::snprintf(line, sizeof(line),
                "discrete (collision world, ccd off: contacts at each frame's poses): %llu hits, %llu begin events, "
                "%llu steps, %.3f us per step\n",
                count(d.hits), count(d.begin_events), count(d.steps), per_step_us(d));
  text += line;
  std::snprintf(line, sizeof(line),
                "continuous (collision world, ccd bullet: impacts over each frame's motion): %llu hits, %llu impacts, "
                "%llu steps, %.3f us per step\n",
                count(cc.hits), count(cc.impacts), count(cc.steps), per_step_us(cc));
  text += line;
  std::snprintf(line, sizeof(line), "tunnelled (caught only by the continuous detector): %d\n",
                scene.tunnelled_count());
  text += line;
  if (cc.late_hits > 0) {
    text += "warning: " + std::to_string(cc.late_hits) +
            " bullets stopped by a contact at a frame's end with no impact event before it\n";
  }
  if (scene.discrete_only_count() > 0) {
    text += "warning: " + std::to_string(scene.discrete_only_count()) +
            " bullets stopped by the discrete detector only (an overlap that continuous detection missed)\n";
  }
  return text;
}

int run_tunnelling_demo(const TunnellingDemoOptions& options, std::ostream& out, std::ostream& err) {
  TunnellingScene scene(options.config);
  const int png_frame = std::clamp(options.png_frame, 0, std::max(options.config.frames - 1, 0));
  std::optional<Error> picture_error;
  scene.run([&](CcdMode mode, int frame, const CollisionWorld& world) {
    if (mode != CcdMode::Bullet || frame != png_frame || options.png_path.empty()) return;
    RenderOptions picture;
    picture.view = RenderView::Top;
    picture_error = write_world_picture(world, options.png_path, picture);
  });
  if (picture_error) {
    err << "proxima demo-tunnelling: " << picture_error->what() << "\n";
    return 1;
  }
  if (!options.quiet) out << tunnelling_report(scene);
  if (!options.svg_path.empty()) {
    if (!write_file(options.svg_path, render_tunnelling_svg(scene))) {
      err << "proxima demo-tunnelling: cannot write " << options.svg_path << "\n";
      return 1;
    }
    if (!options.quiet) out << "picture: " << options.svg_path << "\n";
  }
  if (!options.png_path.empty() && !options.quiet) {
    out << "frame " << png_frame << " of the continuous run drawn by proxima render: " << options.png_path << "\n";
  }
  return 0;
}

}  // namespace proxima::tool
