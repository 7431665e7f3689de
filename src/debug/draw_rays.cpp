// Emitters of rays and their hits (debug/draw_rays.hpp).
#include <proxima/debug/draw_rays.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

namespace proxima::debug {

namespace {

constexpr DrawTag kQueries{DrawLayer::Queries, 0};

struct HitView {
  Vec3 point;
  Vec3 normal;
};

void emit(DebugDraw& sink, const Ray& ray, Real max_t, std::span<const HitView> hits, Real farthest,
          const RayDrawOptions& options) {
  const Real extent = std::isfinite(max_t) ? max_t : Real(1);
  std::vector<DrawLine> lines;
  std::vector<DrawPoint> markers;
  if (hits.empty()) {
    lines.push_back({ray.origin, ray.at(extent), options.miss_color, kQueries});
  } else {
    lines.push_back({ray.origin, ray.at(farthest), options.ray_color, kQueries});
  }
  for (const HitView& h : hits) {
    markers.push_back({h.point, options.point_size, options.hit_color, kQueries});
    lines.push_back({h.point, h.point + h.normal * options.normal_length, options.hit_color, kQueries});
  }
  sink.draw_lines(lines);
  sink.draw_points(markers);
}

}  // namespace

void draw_ray(DebugDraw& sink, const Ray& ray, Real max_t, const std::optional<RayHit>& hit,
              const RayDrawOptions& options) {
  if (!hit) {
    emit(sink, ray, max_t, {}, Real(0), options);
    return;
  }
  const HitView view{hit->point, hit->normal};
  emit(sink, ray, max_t, {&view, 1}, hit->t, options);
}

void draw_world_hits(DebugDraw& sink, const Ray& ray, Real max_t, std::span<const WorldHit> hits,
                     const RayDrawOptions& options) {
  std::vector<HitView> views;
  Real farthest = Real(0);
  for (const WorldHit& h : hits) {
    views.push_back({h.point, h.normal});
    farthest = std::max(farthest, h.t);
  }
  emit(sink, ray, max_t, views, farthest, options);
}

}  // namespace proxima::debug
