/// @file dynamic_aabb_tree.cpp
/// DynamicAabbTree: two pooled binary AABB trees (static, moving) with fat leaves.
///
/// Steps:
/// 1. insert: make the fat box, find the SAH-best sibling by branch and bound (the cost of a
///    sibling is the area of the new parent plus the area growth it inherits from its
///    ancestors; a subtree is skipped when its lower bound cannot beat the best found), link a
///    new parent, then walk up refitting boxes and heights and applying the best area-reducing
///    rotation at each ancestor (child <-> grandchild or grandchild <-> grandchild swap).
/// 2. update: O(1) while the new box fits in the fat box (and the fat box is not more than twice
///    too large); otherwise remove and reinsert.
/// 3. rebuild: top-down binned SAH over the leaves' fat boxes (16 bins, 3 axes), nodes emitted
///    in depth-first order for locality.
/// 4. find_pairs: simultaneous descent of node pairs (moving x moving, moving x static) with a
///    fixed stack, splitting the node of larger area; leaf pairs test the real boxes and filters.
///    An executor of several threads runs the top node pairs as tasks; each chunk of tasks
///    keeps its own output; results are sorted.
/// References: E. Catto, Box2D v3 dynamic_tree.c (design); J. Bittner et al. 2013 (insertion
/// search); A. Kopta et al. 2012 (rotations); I. Wald 2007 (binned SAH); C. Ericson,
/// Real-Time Collision Detection, 6.2 and 6.5.

#include <proxima/broadphase/detail/query_support.hpp>
#include <proxima/broadphase/dynamic_aabb_tree.hpp>
#include <proxima/broadphase/pair_tracker.hpp>
#include <proxima/core/tolerance.hpp>
#include <proxima/geometry/raycast.hpp>

#include <algorithm>
#include <array>
#include <utility>

#include "broadphase/batch_update_check.hpp"

