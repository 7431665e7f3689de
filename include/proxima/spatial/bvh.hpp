#pragma once
/// @file bvh.hpp
/// Bvh: a binary bounding-volume hierarchy of axis-aligned boxes over a set of primitives
/// (triangles of a mesh, children of a compound), built by binned SAH, refitted after the
/// primitives move, traversed with a fixed stack and no allocation.
///
/// The builder takes spans of primitive boxes and centres (so it is independent of what
/// the primitives are); traversal is templated on a node test and a leaf callable.

#include <proxima/geometry/aabb.hpp>

#include <cstdint>
#include <span>
#include <vector>

namespace proxima {

/// One node: 32 bytes in single precision. Inner nodes have count == 0 and their children
/// at nodes()[first] and nodes()[first + 1]; leaves hold primitives()[first, first + count).
struct BvhNode {
  Vec3 min{Real(0)};        ///< box minimum corner (frame of the primitives)
  std::uint32_t first = 0;  ///< inner: index of the first child; leaf: first primitive slot
  Vec3 max{Real(0)};        ///< box maximum corner
  std::uint32_t count = 0;  ///< 0 for an inner node, else the number of primitives in the leaf

  /// True for a leaf.
  bool is_leaf() const { return count != 0; }
  /// The node's box.
  Aabb bounds() const { return {min, max}; }
};

/// How to build a Bvh.
struct BvhBuildOptions {
  std::uint32_t max_leaf_size = 4;  ///< a node with more primitives is always split (1..255)
  std::uint32_t bin_count = 16;     ///< SAH bins per axis (2..64)
  Real traversal_cost = Real(1);    ///< SAH cost of visiting a node, relative to ...
  Real primitive_cost = Real(1);    ///< ... the cost of testing one primitive
};

/// Shape statistics of a built Bvh.
struct BvhStats {
  std::uint32_t node_count = 0;  ///< nodes, inner and leaf
  std::uint32_t leaf_count = 0;  ///< leaves
  std::uint32_t depth = 0;       ///< longest root-to-leaf path in nodes (root alone = 1)
  Real sah_cost = Real(0);       ///< SAH cost of the tree relative to the root's area
};

/// A binary AABB hierarchy over primitives 0..n-1. Node 0 is the root.
class Bvh {
 public:
  /// Longest root-to-leaf path a build may produce; traversal stacks have this size.
  static constexpr std::uint32_t kMaxDepth = 64;

  /// An empty hierarchy (no primitive).
  Bvh() = default;

  /// Builds over `boxes` (one per primitive) with their `centers` (usually box centres;
  /// the split decisions use them), by binned SAH (Wald, "On fast construction of
  /// SAH-based bounding volume hierarchies", 2007). Both spans have the same size; an empty
  /// span gives an empty Bvh. Depth never exceeds kMaxDepth (the builder falls back to
  /// median splits where SAH would go deeper). O(n log n).
  static Bvh build(std::span<const Aabb> boxes, std::span<const Vec3> centers, const BvhBuildOptions& options = {});

  /// Recomputes every node box bottom-up from new primitive boxes (same count and order as
  /// at build). The topology is kept, so the tree stays valid but may loosen. O(n).
  void refit(std::span<const Aabb> boxes);

  /// The nodes; node 0 is the root (empty span when no primitive).
  std::span<const BvhNode> nodes() const { return nodes_; }
  /// Primitive indices in leaf order: leaves refer to ranges of this array.
  std::span<const std::uint32_t> primitives() const { return primitives_; }
  /// True when built over no primitive.
  bool empty() const { return nodes_.empty(); }
  /// Box of everything (empty box when no primitive).
  Aabb bounds() const { return nodes_.empty() ? Aabb::empty() : nodes_[0].bounds(); }
  /// Node count, depth and SAH cost.
  BvhStats stats() const;

  /// Depth-first traversal: `enter(const BvhNode&) -> bool` decides whether a node's subtree
  /// is visited; `leaf(std::uint32_t primitive) -> bool` is called for each primitive of a
  /// visited leaf and returns false to stop the whole traversal. Returns false when stopped.
  /// Fixed stack of kMaxDepth entries, no allocation.
  template <class Enter, class Leaf>
  bool traverse(Enter&& enter, Leaf&& leaf) const {
    if (nodes_.empty()) return true;
    std::uint32_t stack[kMaxDepth + 1];
    std::uint32_t top = 0;
    if (!enter(nodes_[0])) return true;
    stack[top++] = 0;
    while (top != 0) {
      const BvhNode& node = nodes_[stack[--top]];
      if (node.is_leaf()) {
        for (std::uint32_t i = node.first; i != node.first + node.count; ++i)
          if (!leaf(primitives_[i])) return false;
        continue;
      }
      for (std::uint32_t c = node.first + 1;; --c) {  // right pushed first, left popped first
        if (enter(nodes_[c])) stack[top++] = c;
        if (c == node.first) break;
      }
    }
    return true;
  }

  /// Branch and bound, nearest first: `gap(box)` is a lower bound on the answer for anything
  /// in a node's box (a distance, 0 when the box is reached); nodes are visited in
  /// increasing gap order (the nearer child first) and skipped while their gap exceeds
  /// `bound`, which `leaf(primitive)` may lower as it finds answers. A gap of 0 or less is
  /// never skipped: a box gap bounds separations, not penetration depths. Fixed stack.
  template <class Gap, class Leaf>
  void traverse_nearest(Gap&& gap, const Real& bound, Leaf&& leaf) const {
    if (nodes_.empty()) return;
    struct Entry {
      std::uint32_t node;
      Real gap;
    };
    Entry stack[kMaxDepth + 2];
    std::uint32_t top = 0;
    stack[top++] = {0, gap(nodes_[0].bounds())};
    const auto worth = [&](Real g) { return g <= bound || g <= Real(0); };
    while (top != 0) {
      const Entry e = stack[--top];
      if (!worth(e.gap)) continue;
      const BvhNode& node = nodes_[e.node];
      if (node.is_leaf()) {
        for (std::uint32_t i = node.first; i != node.first + node.count; ++i) leaf(primitives_[i]);
        continue;
      }
      const std::uint32_t l = node.first, r = node.first + 1;
      const Real gl = gap(nodes_[l].bounds()), gr = gap(nodes_[r].bounds());
      const bool left_first = gl <= gr;  // the nearer child is pushed last, popped first
      const Entry near{left_first ? l : r, left_first ? gl : gr};
      const Entry far{left_first ? r : l, left_first ? gr : gl};
      if (worth(far.gap)) stack[top++] = far;
      if (worth(near.gap)) stack[top++] = near;
    }
  }

 private:
  std::vector<BvhNode> nodes_;
  std::vector<std::uint32_t> primitives_;
};

}  // namespace proxima
