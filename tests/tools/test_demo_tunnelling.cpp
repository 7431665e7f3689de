// Tests of `proxima demo-tunnelling`: the continuous detector (a collision world with CcdMode::Bullet) against an
// independent reference written here (the relative motion sampled 10,000 times per frame,
// with the exact sphere-box distance by clamping, in double), the discrete detector missing
// some crossings (the scene really tunnels), the SVG (well-formed, both panels), determinism,
// and the command line.
#include <gtest/gtest.h>

#include <proxima/core/tolerance.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "cli_run.hpp"
#include "demo_tunnelling.hpp"
#include "tunnelling_scene.hpp"

namespace proxima {
namespace test_demo_tunnelling {

using tool::TunnellingConfig;
using tool::TunnellingScene;

struct D3 {
  double x, y, z;
};

D3 to_d3(const Vec3& v) { return {double(v.x), double(v.y), double(v.z)}; }

// The bullet's centre at `time` seconds, in double, from its firing data.
D3 bullet_centre(const tool::TunnellingBullet& b, double time, double frame_rate) {
  const double flight = time - double(b.fire_frame) / frame_rate;
  const D3 s = to_d3(b.start);
  const D3 v = to_d3(b.velocity);
  return {s.x + v.x * flight, s.y + v.y * flight, s.z + v.z * flight};
}

// Exact signed distance from a sphere (centre c, radius r) to the plate at `time`: the
// centre taken into the plate's frame (rotation by -(phase + spin time) about z), clamped
// to the box; inside the box, minus the distance to the nearest face.
double sphere_plate_distance(const D3& c, double r, const tool::TunnellingPlate& plate, double time) {
  const double angle = plate.phase + plate.spin * time;
  const D3 o = to_d3(plate.centre);
  const D3 h = to_d3(plate.box.half_extents());
  const double dx = c.x - o.x;
  const double dy = c.y - o.y;
  const double cs = std::cos(angle);
  const double sn = std::sin(angle);
  const double l[3] = {cs * dx + sn * dy, -sn * dx + cs * dy, c.z - o.z};
  const double hh[3] = {h.x, h.y, h.z};
  double outside = 0.0;
  double inside = std::numeric_limits<double>::infinity();
  bool out = false;
  for (int a = 0; a < 3; ++a) {
    const double excess = std::abs(l[a]) - hh[a];
    if (excess > 0.0) {
      out = true;
      outside += excess * excess;
    }
    inside = std::min(inside, hh[a] - std::abs(l[a]));
  }
  return out ? std::sqrt(outside) - r : -inside - r;
}

// The reference's answer for one bullet: the first sampled time at which it overlaps or
// touches a plate (distance <= 0), and the least distance seen over the whole flight.
struct ReferenceContact {
  bool found = false;
  int plate = -1;
  double time = 0.0;
  double least_distance = std::numeric_limits<double>::infinity();
};

ReferenceContact reference_contact(const TunnellingScene& scene, int i, int samples_per_frame) {
  const TunnellingConfig& c = scene.config();
  const tool::TunnellingBullet& b = scene.bullets()[std::size_t(i)];
  const double r = double(b.sphere.radius());
  const double dt = 1.0 / c.frame_rate;
  ReferenceContact ref;
  for (int f = b.fire_frame; f < c.frames && !ref.found; ++f) {
    const double t0 = f * dt;
    // Plates that may come within reach this frame: the segment flown against the plate's
    // bounding sphere (radius |h|), a conservative cull.
    std::vector<int> near;
    const D3 a = bullet_centre(b, t0, c.frame_rate);
    const D3 e = bullet_centre(b, t0 + dt, c.frame_rate);
    for (std::size_t k = 0; k < scene.plates().size(); ++k) {
      const tool::TunnellingPlate& p = scene.plates()[k];
      const D3 o = to_d3(p.centre);
      const D3 h = to_d3(p.box.half_extents());
      const D3 d{e.x - a.x, e.y - a.y, e.z - a.z};
      const D3 ao{o.x - a.x, o.y - a.y, o.z - a.z};
      const double dd = d.x * d.x + d.y * d.y + d.z * d.z;
      const double s = dd > 0 ? std::clamp((ao.x * d.x + ao.y * d.y + ao.z * d.z) / dd, 0.0, 1.0) : 0.0;
      const D3 q{a.x + s * d.x - o.x, a.y + s * d.y - o.y, a.z + s * d.z - o.z};
      const double reach = r + std::sqrt(h.x * h.x + h.y * h.y + h.z * h.z) + 1e-3;
      if (q.x * q.x + q.y * q.y + q.z * q.z <= reach * reach) near.push_back(int(k));
    }
    if (near.empty()) continue;
    for (int s = 0; s <= samples_per_frame && !ref.found; ++s) {
      const double t = t0 + dt * double(s) / double(samples_per_frame);
      const D3 centre = bullet_centre(b, t, c.frame_rate);
      for (int k : near) {
        const double d = sphere_plate_distance(centre, r, scene.plates()[std::size_t(k)], t);
        ref.least_distance = std::min(ref.least_distance, d);
        if (d <= 0.0) {
          ref.found = true;
          ref.plate = k;
          ref.time = t;
          break;
        }
      }
    }
  }
  return ref;
}

// Distance (reference) from bullet i to plate k at `time`.
double reference_distance(const TunnellingScene& scene, int i, int k, double time) {
  const tool::TunnellingBullet& b = scene.bullets()[std::size_t(i)];
  return sphere_plate_distance(bullet_centre(b, time, scene.config().frame_rate), double(b.sphere.radius()),
                               scene.plates()[std::size_t(k)], time);
}

// Well-formedness of the SVG's XML: every element closed in order.
bool xml_tags_balanced(const std::string& xml) {
  std::vector<std::string> open;
  for (std::size_t at = xml.find('<'); at != std::string::npos; at = xml.find('<', at + 1)) {
    const std::size_t end = xml.find('>', at);
    if (end == std::string::npos) return false;
    const std::string tag = xml.substr(at + 1, end - at - 1);
    if (tag.empty()) return false;
    if (tag.front() == '/') {
      if (open.empty() || open.back() != tag.substr(1)) return false;
      open.pop_back();
    } else if (tag.back() != '/') {
      open.push_back(tag.substr(0, tag.find_first_of(" \t\n")));
    }
    at = end;
  }
  return open.empty();
}

std::size_t count_of(const std::string& text, const std::string& needle) {
  std::size_t count = 0;
  for (std::size_t at = text.find(needle); at != std::string::npos; at = text.find(needle, at + 1)) ++count;
  return count;
}

// The report with the timings ("1.234 us per query") blanked.
std::string without_timings(const std::string& report) {
  std::string out;
  std::istringstream in(report);
  std::string line;
  while (std::getline(in, line)) {
    const std::size_t us = line.find(" us per step");
    if (us != std::string::npos) {
      const std::size_t number = line.rfind(' ', us - 1);
      line = line.substr(0, number + 1) + "#" + line.substr(us);
    }
    out += line + "\n";
  }
  return out;
}

// The length tolerance time_of_impact is held to at the time of impact (its default 1e-4,
// raised to the pair's precision floor, 8 linear_tolerance(scale): the scale of this scene
// is below 10), plus the float rounding of the poses.
double toi_tolerance() { return std::max(1e-4, 8.0 * double(linear_tolerance(Real(10)))) + 1e-5; }

TEST(DemoTunnelling, ContinuousCatchesEveryCrossingOfTheReference) {
  TunnellingScene scene(TunnellingConfig{});
  scene.run();
  const int n = int(scene.bullets().size());
  ASSERT_EQ(n, 24);
  const double slack = 1e-5;  // float rounding of positions and rotations, metres
  const double tol = toi_tolerance();
  int crossings = 0;
  for (int i = 0; i < n; ++i) {
    const ReferenceContact ref = reference_contact(scene, i, 10000);
    const tool::BulletOutcome& c = scene.continuous()[std::size_t(i)];
    if (ref.found) {
      ++crossings;
      ASSERT_TRUE(c.hit) << "bullet " << i << " crosses plate " << ref.plate << " at " << ref.time
                         << " s and time_of_impact missed it";
      EXPECT_EQ(c.plate, ref.plate) << "bullet " << i;
      // Not later than the first sampled overlap (and not too early: the certificate below).
      EXPECT_LE(c.time, ref.time + 1e-9) << "bullet " << i;
    } else if (c.hit) {
      // A graze that the sampling missed: allowed only within the tolerance.
      EXPECT_LE(ref.least_distance, tol) << "bullet " << i << ": hit with no reference contact";
    }
    if (c.hit) {
      // The certificate: within target + tolerance at the time of impact, not through.
      const double d = reference_distance(scene, i, c.plate, c.time);
      EXPECT_LE(d, tol) << "bullet " << i;
      EXPECT_GE(d, -slack) << "bullet " << i;
      // The bullet stops on its line at the time of impact, next to the contact point.
      const D3 centre = bullet_centre(scene.bullets()[std::size_t(i)], c.time, scene.config().frame_rate);
      const D3 stop = to_d3(c.stop);
      EXPECT_NEAR(stop.x, centre.x, 1e-4) << "bullet " << i;
      EXPECT_NEAR(stop.y, centre.y, 1e-4) << "bullet " << i;
      const D3 point = to_d3(c.point);
      const double to_point = std::hypot(point.x - centre.x, point.y - centre.y, point.z - centre.z);
      EXPECT_NEAR(to_point, double(scene.bullets()[std::size_t(i)].sphere.radius()), tol + slack) << "bullet " << i;
    }
  }
  // The scene is meaningful: most bullets meet a plate, and some fly past.
  EXPECT_GE(crossings, 10);
  EXPECT_LT(crossings, n);
  EXPECT_EQ(std::uint64_t(std::count_if(scene.continuous().begin(), scene.continuous().end(),
                                        [](const tool::BulletOutcome& o) { return o.hit; })),
            scene.continuous_stats().hits);
  const auto& s = scene.continuous_stats();
  EXPECT_EQ(s.late_hits, 0u);
  EXPECT_EQ(s.impacts, s.hits);
  EXPECT_EQ(s.steps, std::uint64_t(scene.config().frames));
}

TEST(DemoTunnelling, DiscreteMissesSomeCrossings) {
  TunnellingScene scene(TunnellingConfig{});
  scene.run();
  const int n = int(scene.bullets().size());
  int missed = 0;
  for (int i = 0; i < n; ++i) {
    const tool::BulletOutcome& d = scene.discrete()[std::size_t(i)];
    const tool::BulletOutcome& c = scene.continuous()[std::size_t(i)];
    if (d.hit) {
      // A discrete hit is an overlap at a frame pose, which the continuous run met no later.
      EXPECT_LE(reference_distance(scene, i, d.plate, d.time), 1e-5) << "bullet " << i;
      ASSERT_TRUE(c.hit) << "bullet " << i;
      EXPECT_LE(c.time, d.time + 1e-9) << "bullet " << i;
    }
    if (c.hit && !(d.hit && d.plate == c.plate)) {
      ++missed;
      EXPECT_TRUE(scene.tunnelled(i));
      // The discrete run saw the bullet on both sides of the frame's crossing, apart from the plate.
      EXPECT_GT(reference_distance(scene, i, c.plate, double(c.frame + 1) * scene.frame_time()), 0.0) << "bullet " << i;
    }
  }
  EXPECT_EQ(missed, scene.tunnelled_count());
  EXPECT_GT(scene.tunnelled_count(), 0) << "the default scene must show tunnelling";
  EXPECT_GT(scene.discrete_stats().hits, 0u);
  EXPECT_LT(scene.discrete_stats().hits, scene.continuous_stats().hits);
  EXPECT_EQ(scene.discrete_only_count(), 0);
}

TEST(DemoTunnelling, OtherSeedsAgreeWithTheReference) {
  for (std::uint64_t seed : {2ull, 7ull}) {
    TunnellingConfig config;
    config.seed = seed;
    config.bullets = 12;
    TunnellingScene scene(config);
    scene.run();
    for (int i = 0; i < config.bullets; ++i) {
      const ReferenceContact ref = reference_contact(scene, i, 2000);
      const tool::BulletOutcome& c = scene.continuous()[std::size_t(i)];
      if (ref.found) {
        EXPECT_TRUE(c.hit) << "seed " << seed << " bullet " << i;
        EXPECT_LE(c.time, ref.time + 1e-9) << "seed " << seed << " bullet " << i;
      } else if (c.hit) {
        EXPECT_LE(ref.least_distance, toi_tolerance()) << "seed " << seed << " bullet " << i;
      }
    }
  }
}

TEST(DemoTunnelling, SvgHasBothPanelsAndIsWellFormed) {
  const std::filesystem::path path =
      std::filesystem::temp_directory_path() / ("proxima-tunnelling-" + std::to_string(::getpid()) + ".svg");
  tool::TunnellingDemoOptions options;
  options.svg_path = path.string();
  std::ostringstream out;
  std::ostringstream err;
  ASSERT_EQ(tool::run_tunnelling_demo(options, out, err), 0) << err.str();
  std::ifstream file(path, std::ios::binary);
  std::stringstream buffer;
  buffer << file.rdbuf();
  const std::string svg = buffer.str();
  std::filesystem::remove(path);
  ASSERT_FALSE(svg.empty());
  EXPECT_EQ(svg.rfind("<svg", 0), 0u);
  EXPECT_TRUE(xml_tags_balanced(svg));
  EXPECT_EQ(count_of(svg, "<title>discrete panel</title>"), 1u);
  EXPECT_EQ(count_of(svg, "<title>continuous panel</title>"), 1u);
  EXPECT_NE(svg.find(">discrete (world, ccd off)"), std::string::npos);
  EXPECT_NE(svg.find(">continuous (world, ccd bullet)"), std::string::npos);
  // One group per bullet in each panel; the tunnelled ones say so.
  EXPECT_EQ(count_of(svg, ": discrete"), 24u);
  EXPECT_EQ(count_of(svg, ": continuous"), 24u);
  TunnellingScene scene(options.config);
  scene.run();
  EXPECT_EQ(count_of(svg, "(tunnelled)"), std::size_t(scene.tunnelled_count()));
  EXPECT_NE(svg.find("tunnelled: " + std::to_string(scene.tunnelled_count())), std::string::npos);
  EXPECT_GE(count_of(svg, "<polygon"), 10u);  // the plates, twice at least

  // The statistics.
  const std::string report = out.str();
  EXPECT_NE(report.find("24 bullets"), std::string::npos);
  EXPECT_NE(report.find("discrete (collision world, ccd off: contacts at each frame's poses): " +
                        std::to_string(scene.discrete_stats().hits) + " hits"),
            std::string::npos)
      << report;
  EXPECT_NE(report.find("continuous (collision world, ccd bullet: impacts over each frame's motion): " +
                        std::to_string(scene.continuous_stats().hits) + " hits"),
            std::string::npos)
      << report;
  EXPECT_NE(
      report.find("tunnelled (caught only by the continuous detector): " + std::to_string(scene.tunnelled_count())),
      std::string::npos);
  EXPECT_NE(report.find(" us per step"), std::string::npos);
  EXPECT_NE(report.find("picture: " + path.string()), std::string::npos);
  EXPECT_EQ(report.find("warning"), std::string::npos) << report;
}

TEST(DemoTunnelling, Deterministic) {
  TunnellingScene a(TunnellingConfig{});
  TunnellingScene b(TunnellingConfig{});
  a.run();
  b.run();
  ASSERT_EQ(a.continuous().size(), b.continuous().size());
  for (std::size_t i = 0; i < a.continuous().size(); ++i) {
    EXPECT_EQ(a.continuous()[i].hit, b.continuous()[i].hit);
    EXPECT_EQ(a.continuous()[i].time, b.continuous()[i].time);
    EXPECT_EQ(a.continuous()[i].stop, b.continuous()[i].stop);
    EXPECT_EQ(a.discrete()[i].stop, b.discrete()[i].stop);
  }
  EXPECT_EQ(tool::render_tunnelling_svg(a), tool::render_tunnelling_svg(b));
  EXPECT_EQ(without_timings(tool::tunnelling_report(a)), without_timings(tool::tunnelling_report(b)));
  // Running again gives the same answers.
  const std::string first = tool::render_tunnelling_svg(a);
  a.run();
  EXPECT_EQ(tool::render_tunnelling_svg(a), first);
  // Another seed gives another scene.
  TunnellingConfig other;
  other.seed = 2;
  TunnellingScene c(other);
  c.run();
  EXPECT_NE(tool::render_tunnelling_svg(c), first);
}

TEST(DemoTunnelling, CommandLine) {
  const std::filesystem::path path =
      std::filesystem::temp_directory_path() / ("proxima-tunnelling-cli-" + std::to_string(::getpid()) + ".svg");
  const test::CliRun run = test::run_cli("demo-tunnelling --svg '" + path.string() + "'");
  EXPECT_EQ(run.status, 0);
  EXPECT_NE(run.output.find("tunnelled (caught only by the continuous detector): "), std::string::npos) << run.output;
  EXPECT_TRUE(std::filesystem::exists(path));
  std::filesystem::remove(path);
  const test::CliRun quiet = test::run_cli("demo-tunnelling -q --frames 30 --bullets 5 --seed 3 --svg ''");
  EXPECT_EQ(quiet.status, 0);
  EXPECT_EQ(quiet.output, "");
  EXPECT_NE(test::run_cli("demo-tunnelling --frames -1 2>/dev/null").status, 0);
  EXPECT_NE(test::run_cli("demo-tunnelling --svg /nonexistent-directory/x.svg 2>/dev/null").status, 0);
  const test::CliRun help = test::run_cli("--help");
  EXPECT_NE(help.output.find("demo-tunnelling"), std::string::npos);
}

}  // namespace test_demo_tunnelling
}  // namespace proxima
