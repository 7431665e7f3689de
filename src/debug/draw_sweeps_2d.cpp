// Emitters of 2D sweeps and times of impact (debug/draw_sweeps_2d.hpp).
//
// Steps of a sweep: the shape drawn at t = 0, at the impact, at t = 1 (draw_shape_2d on the
// Sweeps layer, the ends faded), then its origin's path sampled along the motion.
#include <proxima/debug/draw_shapes_2d.hpp>
#include <proxima/debug/draw_sweeps_2d.hpp>

#include <algorithm>
#include <vector>

namespace proxima::debug {

namespace {

constexpr DrawTag kSweeps{DrawLayer::Sweeps, 0};

}  // namespace

void draw_sweep_2d(DebugDraw& sink, const d2::Shape& shape, const d2::Motion& motion, std::optional<Real> toi,
                   const SweepDrawOptions& options) {
  Shape2DDrawOptions look;
  look.segments = options.tessellation.segments;
  look.layer = DrawLayer::Sweeps;
  look.chain_normal_length = Real(0);
  draw_shape_2d(sink, shape, motion.at(Real(0)), sweep_end_color(options.color), look);
  if (toi) draw_shape_2d(sink, shape, motion.at(std::clamp(*toi, Real(0), Real(1))), options.color, look);
  draw_shape_2d(sink, shape, motion.at(Real(1)), sweep_end_color(options.color), look);
  const int samples = std::clamp(options.path_samples, 1, 1024);
  std::vector<DrawLine> path;
  for (int i = 0; i < samples; ++i) {
    const Real t0 = Real(i) / Real(samples), t1 = Real(i + 1) / Real(samples);
    path.push_back({plane_point(motion.at(t0).position), plane_point(motion.at(t1).position), options.color, kSweeps});
  }
  sink.draw_lines(path);
}

void draw_time_of_impact_2d(DebugDraw& sink, const d2::Shape& shape_a, const d2::Motion& motion_a,
                            const d2::Shape& shape_b, const d2::Motion& motion_b, const d2::ToiResult& result,
                            Real normal_length, const SweepDrawOptions& options) {
  const bool hit = result.status == d2::CcdStatus::Hit || result.status == d2::CcdStatus::InitiallyOverlapping;
  const std::optional<Real> toi = hit ? std::optional<Real>(result.toi) : std::nullopt;
  draw_sweep_2d(sink, shape_a, motion_a, toi, options);
  SweepDrawOptions other = options;
  other.color = Rgba{160, 160, 160, options.color.a};
  draw_sweep_2d(sink, shape_b, motion_b, toi, other);
  if (hit) draw_impact_point(sink, plane_point(result.point), plane_point(result.normal), normal_length);
}

}  // namespace proxima::debug
