#pragma once
/// @file loose_octree.hpp
/// LooseTree<Dim>: the loose octree ("octree", Dim = 3) and the loose quadtree ("quadtree",
/// Dim = 2, which partitions x and y only: z is never split, so 3D boxes stacked in z share
/// nodes), with looseness factor 2 (Ulrich, "Loose Octrees", Game Programming Gems 1, 4.11;
/// Ericson, Real-Time Collision Detection, 7.3.6).
///
/// A node of half size H (its cell is centre +- H) has loose bounds centre +- 2H. A box is
/// stored in the deepest node, reached from the root by following the child whose cell holds
/// the box centre, whose loose bounds still contain the box (so a box of half extent h sits
/// at the depth where H/2 < h <= H, whatever its position). Nodes are created on demand and
/// deleted when empty; the root doubles towards a box that leaves it.
///
/// Steps of find_pairs: 1. the boxes are gathered node by node into one array (a node's own
/// boxes contiguous, sorted on x when many) and every node gets the tight box of its own
/// boxes and of its subtree (bottom-up); 2. a simultaneous descent of the tree against itself
/// on those tight boxes: self(N) = N's own boxes among themselves (sweep on x), against each
/// child subtree, self of each child, cross of each child pair; cross(A, B) = own boxes of
/// each against the other subtree, then the child pairs whose tight boxes overlap (the
/// Ericson 6.5.3 BVH-BVH descent with the octree nodes as volumes); no per-box walk from the
/// root. The top tasks (self and cross of the first levels) are run by the executor of
/// find_pairs(out, executor); pairs are radix-sorted. O(n + nodes + node pairs met + k') with k' the
/// candidate pairs of overlapping tight boxes.
/// Queries walk the nodes whose loose bounds the box, point or ray meets.

#include <proxima/broadphase/broadphase.hpp>
#include <proxima/broadphase/broadphase_queries.hpp>
#include <proxima/broadphase/pair_tracker.hpp>
#include <proxima/broadphase/proxy_table.hpp>
#include <proxima/core/executor.hpp>

#include <algorithm>
#include <cstdint>
#include <span>
#include <vector>

namespace proxima {

/// Loose 2^Dim-tree over x, y (and z when Dim = 3). See the file comment.
template <int Dim>
class LooseTree : public BroadPhaseQueries<LooseTree<Dim>> {
  static_assert(Dim == 2 || Dim == 3, "LooseTree partitions 2 or 3 axes");

 public:
  /// Number of children of a node.
  static constexpr int kChildren = 1 << Dim;

  /// Adds a proxy. O(depth).
  BroadPhaseStatus insert(ProxyId id, const Aabb& box, ProxyKind kind = ProxyKind::Moving, ProxyFilter filter = {});
  /// Removes a proxy (empty nodes are deleted). O(depth).
  BroadPhaseStatus remove(ProxyId id);
  /// Moves a proxy to the node its new box belongs to. O(depth).
  BroadPhaseStatus update(ProxyId id, const Aabb& box);
  /// Moves many proxies, all or nothing. O(m depth).
  BroadPhaseStatus update(std::span<const ProxyUpdate> updates);
  /// Rebuilds the tree around the current boxes (fits the root, resets the depth limit).
  void rebuild();
  /// find_pairs(out): the serial form of the one below (BroadPhaseQueries).
  using BroadPhaseQueries<LooseTree>::find_pairs;
  /// Every pair, sorted (broadphase.hpp), with the top tasks run by `executor` (same output
  /// for every executor).
  void find_pairs(std::vector<ProxyPair>& out, Executor& executor);
  /// Proxies whose box overlaps `box` (closed), each once, by a walk of the nodes whose loose
  /// bounds meet it (pairs_found is not counted); an inverted or NaN box reports nothing.
  /// Returns the query's counters. query_point is this query on the point's box.
  template <OverlapCallback OnOverlap>
  BroadPhaseStats query_aabb(const Aabb& box, OnOverlap&& on_overlap) const;
  /// Proxies whose box the ray enters at t <= the current max fraction (t of
  /// geometry::ray_aabb), nodes pruned by their loose bounds against the clipped ray.
  template <RayCallback OnRay>
  BroadPhaseStats query_ray(const Ray& ray, Real max_t, OnRay&& on_ray) const;
  /// Checks the links, counts and that every box lies in its node's loose bounds. O(n + nodes).
  bool validate() const;
  /// Number of proxies.
  std::size_t size() const { return proxies_.size(); }
  /// Number of live nodes.
  std::size_t node_count() const { return nodes_.size() - free_.size(); }
  /// Depth of the deepest live node (root = 0). O(nodes).
  int depth() const;
  /// Bytes held by the structure's buffers (capacity).
  std::size_t memory_bytes() const;

 private:
  friend class BroadPhaseQueries<LooseTree>;
  static constexpr std::int32_t kNil = -1;
  static constexpr std::uint32_t kNone = 0xffffffffu;
  struct Node {
    Vec3 center{0};
    Real half = 1;
    Aabb loose;  // center +- 2 half on the partitioned axes, unbounded on the others
    std::int32_t child[kChildren];
    std::int32_t parent = kNil;
    std::uint32_t first = kNone;  // first proxy id of the node's list
    std::uint32_t count = 0;      // proxies in this node
    std::uint32_t children = 0;   // live children
  };

