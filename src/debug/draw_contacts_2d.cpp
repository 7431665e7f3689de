// Emitters of 2D contacts (debug/draw_contacts_2d.hpp): the points are lifted to z = 0 and
// drawn by the 3D emitter, so 2D and 3D manifolds look alike.
#include <proxima/debug/draw_contacts_2d.hpp>
#include <proxima/debug/draw_shapes_2d.hpp>

#include <algorithm>
#include <vector>

namespace proxima::debug {

void draw_manifold_2d(DebugDraw& sink, const d2::Manifold& manifold, const ContactDrawOptions& options) {
  const int count = std::clamp(manifold.count, 0, d2::kMaxManifoldPoints);
  std::vector<ContactPoint> points;
  for (int i = 0; i < count; ++i) {
    const d2::ContactPoint& p = manifold.points[static_cast<std::size_t>(i)];
    ContactPoint lifted;
    lifted.point_a = plane_point(p.point_a);
    lifted.point_b = plane_point(p.point_b);
    lifted.normal = plane_point(manifold.normal);
    lifted.depth = p.depth;
    points.push_back(lifted);
  }
  draw_contact_points(sink, points, options);
}

void draw_impact_2d(DebugDraw& sink, const d2::ImpactEvent& impact, const ContactDrawOptions& options) {
  const Vec3 at = plane_point(impact.point);
  const DrawPoint marker{at, options.point_size, options.point_color, DrawTag{DrawLayer::Contacts, 0}};
  const DrawLine normal{at, at + plane_point(impact.normal) * options.normal_length, options.normal_color,
                        DrawTag{DrawLayer::Normals, 0}};
  sink.draw_points({&marker, 1});
  sink.draw_lines({&normal, 1});
}

}  // namespace proxima::debug
