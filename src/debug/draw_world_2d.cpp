// Emitters of a 2D collision world (debug/draw_world_2d.hpp).
#include <proxima/debug/draw_contacts_2d.hpp>
#include <proxima/debug/draw_world.hpp>
#include <proxima/debug/draw_world_2d.hpp>

namespace proxima::debug {

Rgba object_color(const d2::ObjectDesc& object) { return object_color(object.kind, object.sensor, object.filter); }

void draw_world_2d(DebugDraw& sink, const d2::CollisionWorld& world, const World2DDrawOptions& options) {
  for (const d2::ObjectHandle handle : world.objects()) {
    const std::optional<d2::ObjectDesc> object = world.object(handle);
    if (!object) continue;
    const Rgba color = object_color(*object);
    if (options.shapes) draw_shape_2d(sink, object->shape, object->pose, color, options.shape);
    if (options.bounds) draw_bounds_2d(sink, object->shape, object->pose, color);
  }
  if (options.contacts) {
    for (const d2::WorldManifold& m : world.manifolds()) draw_manifold_2d(sink, m.manifold, options.contact);
  }
  if (options.impacts) {
    for (const d2::ImpactEvent& impact : world.events().impacts) draw_impact_2d(sink, impact, options.contact);
  }
}

}  // namespace proxima::debug
