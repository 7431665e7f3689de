/// @file shape_queries.cpp
/// Bounds and ray casts over any shape (ShapeRef).
///
/// Steps: a convex shape or a mesh answers with its own world_aabb / raycast (the ray mapped
/// into its local frame, the hit mapped back; a mesh hit names its triangle); a compound
/// maps the ray into its frame and walks its BVH front to back (children of a node ordered
/// by their slab entry parameter, subtrees whose entry is past the best hit so far
/// skipped), casting against each child at its local pose, nested compounds recursively.
/// Ordered BVH traversal as in Wald et al., "Interactive rendering with coherent ray
/// tracing" (2001); slab test of Kay and Kajiya (1986).
#include <proxima/geometry/raycast.hpp>
#include <proxima/shapes/shape_queries.hpp>

#include <type_traits>

namespace proxima {

Aabb world_aabb(ShapeRef shape, const Transform& pose) {
  return visit_shape(shape, [&](const auto& s) { return s.world_aabb(pose); });
}

namespace {

/// Closest hit in the compound's frame (ray and hit in that frame).
std::optional<RayHit> raycast_compound(const Compound& compound, const Ray& ray, Real max_t) {
  const Bvh& bvh = compound.bvh();
  const auto nodes = bvh.nodes();
  const auto prims = bvh.primitives();
  const auto kids = compound.children();
  std::optional<RayHit> best;
  Real best_t = max_t;
  if (nodes.empty()) return best;
  const auto root = geometry::ray_aabb(ray, best_t, nodes[0].bounds());
  if (!root) return best;
  struct Entry {
    std::uint32_t node;
    Real t;
  };
  Entry stack[Bvh::kMaxDepth + 2];
  std::uint32_t top = 0;
  stack[top++] = {0, root->t};
  while (top != 0) {
    const Entry e = stack[--top];
    if (e.t > best_t) continue;
    const BvhNode& node = nodes[e.node];
    if (node.is_leaf()) {
      for (std::uint32_t i = node.first; i != node.first + node.count; ++i) {
        const std::uint32_t c = prims[i];
        const CompoundChild& child = kids[c];
        auto hit = raycast(ShapeRef(child.shape), child.pose, ray, best_t);
        if (hit && (!best || hit->t < best_t || (hit->t == best_t && c < best->sub.child))) {
          best = hit;
          best->sub.child = c;
          best_t = hit->t;
        }
      }
      continue;
    }
    const std::uint32_t l = node.first, r = node.first + 1;
    const auto hl = geometry::ray_aabb(ray, best_t, nodes[l].bounds());
    const auto hr = geometry::ray_aabb(ray, best_t, nodes[r].bounds());
    // Push the farther first so the nearer pops first.
    if (hl && hr) {
      if (hl->t <= hr->t) {
        stack[top++] = {r, hr->t};
        stack[top++] = {l, hl->t};
      } else {
        stack[top++] = {l, hl->t};
        stack[top++] = {r, hr->t};
      }
    } else if (hl) {
      stack[top++] = {l, hl->t};
    } else if (hr) {
      stack[top++] = {r, hr->t};
    }
  }
  return best;
}

}  // namespace

std::optional<RayHit> raycast(ShapeRef shape, const Transform& pose, const Ray& ray, Real max_t) {
  const Ray local = ray.to_local(pose);
  std::optional<RayHit> hit = visit_shape(shape, [&](const auto& s) -> std::optional<RayHit> {
    if constexpr (std::is_same_v<std::decay_t<decltype(s)>, Compound>)
      return raycast_compound(s, local, max_t);
    else
      return s.raycast(local, max_t);
  });
  if (!hit) return std::nullopt;
  return hit->to_world(pose);
}

}  // namespace proxima
