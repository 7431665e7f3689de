// Emitters of shapes, bounds and hierarchy nodes (debug/draw_shapes.hpp): each builds one
// array of primitives and hands it to the sink in one call.
#include <proxima/debug/draw_shapes.hpp>
#include <proxima/shapes/shape.hpp>
#include <proxima/shapes/shape_queries.hpp>

#include <array>
#include <utility>
#include <vector>

namespace proxima::debug {

Rgba level_color(int level) {
  static constexpr std::array<Rgba, 8> kPalette = {
      Rgba{230, 25, 75, 255},  Rgba{60, 180, 75, 255},  Rgba{0, 130, 200, 255},  Rgba{245, 130, 48, 255},
      Rgba{145, 30, 180, 255}, Rgba{70, 240, 240, 255}, Rgba{240, 50, 230, 255}, Rgba{128, 128, 0, 255}};
  return kPalette[static_cast<std::size_t>(level < 0 ? 0 : level) % kPalette.size()];
}

DrawBox box_of(const Aabb& box, Rgba color, DrawTag tag) {
  return DrawBox{box.center(), box.half_extents(), kIdentityQuat, color, tag};
}

void draw_mesh(DebugDraw& sink, const DrawMesh& mesh, const Transform& pose, Rgba color, DrawTag tag) {
  std::vector<DrawTriangle> triangles;
  triangles.reserve(mesh.triangle_count());
  for (std::size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
    triangles.push_back({pose.apply(mesh.positions[mesh.indices[i]]), pose.apply(mesh.positions[mesh.indices[i + 1]]),
                         pose.apply(mesh.positions[mesh.indices[i + 2]]), color, tag});
  }
  sink.draw_triangles(triangles);
}

void draw_shape(DebugDraw& sink, ShapeRef shape, const Transform& pose, Rgba color,
                const TessellationOptions& options) {
  draw_mesh(sink, tessellate(shape, options), pose, color, DrawTag{DrawLayer::Shapes, 0});
}

void draw_bounds(DebugDraw& sink, ShapeRef shape, const Transform& pose, Rgba color) {
  const DrawBox box = box_of(world_aabb(shape, pose), color, DrawTag{DrawLayer::Bounds, 0});
  sink.draw_boxes({&box, 1});
}

void draw_bvh(DebugDraw& sink, const Bvh& bvh, const Transform& pose, int min_level, int max_level) {
  if (bvh.empty()) return;
  std::vector<DrawBox> boxes;
  std::vector<std::pair<std::uint32_t, int>> stack{{0u, 0}};
  while (!stack.empty()) {
    const auto [index, depth] = stack.back();
    stack.pop_back();
    const BvhNode& node = bvh.nodes()[index];
    if (depth >= min_level && depth <= max_level) {
      const auto tag = DrawTag{DrawLayer::Bvh, static_cast<std::uint16_t>(depth)};
      const Aabb box = node.bounds();
      boxes.push_back({pose.apply(box.center()), box.half_extents(), pose.rotation, level_color(depth), tag});
    }
    if (node.is_leaf() || depth >= max_level) continue;
    stack.emplace_back(node.first + 1, depth + 1);
    stack.emplace_back(node.first, depth + 1);
  }
  sink.draw_boxes(boxes);
}

void draw_shape_bvh(DebugDraw& sink, ShapeRef shape, const Transform& pose, int min_level, int max_level) {
  if (shape.type() == ShapeType::TriangleMesh)
    draw_bvh(sink, shape.as<TriangleMesh>().bvh(), pose, min_level, max_level);
  if (shape.type() == ShapeType::Compound) draw_bvh(sink, shape.as<Compound>().bvh(), pose, min_level, max_level);
}

void draw_broadphase(DebugDraw& sink, const DynamicAabbTree& tree, int min_level, int max_level) {
  std::vector<DrawBox> boxes;
  tree.visit_nodes([&](const DynamicAabbTree::NodeView& node) {
    if (node.depth < min_level || node.depth > max_level) return;
    const auto tag = DrawTag{DrawLayer::BroadPhase, static_cast<std::uint16_t>(node.depth)};
    boxes.push_back(box_of(node.box, level_color(node.depth), tag));
  });
  sink.draw_boxes(boxes);
}

void draw_proxy_boxes(DebugDraw& sink, std::span<const Aabb> boxes, Rgba color) {
  std::vector<DrawBox> out;
  out.reserve(boxes.size());
  for (const Aabb& box : boxes) out.push_back(box_of(box, color, DrawTag{DrawLayer::BroadPhase, 0}));
  sink.draw_boxes(out);
}

}  // namespace proxima::debug
