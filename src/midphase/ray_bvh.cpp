/// @file ray_bvh.cpp
/// RayBvh::build: collapses a binary Bvh into 4-wide nodes (steps in ray_bvh.hpp).
///  1. A wide node starts from the binary node's two children (or the binary leaf itself
///     for a leaf root) and opens its inner child of largest surface area until it has four
///     children or only leaves.
///  2. Boxes are rounded outward to float; unused children get an empty (inverted) box.
///  3. Inner children are collapsed recursively, depth first (depth <= Bvh::kMaxDepth).

#include "midphase/ray_bvh.hpp"

#include <proxima/core/tolerance.hpp>

#include <algorithm>
#include <limits>

namespace proxima::detail {
namespace {

inline Real half_area(const BvhNode& n) {
  const Vec3 e = glm::max(n.max - n.min, Vec3(Real(0)));
  return e.x * e.y + e.y * e.z + e.z * e.x;
}

std::uint32_t collapse(std::span<const BvhNode> nodes, std::uint32_t b, std::vector<RayNode4>& out) {
  std::uint32_t slots[4];
  int n = 0;
  if (nodes[b].is_leaf()) {
    slots[n++] = b;
  } else {
    slots[n++] = nodes[b].first;
    slots[n++] = nodes[b].first + 1;
  }
  while (n < 4) {
    int pick = -1;
    Real best = Real(-1);
    for (int i = 0; i < n; ++i) {
      const BvhNode& s = nodes[slots[i]];
      if (s.is_leaf()) continue;
      const Real area = half_area(s);
      if (area > best) {
        best = area;
        pick = i;
      }
    }
    if (pick < 0) break;
    const std::uint32_t first = nodes[slots[pick]].first;
    slots[pick] = first;
    slots[n++] = first + 1;
  }
  const auto index = static_cast<std::uint32_t>(out.size());
  out.emplace_back();
  {
    RayNode4& w = out.back();
    constexpr float inf = std::numeric_limits<float>::infinity();
    for (int c = 0; c < 4; ++c) {
      w.child[c] = 0;
      w.count[c] = 0;
      for (int a = 0; a < 3; ++a) {
        w.box[2 * a][c] = inf;
        w.box[2 * a + 1][c] = -inf;
      }
    }
    for (int c = 0; c < n; ++c) {
      const BvhNode& s = nodes[slots[c]];
      for (int a = 0; a < 3; ++a) {
        w.box[2 * a][c] = round_down_float(s.min[a]);
        w.box[2 * a + 1][c] = round_up_float(s.max[a]);
      }
      if (s.is_leaf()) {
        w.child[c] = s.first;
        w.count[c] = static_cast<std::uint8_t>(s.count);
      }
    }
    std::fill(std::begin(w.padding), std::end(w.padding), std::uint8_t(0));
  }
  for (int c = 0; c < n; ++c) {
    if (nodes[slots[c]].is_leaf()) continue;
    const std::uint32_t child = collapse(nodes, slots[c], out);
    out[index].child[c] = child;  // `out` may have moved: index, not reference
  }
  return index;
}

}  // namespace

RayBvh RayBvh::build(const Bvh& bvh) {
  RayBvh r;
  if (bvh.empty()) return r;
  const Aabb box = bvh.bounds();
  for (int a = 0; a < 3; ++a)
    if (!(std::abs(box.min[a]) <= kRayBvhMaxCoordinate && std::abs(box.max[a]) <= kRayBvhMaxCoordinate)) return r;
  for (const BvhNode& n : bvh.nodes())
    if (n.is_leaf() && n.count > 255) return r;  // cannot happen (max_leaf_size <= 255)
  r.nodes.reserve(bvh.nodes().size() / 2 + 1);
  collapse(bvh.nodes(), 0, r.nodes);
  return r;
}

}  // namespace proxima::detail
