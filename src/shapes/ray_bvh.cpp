/// @file ray_bvh.cpp
/// RayBvh::build: collapses a binary Bvh into 4-wide nodes (steps in ray_bvh.hpp).
///  1. One reverse pass over the binary nodes gives each subtree's slot range in
///     Bvh::primitives() (a subtree's leaves are contiguous there: the builder partitions
///     in place).
///  2. A wide node starts from the binary node's two children (or the binary leaf itself
///     for a leaf root) and opens its inner child of largest surface area until it has four
///     children or only "leaves". A subtree of at most kMergeBelow triangles counts as one
///     leaf (its range becomes one wide leaf of up to two four-triangle blocks: fewer, fuller
///     nodes for the SIMD triangle rejection).
///  3. Boxes are rounded outward to float; unused children get an empty (inverted) box.
///  4. Inner children are collapsed recursively, depth first (depth <= Bvh::kMaxDepth).

#include "shapes/ray_bvh.hpp"

#include <proxima/core/tolerance.hpp>

#include <algorithm>
#include <limits>

namespace proxima::detail {
namespace {

/// Subtrees of at most this many triangles become one wide leaf.
constexpr std::uint32_t kMergeBelow = 8;

inline Real half_area(const BvhNode& n) {
  const Vec3 e = glm::max(n.max - n.min, Vec3(Real(0)));
  return e.x * e.y + e.y * e.z + e.z * e.x;
}

class Collapser {
 public:
  Collapser(const Bvh& bvh, std::span<const std::array<Vec3, 3>> corners, RayBvh& out)
      : nodes_(bvh.nodes()), corners_(corners), out_(out), first_(nodes_.size()), count_(nodes_.size()) {
    for (std::size_t i = nodes_.size(); i-- > 0;) {  // children have larger indices
      const BvhNode& n = nodes_[i];
      if (n.is_leaf()) {
        first_[i] = n.first;
        count_[i] = n.count;
      } else {
        first_[i] = first_[n.first];
        count_[i] = count_[n.first] + count_[n.first + 1];
      }
    }
  }

  /// True when binary node b becomes one wide leaf.
  bool is_leaf(std::uint32_t b) const { return nodes_[b].is_leaf() || count_[b] <= kMergeBelow; }

  std::uint32_t collapse(std::uint32_t b) {
    std::uint32_t slots[4];
    int n = 0;
    if (is_leaf(b)) {
      slots[n++] = b;
    } else {
      slots[n++] = nodes_[b].first;
      slots[n++] = nodes_[b].first + 1;
    }
    while (n < 4) {
      int pick = -1;
      Real best = Real(-1);
      for (int i = 0; i < n; ++i) {
        if (is_leaf(slots[i])) continue;
        const Real area = half_area(nodes_[slots[i]]);
        if (area > best) {
          best = area;
          pick = i;
        }
      }
      if (pick < 0) break;
      const std::uint32_t first = nodes_[slots[pick]].first;
      slots[pick] = first;
      slots[n++] = first + 1;
    }
    const auto index = static_cast<std::uint32_t>(out_.nodes.size());
    RayNode4 w{};
    constexpr float inf = std::numeric_limits<float>::infinity();
    for (int c = 0; c < 4; ++c) {
      for (int a = 0; a < 3; ++a) {
        w.box[2 * a][c] = inf;
        w.box[2 * a + 1][c] = -inf;
      }
    }
    for (int c = 0; c < n; ++c) {
      const BvhNode& s = nodes_[slots[c]];
      for (int a = 0; a < 3; ++a) {
        w.box[2 * a][c] = round_down_float(s.min[a]);
        w.box[2 * a + 1][c] = round_up_float(s.max[a]);
      }
      if (is_leaf(slots[c])) {
        w.child[c] = add_blocks(first_[slots[c]], count_[slots[c]]);
        w.count[c] = static_cast<std::uint8_t>(count_[slots[c]]);
      }
    }
    out_.nodes.push_back(w);
    for (int c = 0; c < n; ++c) {
      if (is_leaf(slots[c])) continue;
      const std::uint32_t child = collapse(slots[c]);
      out_.nodes[index].child[c] = child;  // the vector may have moved: index, not reference
    }
    return index;
  }

 private:
  /// Appends the blocks of the leaf over slots [first, first + count); returns the first.
  std::uint32_t add_blocks(std::uint32_t first, std::uint32_t count) {
    const auto index = static_cast<std::uint32_t>(out_.blocks.size());
    for (std::uint32_t s = 0; s < count; s += 4) {
      TriangleBlock4& b = out_.blocks.emplace_back();
      b.slot = first + s;
      b.count = std::min<std::uint32_t>(4, count - s);
      for (std::uint32_t lane = 0; lane < 4; ++lane)
        for (int j = 0; j < 3; ++j)
          for (int a = 0; a < 3; ++a) b.v[j][a][lane] = lane < b.count ? corners_[first + s + lane][j][a] : Real(0);
    }
    return index;
  }

  std::span<const BvhNode> nodes_;
  std::span<const std::array<Vec3, 3>> corners_;
  RayBvh& out_;
  std::vector<std::uint32_t> first_;  // first slot of each binary subtree
  std::vector<std::uint32_t> count_;  // triangles of each binary subtree
};

}  // namespace

RayBvh RayBvh::build(const Bvh& bvh, std::span<const std::array<Vec3, 3>> corners) {
  RayBvh r;
  if (bvh.empty() || corners.size() != bvh.primitives().size()) return r;
  const Aabb box = bvh.bounds();
  for (int a = 0; a < 3; ++a)
    if (!(std::abs(box.min[a]) <= kRayBvhMaxCoordinate && std::abs(box.max[a]) <= kRayBvhMaxCoordinate)) return r;
  for (const BvhNode& n : bvh.nodes())
    if (n.is_leaf() && n.count > 255) return r;  // cannot happen (max_leaf_size <= 255)
  r.nodes.reserve(bvh.nodes().size() / 2 + 1);
  r.blocks.reserve(corners.size() / 2 + 1);
  Collapser(bvh, corners, r).collapse(0);
  return r;
}

}  // namespace proxima::detail