namespace proxima {

namespace {

constexpr int kBins = 16;
constexpr int kMaxBuildDepth = 64;
constexpr std::size_t kAllAxesBelow = 4096;
constexpr std::size_t kBinnedBelow = 16384;

/// Closed box overlap without short-circuit branches (the six comparisons are unpredictable in
/// tree traversal; evaluating all of them is cheaper than mispredicting).
inline bool overlap(const Aabb& a, const Aabb& b) {
  return static_cast<bool>(static_cast<int>(a.min.x <= b.max.x) & static_cast<int>(b.min.x <= a.max.x) &
                           static_cast<int>(a.min.y <= b.max.y) & static_cast<int>(b.min.y <= a.max.y) &
                           static_cast<int>(a.min.z <= b.max.z) & static_cast<int>(b.min.z <= a.max.z));
}

struct BuildItem {
  Aabb box;   ///< fat box
  Aabb real;  ///< the proxy's box (carried along to avoid random reads when writing leaves)
  Vec3 centre;
  ProxyId id;
};

}  // namespace

DynamicAabbTree::DynamicAabbTree(const DynamicAabbTreeConfig& config) : config_(config) {
  if (!(config_.margin_fraction >= Real(0))) config_.margin_fraction = Real(0);
  if (!(config_.refit_margin_fraction >= Real(0))) config_.refit_margin_fraction = Real(0);
  if (!(config_.margin_min >= Real(0))) config_.margin_min = Real(0);
}

// ---- pool ---------------------------------------------------------------------------------

std::uint32_t DynamicAabbTree::allocate(Tree& tree) {
  std::uint32_t index;
  if (tree.free_list != kNull) {
    index = tree.free_list;
    tree.free_list = tree.nodes[index].parent;
  } else {
    index = static_cast<std::uint32_t>(tree.nodes.size());
    tree.nodes.emplace_back();
    tree.real.emplace_back();
  }
  tree.nodes[index] = Node{};
  ++tree.in_use;
  return index;
}

void DynamicAabbTree::release(Tree& tree, std::uint32_t index) {
  Node& n = tree.nodes[index];
  n.child1 = kNull;
  n.child2 = kNull;
  n.height = -1;
  n.parent = tree.free_list;
  tree.free_list = index;
  --tree.in_use;
}

// ---- insertion, removal, rotations --------------------------------------------------------

void DynamicAabbTree::refit_up(Tree& tree, std::uint32_t index) {
  while (index != kNull) {
    Node& n = tree.nodes[index];
    const Node& c1 = tree.nodes[n.child1];
    const Node& c2 = tree.nodes[n.child2];
    n.box = merge(c1.box, c2.box);
    n.height = 1 + std::max(c1.height, c2.height);
    index = n.parent;
  }
}

void DynamicAabbTree::insert_leaf(Tree& tree, std::uint32_t leaf) {
  ++tree.leaves;
  tree.order_valid = false;
  if (tree.root == kNull) {
    tree.root = leaf;
    tree.nodes[leaf].parent = kNull;
    return;
  }
  const Aabb box = tree.nodes[leaf].box;
  const Real box_area = box.surface_area();

  // Branch and bound over the SAH insertion cost.
  std::uint32_t best = tree.root;
  Real best_cost = merge(tree.nodes[tree.root].box, box).surface_area();
  struct Entry {
    std::uint32_t node;
    Real inherited;
  };
  detail::TraversalStack<Entry, 256> stack;
  stack.push({tree.root, Real(0)});
  while (!stack.empty()) {
    const Entry e = stack.pop();
    const Node& n = tree.nodes[e.node];
    const Real direct = merge(n.box, box).surface_area();
    const Real cost = direct + e.inherited;
    if (cost < best_cost) {
      best_cost = cost;
      best = e.node;
    }
    if (n.is_leaf()) continue;
    const Real inherited = e.inherited + direct - n.box.surface_area();
    if (box_area + inherited < best_cost) {
      stack.push({n.child1, inherited});
      stack.push({n.child2, inherited});
    }
  }

  const std::uint32_t sibling = best;
  const std::uint32_t parent = allocate(tree);  // may reallocate: no references held above
  const std::uint32_t old_parent = tree.nodes[sibling].parent;
  Node& p = tree.nodes[parent];
  p.parent = old_parent;
  p.box = merge(tree.nodes[sibling].box, box);
  p.child1 = sibling;
  p.child2 = leaf;
  p.height = tree.nodes[sibling].height + 1;
  if (old_parent != kNull) {
    Node& op = tree.nodes[old_parent];
    (op.child1 == sibling ? op.child1 : op.child2) = parent;
  } else {
    tree.root = parent;
  }
  tree.nodes[sibling].parent = parent;
  tree.nodes[leaf].parent = parent;

  std::uint32_t index = parent;
  while (index != kNull) {
    Node& n = tree.nodes[index];
    n.box = merge(tree.nodes[n.child1].box, tree.nodes[n.child2].box);
    n.height = 1 + std::max(tree.nodes[n.child1].height, tree.nodes[n.child2].height);
    if (config_.rotations) rotate(tree, index);
    index = tree.nodes[index].parent;
  }
}

void DynamicAabbTree::remove_leaf(Tree& tree, std::uint32_t leaf) {
  --tree.leaves;
  tree.order_valid = false;
  if (leaf == tree.root) {
    tree.root = kNull;
    return;
  }
  const std::uint32_t parent = tree.nodes[leaf].parent;
  const std::uint32_t grand = tree.nodes[parent].parent;
  const std::uint32_t sibling =
      tree.nodes[parent].child1 == leaf ? tree.nodes[parent].child2 : tree.nodes[parent].child1;
  if (grand != kNull) {
    Node& g = tree.nodes[grand];
    (g.child1 == parent ? g.child1 : g.child2) = sibling;
    tree.nodes[sibling].parent = grand;
    release(tree, parent);
    refit_up(tree, grand);
  } else {
    tree.root = sibling;
    tree.nodes[sibling].parent = kNull;
    release(tree, parent);
  }
  tree.nodes[leaf].parent = kNull;
}

void DynamicAabbTree::rotate(Tree& tree, std::uint32_t index) {
  std::vector<Node>& nodes = tree.nodes;
  const std::uint32_t b = nodes[index].child1;
  const std::uint32_t c = nodes[index].child2;
  const bool b_internal = !nodes[b].is_leaf();
  const bool c_internal = !nodes[c].is_leaf();
  if (!b_internal && !c_internal) return;

  // Candidate swaps (x, y): x and y exchange places; cost is the change of summed area.
  std::uint32_t best_x = kNull;
  std::uint32_t best_y = kNull;
  Real best_diff = Real(0);
  auto consider = [&](std::uint32_t x, std::uint32_t y, Real diff) {
    if (diff < best_diff) {
      best_diff = diff;
      best_x = x;
      best_y = y;
    }
  };
  if (c_internal) {
    const std::uint32_t f = nodes[c].child1;
    const std::uint32_t g = nodes[c].child2;
    const Real area_c = nodes[c].box.surface_area();
    consider(b, f, merge(nodes[b].box, nodes[g].box).surface_area() - area_c);
    consider(b, g, merge(nodes[b].box, nodes[f].box).surface_area() - area_c);
  }
  if (b_internal) {
    const std::uint32_t d = nodes[b].child1;
    const std::uint32_t e = nodes[b].child2;
    const Real area_b = nodes[b].box.surface_area();
    consider(c, d, merge(nodes[c].box, nodes[e].box).surface_area() - area_b);
    consider(c, e, merge(nodes[c].box, nodes[d].box).surface_area() - area_b);
  }
  if (b_internal && c_internal) {
    const std::uint32_t d = nodes[b].child1;
    const std::uint32_t e = nodes[b].child2;
    const std::uint32_t f = nodes[c].child1;
    const std::uint32_t g = nodes[c].child2;
    const Real base = nodes[b].box.surface_area() + nodes[c].box.surface_area();
    consider(
        d, f,
        merge(nodes[f].box, nodes[e].box).surface_area() + merge(nodes[d].box, nodes[g].box).surface_area() - base);
    consider(
        d, g,
        merge(nodes[g].box, nodes[e].box).surface_area() + merge(nodes[f].box, nodes[d].box).surface_area() - base);
  }
  if (best_x == kNull) return;

  // Exchange best_x and best_y under their parents, then refit the lower parents.
  const std::uint32_t px = nodes[best_x].parent;
  const std::uint32_t py = nodes[best_y].parent;
  (nodes[px].child1 == best_x ? nodes[px].child1 : nodes[px].child2) = best_y;
  (nodes[py].child1 == best_y ? nodes[py].child1 : nodes[py].child2) = best_x;
  nodes[best_x].parent = py;
  nodes[best_y].parent = px;
  for (const std::uint32_t n : {b, c}) {
    Node& m = nodes[n];
    if (m.is_leaf()) continue;
    m.box = merge(nodes[m.child1].box, nodes[m.child2].box);
    m.height = 1 + std::max(nodes[m.child1].height, nodes[m.child2].height);
  }
  // b and c may have moved below each other's place; index keeps the same two children slots.
  Node& a = nodes[index];
  a.height = 1 + std::max(nodes[a.child1].height, nodes[a.child2].height);
}

// ---- fat boxes ------------------------------------------------------------------------------

Aabb DynamicAabbTree::make_fat(const Aabb& box, ProxyKind kind) const {
  if (kind == ProxyKind::Static) return box;
  const Vec3 e = box.extents();
  const Real margin = std::max(config_.margin_min, config_.margin_fraction * std::max(e.x, std::max(e.y, e.z)));
  Aabb fat = box.inflated(margin);
  // Keep fat boxes finite and within range even for boxes near kMaxCoordinate.
  fat.min = glm::max(fat.min, Vec3(-kMaxCoordinate));
  fat.max = glm::min(fat.max, Vec3(kMaxCoordinate));
  return fat;
}

bool DynamicAabbTree::needs_reinsert(const Proxy& p, const Aabb& fat) const {
  if (!fat.contains(p.box)) return true;
  if (p.kind == ProxyKind::Static) return fat.min != p.box.min || fat.max != p.box.max;
  // A fat box more than twice the size the new box would get is too loose: refresh it.
  const Aabb ideal = make_fat(p.box, p.kind);
  const Vec3 fe = fat.extents();
  const Vec3 ie = ideal.extents();
  return (fe.x + fe.y + fe.z) > Real(2) * (ie.x + ie.y + ie.z);
}

void DynamicAabbTree::reinsert(Proxy& p) {
  Tree& tree = tree_of(p.kind);
  remove_leaf(tree, p.leaf);
  tree.nodes[p.leaf].box = make_fat(p.box, p.kind);
  insert_leaf(tree, p.leaf);
}

// ---- public edits ---------------------------------------------------------------------------

BroadPhaseStatus DynamicAabbTree::insert(ProxyId id, const Aabb& box, ProxyKind kind, ProxyFilter filter) {
  const BroadPhaseStatus s = check_box(box);
  if (s != BroadPhaseStatus::Ok) return s;
  if (id < proxies_.size() && proxies_[id].leaf != kNull) return BroadPhaseStatus::DuplicateId;
  if (id >= proxies_.size()) proxies_.resize(static_cast<std::size_t>(id) + 1);
  Tree& tree = tree_of(kind);
  const std::uint32_t leaf = allocate(tree);
  tree.nodes[leaf].box = make_fat(box, kind);
  tree.nodes[leaf].child2 = id;
  tree.real[leaf] = box;
  Proxy& p = proxies_[id];
  p.box = box;
  p.filter = filter;
  p.kind = kind;
  p.leaf = leaf;
  insert_leaf(tree, leaf);
  ++count_;
  return BroadPhaseStatus::Ok;
}

BroadPhaseStatus DynamicAabbTree::remove(ProxyId id) {
  if (id >= proxies_.size() || proxies_[id].leaf == kNull) return BroadPhaseStatus::UnknownId;
  Proxy& p = proxies_[id];
  Tree& tree = tree_of(p.kind);
  remove_leaf(tree, p.leaf);
  release(tree, p.leaf);
  p = Proxy{};
  --count_;
  return BroadPhaseStatus::Ok;
}

BroadPhaseStatus DynamicAabbTree::update(ProxyId id, const Aabb& box) {
  if (id >= proxies_.size() || proxies_[id].leaf == kNull) return BroadPhaseStatus::UnknownId;
  const BroadPhaseStatus s = check_box(box);
  if (s != BroadPhaseStatus::Ok) return s;
  Proxy& p = proxies_[id];
  p.box = box;
  Tree& tree = tree_of(p.kind);
  tree.real[p.leaf] = box;
  if (needs_reinsert(p, tree.nodes[p.leaf].box)) reinsert(p);
  return BroadPhaseStatus::Ok;
}

BroadPhaseStatus DynamicAabbTree::update(std::span<const ProxyUpdate> updates) {
  const BroadPhaseStatus s =
      detail::check_batch(updates, [&](ProxyId id) { return id < proxies_.size() && proxies_[id].leaf != kNull; });
  if (s != BroadPhaseStatus::Ok) return s;
  // Apply the boxes; count the moving leaves that leave their fat boxes.
  std::size_t moving_out = 0;
  for (const ProxyUpdate& u : updates) {
    Proxy& p = proxies_[u.id];
    p.box = u.box;
    tree_of(p.kind).real[p.leaf] = u.box;
    if (p.kind == ProxyKind::Moving && !moving_.nodes[p.leaf].box.contains(u.box)) ++moving_out;
  }
  const bool refit_moving = moving_.leaves >= 64 &&
                            static_cast<Real>(moving_out) > config_.refit_fraction * static_cast<Real>(moving_.leaves);
  for (const ProxyUpdate& u : updates) {
    Proxy& p = proxies_[u.id];
    if (refit_moving && p.kind == ProxyKind::Moving) continue;  // handled below
    if (needs_reinsert(p, tree_of(p.kind).nodes[p.leaf].box)) reinsert(p);
  }
  if (refit_moving) {
    // Every updated moving leaf gets a fat box with the refit margin (tight by default: the
    // whole tree is refitted anyway, and tight boxes find pairs faster).
    for (const ProxyUpdate& u : updates) {
      const Proxy& p = proxies_[u.id];
      if (p.kind != ProxyKind::Moving) continue;
      const Vec3 e = p.box.extents();
      const Real margin = config_.refit_margin_fraction * std::max(e.x, std::max(e.y, e.z));
      Aabb fat = margin > Real(0) ? p.box.inflated(margin) : p.box;
      fat.min = glm::max(fat.min, Vec3(-kMaxCoordinate));
      fat.max = glm::min(fat.max, Vec3(kMaxCoordinate));
      moving_.nodes[p.leaf].box = fat;
    }
  }
  if (refit_moving) {
    const Real cost = refit_all(moving_);
    if (cost > (Real(1) + config_.rebuild_degradation) * moving_.built_cost) rebuild_tree(moving_);
  }
  return BroadPhaseStatus::Ok;
}

Real DynamicAabbTree::tree_cost(const Tree& tree) {
  if (tree.root == kNull) return Real(0);
  const Real root_area = tree.nodes[tree.root].box.surface_area();
  if (!(root_area > Real(0))) return Real(0);
  Real sum = Real(0);
  for (std::size_t i = 0; i < tree.nodes.size(); ++i) {
    const Node& n = tree.nodes[i];
    if (n.height > 0) sum += n.box.surface_area();  // internal nodes in use (free ones: -1)
  }
  return sum / root_area;
}

Real DynamicAabbTree::refit_all(Tree& tree) {
  if (tree.root == kNull) return Real(0);
  if (!tree.order_valid) {
    // Pre-order of the internal nodes, reversed: children come before their parents.
    tree.refit_order.clear();
    std::vector<std::uint32_t> stack{tree.root};
    while (!stack.empty()) {
      const std::uint32_t i = stack.back();
      stack.pop_back();
      const Node& n = tree.nodes[i];
      if (n.is_leaf()) continue;
      tree.refit_order.push_back(i);
      stack.push_back(n.child1);
      stack.push_back(n.child2);
    }
    std::reverse(tree.refit_order.begin(), tree.refit_order.end());
    tree.order_valid = true;
  }
  Real sum = Real(0);
  for (const std::uint32_t i : tree.refit_order) {
    Node& n = tree.nodes[i];
    n.box = merge(tree.nodes[n.child1].box, tree.nodes[n.child2].box);
    sum += n.box.surface_area();
  }
  const Real root_area = tree.nodes[tree.root].box.surface_area();
  return root_area > Real(0) ? sum / root_area : Real(0);
}

// ---- binned SAH rebuild -----------------------------------------------------------------------

void DynamicAabbTree::rebuild() {
  rebuild_tree(static_);
  rebuild_tree(moving_);
}

void DynamicAabbTree::rebuild_tree(Tree& tree) {
  // Scratch kept per thread, so that a steady rebuild allocates nothing: the build items, and
  // `fresh`, which holds the buffers of the tree the last rebuild replaced (swapped out).
  static thread_local std::vector<BuildItem> item_scratch;
  static thread_local Tree tree_scratch;
  std::vector<BuildItem>& items = item_scratch;
  Tree& fresh = tree_scratch;
  items.clear();
  for (std::size_t i = 0; i < tree.nodes.size(); ++i) {
    const Node& n = tree.nodes[i];
    if (n.height == 0 && n.is_leaf() && n.child2 != kNull)
      items.push_back({n.box, tree.real[i], n.box.center(), n.child2});
  }
  // Leaves must be exactly the proxies of this tree (freed nodes have height -1).
  fresh.nodes.clear();
  fresh.real.clear();
  fresh.refit_order.clear();
  fresh.order_valid = false;
  fresh.built_cost = Real(0);
  fresh.root = kNull;
  fresh.free_list = kNull;
  fresh.in_use = 0;
  fresh.leaves = 0;
  if (items.empty()) {
    std::swap(tree, fresh);
    return;
  }
  fresh.nodes.reserve(2 * items.size() - 1);

  struct Bin {
    Aabb box;
    std::size_t count = 0;
  };
  // Recursive lambda via explicit function object: returns the index of the subtree root.
  // Fills the already allocated node `index`; the two children of a node are allocated next
  // to each other (one cache line holds both in float), before either subtree.
  auto build = [&](auto&& self, std::uint32_t index, std::size_t begin, std::size_t end, std::uint32_t parent,
                   int depth) -> void {
    fresh.nodes[index].parent = parent;
    const std::size_t count = end - begin;
    if (count == 1) {
      Node& leaf = fresh.nodes[index];
      leaf.box = items[begin].box;
      leaf.child2 = items[begin].id;
      fresh.real[index] = items[begin].real;
      leaf.height = 0;
      proxies_[items[begin].id].leaf = index;
      return;
    }
    Aabb centres = Aabb::empty();
    for (std::size_t i = begin; i < end; ++i) centres.grow(items[i].centre);
    std::size_t mid = begin + count / 2;
    bool split_found = false;
    if (count > kBinnedBelow && depth < kMaxBuildDepth) {
      // Large node: split at the middle of the widest centre spread (one partition pass; SAH
      // binning of 10^5 boxes per level costs more than it gains this high in the tree).
      const Vec3 spread = centres.extents();
      const int axis = spread.x >= spread.y && spread.x >= spread.z ? 0 : (spread.y >= spread.z ? 1 : 2);
      const Real middle = (centres.min[axis] + centres.max[axis]) * Real(0.5);
      auto it = std::partition(items.begin() + static_cast<std::ptrdiff_t>(begin),
                               items.begin() + static_cast<std::ptrdiff_t>(end),
                               [&](const BuildItem& x) { return x.centre[axis] < middle; });
      mid = static_cast<std::size_t>(it - items.begin());
      split_found = mid > begin && mid < end;
    } else if (depth < kMaxBuildDepth) {
      Real best_cost = kRealMax;
      int best_axis = -1;
      int best_bin = -1;
      // Large nodes bin only the axis of widest centre spread (three times cheaper, nearly
      // the same cost where boxes are spread out); nodes of up to kAllAxesBelow items try all three.
      const Vec3 spread = centres.extents();
      const int widest = spread.x >= spread.y && spread.x >= spread.z ? 0 : (spread.y >= spread.z ? 1 : 2);
      const bool all_axes = count <= kAllAxesBelow;
      for (int axis = all_axes ? 0 : widest; axis < (all_axes ? 3 : widest + 1); ++axis) {
        const Real lo = centres.min[axis];
        const Real extent = centres.max[axis] - lo;
        if (!(extent > Real(0))) continue;
        const Real scale = Real(kBins) / extent;
        // A spread so small (subnormal) that the bins' scale overflows: no split on this axis
        // (an infinite scale made 0 * inf, an invalid operation).
        if (!std::isfinite(scale)) continue;
        Bin bins[kBins];
        for (std::size_t i = begin; i < end; ++i) {
          int bi = static_cast<int>((items[i].centre[axis] - lo) * scale);
          bi = std::clamp(bi, 0, kBins - 1);
          bins[bi].box.grow(items[i].box);
          ++bins[bi].count;
        }
        Real right_area[kBins];
        std::size_t right_count[kBins];
        Aabb acc = Aabb::empty();
        std::size_t cnt = 0;
        for (int i = kBins - 1; i > 0; --i) {
          acc.grow(bins[i].box);
          cnt += bins[i].count;
          right_area[i] = cnt ? acc.surface_area() : Real(0);
          right_count[i] = cnt;
        }
        acc = Aabb::empty();
        cnt = 0;
        for (int i = 0; i < kBins - 1; ++i) {
          acc.grow(bins[i].box);
          cnt += bins[i].count;
          if (cnt == 0 || right_count[i + 1] == 0) continue;
          const Real cost =
              acc.surface_area() * static_cast<Real>(cnt) + right_area[i + 1] * static_cast<Real>(right_count[i + 1]);
          if (cost < best_cost) {
            best_cost = cost;
            best_axis = axis;
            best_bin = i;
          }
        }
      }
      if (best_axis >= 0) {
        const Real lo = centres.min[best_axis];
        const Real scale = Real(kBins) / (centres.max[best_axis] - lo);
        auto it = std::partition(items.begin() + static_cast<std::ptrdiff_t>(begin),
                                 items.begin() + static_cast<std::ptrdiff_t>(end), [&](const BuildItem& it2) {
                                   int bi = static_cast<int>((it2.centre[best_axis] - lo) * scale);
                                   return std::clamp(bi, 0, kBins - 1) <= best_bin;
                                 });
        mid = static_cast<std::size_t>(it - items.begin());
        split_found = mid > begin && mid < end;
      }
    }
    if (!split_found) {
      // Median split on the widest centre axis (also bounds the depth).
      const Vec3 e = centres.extents();
      const int axis = e.x >= e.y && e.x >= e.z ? 0 : (e.y >= e.z ? 1 : 2);
      mid = begin + count / 2;
      std::nth_element(
          items.begin() + static_cast<std::ptrdiff_t>(begin), items.begin() + static_cast<std::ptrdiff_t>(mid),
          items.begin() + static_cast<std::ptrdiff_t>(end), [axis](const BuildItem& x, const BuildItem& y) {
            return x.centre[axis] < y.centre[axis] || (x.centre[axis] == y.centre[axis] && x.id < y.id);
          });
    }
    const auto c1 = static_cast<std::uint32_t>(fresh.nodes.size());
    const std::uint32_t c2 = c1 + 1;
    fresh.nodes.emplace_back();
    fresh.nodes.emplace_back();
    self(self, c1, begin, mid, index, depth + 1);
    self(self, c2, mid, end, index, depth + 1);
    Node& n = fresh.nodes[index];
    n.child1 = c1;
    n.child2 = c2;
    n.box = merge(fresh.nodes[c1].box, fresh.nodes[c2].box);
    n.height = 1 + std::max(fresh.nodes[c1].height, fresh.nodes[c2].height);
  };
  fresh.real.resize(2 * items.size() - 1);
  fresh.nodes.emplace_back();
  build(build, 0, 0, items.size(), kNull, 0);
  fresh.root = 0;
  fresh.in_use = fresh.nodes.size();
  fresh.leaves = items.size();
  // Children are allocated after their parents (larger indices), so the reversed list of
  // internal nodes is a valid refit order.
  for (std::size_t i = fresh.nodes.size(); i-- > 0;) {
    if (!fresh.nodes[i].is_leaf()) fresh.refit_order.push_back(static_cast<std::uint32_t>(i));
  }
  fresh.order_valid = true;
  fresh.built_cost = tree_cost(fresh);
  std::swap(tree, fresh);
}

// ---- pair finding -----------------------------------------------------------------------------

void DynamicAabbTree::collide_task(const PairTask& task, std::vector<ProxyPair>& out, BroadPhaseStats& st) const {
  const Tree& ta = moving_;
  const Tree& tb = task.cross ? static_ : moving_;
  const Node* na = ta.nodes.data();
  const Node* nb = tb.nodes.data();
  struct Item {
    std::uint32_t a;
    std::uint32_t b;
  };
  // Every pop removes one item and pushes at most four whose heights sum to one less, so the
  // stack never holds more than 3 (height_a + height_b) + 4 items: sized once per task.
  // Pushes are branch-free: the item is written, and the top advances only if the boxes
  // overlap (the overlap outcomes are unpredictable).
  // The stack lives on the thread's stack (no allocation per call) unless the trees are
  // taller than a balanced tree of billions of leaves.
  const std::size_t capacity = 3 * static_cast<std::size_t>(na[task.a].height + nb[task.b].height) + 8;
  std::array<Item, 256> local;
  std::vector<Item> tall;
  if (capacity > local.size()) tall.resize(capacity);
  Item* stack = capacity > local.size() ? tall.data() : local.data();
  std::size_t top = 0;
  if (task.cross || task.a != task.b) {
    if (!overlap(na[task.a].box, nb[task.b].box)) return;
  }
  stack[top++] = {task.a, task.b};
  std::uint64_t visited = 0;
  std::uint64_t tested = 0;
  while (top > 0) {
    const Item it = stack[--top];
    ++visited;
    const Node& a = na[it.a];
    if (!task.cross && it.a == it.b) {
      if (a.is_leaf()) continue;
      stack[top++] = {a.child1, a.child1};
      stack[top++] = {a.child2, a.child2};
      stack[top] = {a.child1, a.child2};
      top += overlap(na[a.child1].box, na[a.child2].box) ? 1 : 0;
      continue;
    }
    const Node& b = nb[it.b];
    const bool a_leaf = a.is_leaf();
    const bool b_leaf = b.is_leaf();
    if (a_leaf && b_leaf) {
      ++tested;
      if (overlap(ta.real[it.a], tb.real[it.b])) {
        const Proxy& pa = proxies_[a.child2];
        const Proxy& pb = proxies_[b.child2];
        if (can_pair(pa.filter, pb.filter)) {
          out.push_back(a.child2 < b.child2 ? ProxyPair{a.child2, b.child2} : ProxyPair{b.child2, a.child2});
        }
      }
      continue;
    }
    if (!a_leaf && !b_leaf) {
      // Both internal: descend both at once (four child pairs).
      const Aabb& a1 = na[a.child1].box;
      const Aabb& a2 = na[a.child2].box;
      const Aabb& b1 = nb[b.child1].box;
      const Aabb& b2 = nb[b.child2].box;
      stack[top] = {a.child1, b.child1};
      top += overlap(a1, b1) ? 1 : 0;
      stack[top] = {a.child1, b.child2};
      top += overlap(a1, b2) ? 1 : 0;
      stack[top] = {a.child2, b.child1};
      top += overlap(a2, b1) ? 1 : 0;
      stack[top] = {a.child2, b.child2};
      top += overlap(a2, b2) ? 1 : 0;
    } else if (b_leaf) {
      stack[top] = {a.child1, it.b};
      top += overlap(na[a.child1].box, b.box) ? 1 : 0;
      stack[top] = {a.child2, it.b};
      top += overlap(na[a.child2].box, b.box) ? 1 : 0;
    } else {
      stack[top] = {it.a, b.child1};
      top += overlap(nb[b.child1].box, a.box) ? 1 : 0;
      stack[top] = {it.a, b.child2};
      top += overlap(nb[b.child2].box, a.box) ? 1 : 0;
    }
  }
  st.nodes_visited += visited;
  st.pairs_tested += tested;
}

void DynamicAabbTree::split_tasks(std::vector<PairTask>& tasks, std::size_t wanted) const {
  // Same rules as collide_task, one level per round, until there are `wanted` tasks.
  static thread_local std::vector<PairTask> next;  // kept per thread: no allocation per call once warm
  for (int round = 0; round < 24 && tasks.size() < wanted; ++round) {
    next.clear();
    bool expanded = false;
    for (const PairTask& t : tasks) {
      const Node& a = moving_.nodes[t.a];
      if (!t.cross && t.a == t.b) {
        if (a.is_leaf()) continue;
        next.push_back({a.child1, a.child1, false});
        next.push_back({a.child2, a.child2, false});
        next.push_back({a.child1, a.child2, false});
        expanded = true;
        continue;
      }
      const Node& b = (t.cross ? static_ : moving_).nodes[t.b];
      if (!a.box.overlaps(b.box)) continue;
      if (a.is_leaf() && b.is_leaf()) {
        next.push_back(t);
        continue;
      }
      expanded = true;
      if (b.is_leaf() || (!a.is_leaf() && a.box.surface_area() >= b.box.surface_area())) {
        next.push_back({a.child1, t.b, t.cross});
        next.push_back({a.child2, t.b, t.cross});
      } else {
        next.push_back({t.a, b.child1, t.cross});
        next.push_back({t.a, b.child2, t.cross});
      }
    }
    tasks.swap(next);
    if (!expanded) break;
  }
}

void DynamicAabbTree::find_pairs(std::vector<ProxyPair>& out, Executor& executor) {
  out.clear();
  BroadPhaseStats st;
  // Kept per thread (the calling one), so that a steady find_pairs allocates nothing; named
  // through references, which the chunks' lambda captures (a thread_local named inside it
  // would be the worker's own).
  static thread_local std::vector<PairTask> task_scratch;
  static thread_local std::vector<BroadPhaseStats> stats_scratch;
  std::vector<PairTask>& tasks = task_scratch;
  std::vector<BroadPhaseStats>& per = stats_scratch;
  tasks.clear();
  if (moving_.root != kNull) {
    tasks.push_back({moving_.root, moving_.root, false});
    if (static_.root != kNull) tasks.push_back({moving_.root, static_.root, true});
  }
  const std::size_t threads = moving_.leaves < 256 ? 1 : executor.concurrency();
  if (threads <= 1) {
    for (const PairTask& t : tasks) collide_task(t, out, st);
  } else {
    // Independent node-pair tasks from the top of the traversal, in chunks run by the
    // executor; per-task counters, per-chunk lists joined in chunk order.
    split_tasks(tasks, threads * 16);
    per.assign(tasks.size(), BroadPhaseStats{});
    run_pair_chunks(tasks.size(), threads * 16, executor, chunk_lists_, out,
                    [&](std::size_t begin, std::size_t end, std::vector<ProxyPair>& list) {
                      for (std::size_t k = begin; k < end; ++k) collide_task(tasks[k], list, per[k]);
                    });
    for (const BroadPhaseStats& s : per) {
      st.nodes_visited += s.nodes_visited;
      st.pairs_tested += s.pairs_tested;
    }
  }
  sort_pairs(out, sort_scratch_);
  st.pairs_found = out.size();
  stats_ = st;
}

// ---- inspection -------------------------------------------------------------------------------

bool DynamicAabbTree::validate_tree(const Tree& tree, ProxyKind kind) const {
  std::size_t reachable = 0;
  std::size_t leaves = 0;
  if (tree.root != kNull) {
    if (tree.root >= tree.nodes.size() || tree.nodes[tree.root].parent != kNull) return false;
    std::vector<std::uint32_t> stack{tree.root};
    while (!stack.empty()) {
      const std::uint32_t i = stack.back();
      stack.pop_back();
      if (i >= tree.nodes.size() || ++reachable > tree.nodes.size()) return false;
      const Node& n = tree.nodes[i];
      if (n.is_leaf()) {
        ++leaves;
        if (n.height != 0 || n.child2 >= proxies_.size()) return false;
        const Proxy& p = proxies_[n.child2];
        if (p.leaf != i || p.kind != kind || !n.box.contains(p.box)) return false;
        if (tree.real[i].min != p.box.min || tree.real[i].max != p.box.max) return false;
        continue;
      }
      if (n.child1 >= tree.nodes.size() || n.child2 >= tree.nodes.size() || n.child1 == n.child2) return false;
      const Node& c1 = tree.nodes[n.child1];
      const Node& c2 = tree.nodes[n.child2];
      if (c1.parent != i || c2.parent != i) return false;
      if (n.height != 1 + std::max(c1.height, c2.height)) return false;
      if (!n.box.contains(c1.box) || !n.box.contains(c2.box)) return false;
      stack.push_back(n.child1);
      stack.push_back(n.child2);
    }
  }
  std::size_t free_count = 0;
  for (std::uint32_t f = tree.free_list; f != kNull; f = tree.nodes[f].parent) {
    if (f >= tree.nodes.size() || ++free_count > tree.nodes.size()) return false;
  }
  return reachable == tree.in_use && leaves == tree.leaves && reachable + free_count == tree.nodes.size() &&
         tree.real.size() == tree.nodes.size();
}

bool DynamicAabbTree::validate() const {
  if (!validate_tree(static_, ProxyKind::Static) || !validate_tree(moving_, ProxyKind::Moving)) return false;
  std::size_t count = 0;
  for (const Proxy& p : proxies_) count += p.leaf != kNull ? 1 : 0;
  return count == count_ && count == static_.leaves + moving_.leaves;
}

Real DynamicAabbTree::sah_cost() const { return tree_cost(static_) + tree_cost(moving_); }

int DynamicAabbTree::height() const {
  const int hs = static_.root == kNull ? -1 : static_.nodes[static_.root].height;
  const int hm = moving_.root == kNull ? -1 : moving_.nodes[moving_.root].height;
  return std::max(hs, hm);
}

std::size_t DynamicAabbTree::node_count() const { return static_.in_use + moving_.in_use; }

Aabb DynamicAabbTree::fat_box(ProxyId id) const {
  if (id >= proxies_.size() || proxies_[id].leaf == kNull) return Aabb::empty();
  const Proxy& p = proxies_[id];
  return tree_of(p.kind).nodes[p.leaf].box;
}

void DynamicAabbTree::visit_nodes(FunctionRef<void(const NodeView&)> visit) const {
  for (const auto& [tree, kind] : {std::pair{&moving_, ProxyKind::Moving}, std::pair{&static_, ProxyKind::Static}}) {
    if (tree->root == kNull) continue;
    std::vector<std::pair<std::uint32_t, int>> stack{{tree->root, 0}};
    while (!stack.empty()) {
      const auto [index, depth] = stack.back();
      stack.pop_back();
      const Node& node = tree->nodes[index];
      visit(NodeView{node.box, depth, node.is_leaf(), kind, node.is_leaf() ? node.child2 : ProxyId(0)});
      if (node.is_leaf()) continue;
      stack.emplace_back(node.child2, depth + 1);
      stack.emplace_back(node.child1, depth + 1);
    }
  }
}

}  // namespace proxima