  std::int32_t new_node(const Vec3& center, Real half, std::int32_t parent);
  static Aabb loose_of(const Vec3& center, Real half);
  static bool contains(const Aabb& outer, const Aabb& inner);
  void make_room(const Aabb& box);
  std::int32_t descend(const Aabb& box);
  void link(ProxyId id, std::int32_t node);
  void unlink(ProxyId id);
  void prune(std::int32_t node);
  struct Item {
    Aabb box;
    ProxyId id;
  };
  /// One unit of pair work: self(a) when b == kNil, the own part of self(a) (own boxes among
  /// themselves and against each child subtree) when b == a, cross(a, b) otherwise.
  struct Task {
    std::int32_t a;
    std::int32_t b;
  };
  void gather();
  void split_tasks(std::size_t wanted);
  void run_task(const Task& task, std::vector<ProxyPair>& out, BroadPhaseStats& st) const;
  void own_pairs(std::int32_t node, std::vector<ProxyPair>& out, BroadPhaseStats& st) const;
  void self_pairs(std::int32_t node, std::vector<ProxyPair>& out, BroadPhaseStats& st) const;
  void cross_pairs(std::int32_t a, std::int32_t b, std::vector<ProxyPair>& out, BroadPhaseStats& st) const;
  void items_vs_subtree(std::uint32_t begin, std::uint32_t end, const Aabb& fit, std::int32_t node,
                        std::vector<ProxyPair>& out, BroadPhaseStats& st) const;
  void test_items(std::uint32_t begin, std::uint32_t end, std::uint32_t begin2, std::uint32_t end2,
                  std::vector<ProxyPair>& out, BroadPhaseStats& st) const;
  template <class OnOverlap>
  bool query_node(std::int32_t node, const Aabb& box, OnOverlap& on_overlap, BroadPhaseStats& st) const;
  static bool ray_meets(const Ray& ray, Real max_t, const Aabb& loose);

  detail::ProxyTable proxies_;
  std::vector<std::int32_t> node_of_;  // by id
  std::vector<std::uint32_t> next_;    // by id: next in the node's list
  std::vector<std::uint32_t> prev_;    // by id: previous in the node's list
  std::vector<Node> nodes_;
  std::vector<std::int32_t> free_;
  std::int32_t root_ = kNil;
  Real min_half_ = 0;  // nodes are not split below this half size
  // find_pairs scratch (step 1 of find_pairs), by node unless said otherwise.
  std::vector<Item> items_;               // by gathered position
  std::vector<std::uint32_t> own_begin_;  // first gathered position of the node's own boxes
  std::vector<Aabb> own_fit_;             // tight box of the own boxes
  std::vector<Aabb> fit_;                 // tight box of the subtree
  std::vector<std::int32_t> order_;       // nodes in depth-first order
  std::vector<Task> tasks_;
  PairSortScratch sort_scratch_;
  BroadPhaseStats stats_;
};

/// Loose octree ("octree").
using LooseOctree = LooseTree<3>;
/// Loose quadtree on x, y ("quadtree").
using LooseQuadtree = LooseTree<2>;

// ---- queries (templates on the callback) ------------------------------------------------

template <int Dim>
template <class OnOverlap>
bool LooseTree<Dim>::query_node(std::int32_t node, const Aabb& box, OnOverlap& on_overlap, BroadPhaseStats& st) const {
  const Node& n = nodes_[std::size_t(node)];
  ++st.nodes_visited;
  for (std::uint32_t id = n.first; id != kNone; id = next_[id]) {
    ++st.pairs_tested;
    if (proxies_[id].box.overlaps(box) && !on_overlap(id)) return false;
  }
  for (const std::int32_t child : n.child) {
    if (child == kNil || !nodes_[std::size_t(child)].loose.overlaps(box)) continue;
    if (!query_node(child, box, on_overlap, st)) return false;
  }
  return true;
}

template <int Dim>
template <OverlapCallback OnOverlap>
BroadPhaseStats LooseTree<Dim>::query_aabb(const Aabb& box, OnOverlap&& on_overlap) const {
  BroadPhaseStats st;
  if (root_ == kNil || !box.is_valid() || !nodes_[std::size_t(root_)].loose.overlaps(box)) return st;
  query_node(root_, box, on_overlap, st);
  return st;
}

template <int Dim>
template <RayCallback OnRay>
BroadPhaseStats LooseTree<Dim>::query_ray(const Ray& ray, Real max_t, OnRay&& on_ray) const {
  BroadPhaseStats st;
  if (root_ == kNil || !detail::ray_input_ok(ray, max_t)) return st;
  Real limit = max_t;
  std::vector<std::int32_t> stack{root_};
  while (!stack.empty()) {
    const std::int32_t node = stack.back();
    stack.pop_back();
    const Node& n = nodes_[std::size_t(node)];
    if (!ray_meets(ray, limit, n.loose)) continue;
    ++st.nodes_visited;
    for (std::uint32_t id = n.first; id != kNone; id = next_[id]) {
      ++st.pairs_tested;
      Real t = 0;
      if (!detail::ray_enters_box(ray, limit, proxies_[id].box, t)) continue;
      const Real next = on_ray(id, t);
      if (next < 0) continue;
      if (next == 0) return st;
      limit = std::min(limit, next);
    }
    for (const std::int32_t child : n.child) {
      if (child != kNil) stack.push_back(child);
    }
  }
  return st;
}

extern template class LooseTree<2>;
extern template class LooseTree<3>;

static_assert(BroadPhaseStructure<LooseOctree>);
static_assert(BroadPhaseStructure<LooseQuadtree>);

}  // namespace proxima
