// Emitters of sweeps and times of impact (debug/draw_sweeps.hpp).
#include <proxima/debug/draw_shapes.hpp>
#include <proxima/debug/draw_sweeps.hpp>

#include <algorithm>
#include <vector>

namespace proxima::debug {

Rgba sweep_end_color(Rgba color) { return Rgba{color.r, color.g, color.b, static_cast<std::uint8_t>(color.a / 3)}; }

void draw_impact_point(DebugDraw& sink, const Vec3& point, const Vec3& normal, Real normal_length) {
  const DrawPoint marker{point, Real(6), Rgba{255, 40, 40, 255}, DrawTag{DrawLayer::Contacts, 0}};
  const DrawLine line{point, point + normal * normal_length, Rgba{255, 220, 0, 255}, DrawTag{DrawLayer::Normals, 0}};
  sink.draw_points({&marker, 1});
  sink.draw_lines({&line, 1});
}

void draw_sweep(DebugDraw& sink, ShapeRef shape, const Motion& motion, std::optional<Real> toi,
                const SweepDrawOptions& options) {
  const DrawTag tag{DrawLayer::Sweeps, 0};
  const DrawMesh mesh = tessellate(shape, options.tessellation);
  draw_mesh(sink, mesh, motion.at(Real(0)), sweep_end_color(options.color), tag);
  if (toi) draw_mesh(sink, mesh, motion.at(std::clamp(*toi, Real(0), Real(1))), options.color, tag);
  draw_mesh(sink, mesh, motion.at(Real(1)), sweep_end_color(options.color), tag);
  const int samples = std::clamp(options.path_samples, 1, 1024);
  std::vector<DrawLine> path;
  for (int i = 0; i < samples; ++i) {
    const Real t0 = Real(i) / Real(samples), t1 = Real(i + 1) / Real(samples);
    path.push_back({motion.at(t0).position, motion.at(t1).position, options.color, tag});
  }
  sink.draw_lines(path);
}

void draw_time_of_impact(DebugDraw& sink, ShapeRef shape_a, const Motion& motion_a, ShapeRef shape_b,
                         const Motion& motion_b, const ToiResult& result, Real normal_length,
                         const SweepDrawOptions& options) {
  const bool hit = result.status == CcdStatus::Hit || result.status == CcdStatus::InitiallyOverlapping;
  const std::optional<Real> toi = hit ? std::optional<Real>(result.toi) : std::nullopt;
  draw_sweep(sink, shape_a, motion_a, toi, options);
  SweepDrawOptions other = options;
  other.color = Rgba{160, 160, 160, options.color.a};
  draw_sweep(sink, shape_b, motion_b, toi, other);
  if (hit) draw_impact_point(sink, result.point, result.normal, normal_length);
}

}  // namespace proxima::debug
