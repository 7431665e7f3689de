// Emitters of contact points (debug/draw_contacts.hpp).
#include <proxima/debug/draw_contacts.hpp>

#include <algorithm>
#include <cstdio>
#include <vector>

namespace proxima::debug {

namespace {

std::string depth_label(Real depth) {
  char text[48];
  std::snprintf(text, sizeof text, "depth=%.4g", static_cast<double>(depth));
  return text;
}

}  // namespace

void draw_contact_points(DebugDraw& sink, std::span<const ContactPoint> points, const ContactDrawOptions& options) {
  const DrawTag contacts{DrawLayer::Contacts, 0};
  const DrawTag normals{DrawLayer::Normals, 0};
  std::vector<DrawPoint> markers;
  std::vector<DrawLine> lines;
  std::vector<DrawText> labels;
  for (const ContactPoint& p : points) {
    const Vec3 mid = (p.point_a + p.point_b) * Real(0.5);
    markers.push_back({p.point_a, options.point_size, options.point_color, contacts});
    markers.push_back({p.point_b, options.point_size, options.point_color, contacts});
    lines.push_back({p.point_a, p.point_b, options.point_color, contacts});
    lines.push_back({mid, mid + p.normal * options.normal_length, options.normal_color, normals});
    if (options.labels) labels.push_back({mid, depth_label(p.depth), options.point_color, contacts});
  }
  sink.draw_points(markers);
  sink.draw_lines(lines);
  if (options.labels) sink.draw_texts(labels);
}

void draw_manifold(DebugDraw& sink, const ContactManifold& manifold, const ContactDrawOptions& options) {
  const int count = std::clamp(manifold.count, 0, kMaxContactPoints);
  draw_contact_points(sink, std::span(manifold.points).first(static_cast<std::size_t>(count)), options);
}

void draw_manifold(DebugDraw& sink, const WorldManifold& manifold, const ContactDrawOptions& options) {
  const int count = std::clamp(manifold.count, 0, kMaxContactPoints);
  std::vector<ContactPoint> points;
  for (int i = 0; i < count; ++i) points.push_back(manifold.points[static_cast<std::size_t>(i)].contact);
  draw_contact_points(sink, points, options);
}

}  // namespace proxima::debug
