// Emitters of a collision world (debug/draw_world.hpp).
#include <proxima/debug/draw_shapes.hpp>
#include <proxima/debug/draw_world.hpp>

#include <array>
#include <bit>
#include <vector>

namespace proxima::debug {

Rgba object_color(const ObjectDesc& object) { return object_color(object.kind, object.sensor, object.filter); }

Rgba object_color(ObjectKind kind, bool sensor, const CollisionFilter& filter) {
  static constexpr std::array<Rgba, 8> kLayerHues = {
      Rgba{70, 130, 230, 255}, Rgba{230, 150, 50, 255}, Rgba{170, 90, 220, 255}, Rgba{60, 190, 190, 255},
      Rgba{220, 90, 140, 255}, Rgba{150, 200, 70, 255}, Rgba{200, 180, 60, 255}, Rgba{120, 120, 230, 255}};
  if (sensor) return Rgba{60, 220, 90, 96};
  if (kind == ObjectKind::Static) return Rgba{150, 150, 150, 255};
  const int bit = filter.layer == 0 ? 0 : std::countr_zero(filter.layer);
  return kLayerHues[static_cast<std::size_t>(bit) % kLayerHues.size()];
}

void draw_world(DebugDraw& sink, const CollisionWorld& world, const WorldDrawOptions& options) {
  std::vector<DrawBox> boxes;
  for (const ObjectHandle handle : world.objects()) {
    const std::optional<ObjectDesc> desc = world.object(handle);
    if (!desc) continue;
    if (options.shapes) draw_shape(sink, desc->geometry, desc->pose, object_color(*desc), options.tessellation);
    if (options.bounds) {
      boxes.push_back(box_of(world.bounds(handle), object_color(*desc), DrawTag{DrawLayer::Bounds, 0}));
    }
  }
  if (options.bounds) sink.draw_boxes(boxes);
  if (!options.contacts) return;
  for (const WorldManifold& manifold : world.contacts()) draw_manifold(sink, manifold, options.contact);
}

}  // namespace proxima::debug
