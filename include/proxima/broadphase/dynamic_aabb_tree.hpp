#pragma once
/// @file dynamic_aabb_tree.hpp
/// DynamicAabbTree ("tree"): the incremental bounding-volume hierarchy of Box2D v3 and Jolt,
/// usually the fastest general-purpose broad phase.
///
/// Design:
/// - Two binary trees, one for Static and one for Moving proxies; pairs come from the moving
///   tree against itself and the moving tree against the static tree (static-static never).
/// - Nodes live in a pool (std::vector) addressed by 32-bit index, with a free list.
/// - Leaves hold a fat box: the proxy's box grown by a margin (a fraction of its largest edge,
///   `DynamicAabbTreeConfig::margin_fraction`). An update whose box still fits in the fat box
///   costs O(1); otherwise the leaf is removed and reinserted. Static proxies get no margin.
/// - Insertion picks the sibling that minimises the surface-area-heuristic (SAH) cost by
///   branch and bound (Bittner, Hapala, Havran, "Fast insertion-based optimization of bounding
///   volume hierarchies", 2013; Box2D v3's b2FindBestSibling) and then applies tree rotations
///   on the way up (Kopta et al., "Fast, effective BVH updates for animated scenes", 2012).
/// - rebuild() rebuilds both trees top-down with binned SAH (Wald, "On fast construction of
///   SAH-based bounding volume hierarchies", 2007; 16 bins; all three axes below 4096 boxes,
///   the widest centre axis above, a midpoint split above 16384), the two children of a node
///   stored next to each other.
///   A batch update that must reinsert more than `refit_fraction` of the moving leaves
///   refits the moving tree instead (new fat boxes in place, every internal box recomputed
///   bottom-up in O(n)) and rebuilds it when refitting has raised its SAH cost by more than
///   `rebuild_degradation` since the last build (Jolt's and many engines' policy for scenes
///   where everything moves).
/// - find_pairs descends tree against tree (a simultaneous traversal of node pairs: both
///   nodes split at once when both are internal; a stack sized once from the tree heights;
///   branch-free pushes), tests the real boxes at leaf pairs, and radix-sorts the result
///   (sort_pairs). With an executor of several threads the top node pairs are split into
///   tasks run by the executor, each chunk of tasks writing its own list; the sorted union is
///   identical to the serial result.
///
/// Complexity: insert/remove O(log n) expected; update O(1) while inside the fat box;
/// find_pairs O(n log n + k) typical; queries O(log n + k) typical; rebuild O(n log n).
/// Queries may run concurrently with each other, not with changes.

#include <proxima/broadphase/broadphase.hpp>
#include <proxima/broadphase/broadphase_queries.hpp>
#include <proxima/broadphase/detail/query_support.hpp>
#include <proxima/broadphase/pair_tracker.hpp>
#include <proxima/broadphase/parallel_pairs.hpp>
#include <proxima/core/executor.hpp>
#include <proxima/core/function_ref.hpp>
#include <proxima/geometry/raycast.hpp>

#include <cstdint>
#include <span>
#include <vector>

namespace proxima {

/// Tuning of a DynamicAabbTree.
struct DynamicAabbTreeConfig {
  /// Fat-box margin on every side, as a fraction of the proxy box's largest edge (>= 0).
  Real margin_fraction = Real(0.1);
  /// Smallest fat-box margin of moving proxies, in length units (>= 0).
  Real margin_min = Real(0);
  /// Apply SAH tree rotations after each insertion.
  bool rotations = true;
  /// A batch update that would reinsert more than this fraction of the moving leaves refits
  /// the moving tree instead (> 1 disables).
  Real refit_fraction = Real(0.1);
  /// Fat-box margin (fraction of the largest edge) given to the moving leaves of a refitting
  /// batch update (>= 0; 0 = tight, fastest pair finding when everything moves every frame).
  Real refit_margin_fraction = Real(0);
  /// After a refit, the moving tree is rebuilt when its SAH cost exceeds (1 + this) times its
  /// cost after the last build.
  Real rebuild_degradation = Real(0.25);
};

/// Incremental AABB tree broad phase (see the file comment). Satisfies BroadPhaseStructure.
class DynamicAabbTree : public BroadPhaseQueries<DynamicAabbTree> {
 public:
  /// Creates an empty tree.
  explicit DynamicAabbTree(const DynamicAabbTreeConfig& config = {});

  /// Adds a proxy with a world box. O(log n). Rejects bad boxes and duplicate ids.
  BroadPhaseStatus insert(ProxyId id, const Aabb& box, ProxyKind kind, ProxyFilter filter = {});
  /// Removes a proxy. O(log n).
  BroadPhaseStatus remove(ProxyId id);
  /// Moves a proxy to a new world box: O(1) inside its fat box, else a reinsertion.
  BroadPhaseStatus update(ProxyId id, const Aabb& box);
  /// Moves many proxies, all or nothing (every entry is checked before any is applied).
  BroadPhaseStatus update(std::span<const ProxyUpdate> updates);
  /// Rebuilds both trees with binned SAH (fat boxes kept). O(n log n).
  void rebuild();
  /// find_pairs(out): the serial form of the one below (BroadPhaseQueries).
  using BroadPhaseQueries::find_pairs;
  /// Every pair (see broadphase.hpp), sorted; `out` is cleared first. The tree-against-tree
  /// descent is split into tasks run by `executor` (same output for every executor).
  void find_pairs(std::vector<ProxyPair>& out, Executor& executor);

  /// Calls `on_ray` for every proxy whose box the ray enters within [0, max_t] (see
  /// RayCallback); the callback's answer clips the ray for the rest of the search.
  template <RayCallback OnRay>
  BroadPhaseStats query_ray(const Ray& ray, Real max_t, OnRay&& on_ray) const;

  /// Checks every invariant: parent links, children inside parents, fat boxes containing the
  /// real boxes, heights, leaf counts, free list, proxy table. O(n).
  bool validate() const;
  /// Number of proxies.
  std::size_t size() const { return count_; }

  /// SAH cost of both trees: the sum of the internal nodes' surface areas divided by the
  /// root's (per tree, then added). Lower is better; rebuild() usually lowers it.
  Real sah_cost() const;
  /// Height of the taller tree (a single leaf has height 0; empty trees -1).
  int height() const;
  /// Number of nodes in use in both trees.
  std::size_t node_count() const;
  /// The fat box of a proxy (its leaf's box); the empty box for an unknown id.
  Aabb fat_box(ProxyId id) const;

  /// One node of a tree, as visit_nodes shows it (for debug drawing).
  struct NodeView {
    Aabb box;           ///< the node's box, world frame (a leaf: the proxy's fat box)
    int depth = 0;      ///< the root of its tree at 0
    bool leaf = false;  ///< true for a leaf (one proxy)
    ProxyKind tree{};   ///< which tree: Moving or Static proxies
    ProxyId proxy = 0;  ///< a leaf's proxy id (0 for an inner node)
  };
  /// Calls `visit` for every node in use, the moving tree first, each tree depth first
  /// (a parent before its children). O(n); allocates a stack of the tree's height.
  void visit_nodes(FunctionRef<void(const NodeView&)> visit) const;

 private:
  friend class BroadPhaseQueries<DynamicAabbTree>;
  static constexpr std::uint32_t kNull = 0xffffffffu;

  /// A pool node. Leaves have child1 == kNull and hold the proxy id in child2.
  struct Node {
    Aabb box;
    std::uint32_t parent = kNull;
    std::uint32_t child1 = kNull;
    std::uint32_t child2 = kNull;
    std::int32_t height = 0;
    bool is_leaf() const { return child1 == kNull; }
  };

  /// One binary tree over a pool of nodes.
  struct Tree {
    std::vector<Node> nodes;
    std::vector<Aabb> real;                  ///< leaves: the proxy's real box (same index as nodes)
    std::vector<std::uint32_t> refit_order;  ///< internal nodes, children before parents
    bool order_valid = false;                ///< refit_order matches the structure
    Real built_cost = Real(0);               ///< SAH cost after the last rebuild
    std::uint32_t root = kNull;
    std::uint32_t free_list = kNull;  ///< chained through Node::parent
    std::size_t in_use = 0;
    std::size_t leaves = 0;
  };

  /// What the tree knows of a proxy, indexed by id.
  struct Proxy {
    Aabb box;
    ProxyFilter filter;
    std::uint32_t leaf = kNull;  ///< kNull when the id is unused
    ProxyKind kind = ProxyKind::Static;
  };

  static std::uint32_t allocate(Tree& tree);
  static void release(Tree& tree, std::uint32_t index);
  void insert_leaf(Tree& tree, std::uint32_t leaf);
  static void remove_leaf(Tree& tree, std::uint32_t leaf);
  void rotate(Tree& tree, std::uint32_t index);
  static void refit_up(Tree& tree, std::uint32_t index);
  void rebuild_tree(Tree& tree);
  Aabb make_fat(const Aabb& box, ProxyKind kind) const;
  bool needs_reinsert(const Proxy& p, const Aabb& fat) const;
  void reinsert(Proxy& p);
  Tree& tree_of(ProxyKind kind) { return kind == ProxyKind::Moving ? moving_ : static_; }
  const Tree& tree_of(ProxyKind kind) const { return kind == ProxyKind::Moving ? moving_ : static_; }
  bool validate_tree(const Tree& tree, ProxyKind kind) const;
  static Real refit_all(Tree& tree);
  static Real tree_cost(const Tree& tree);
  /// Depth-first walk of both trees (moving first) counting nodes_visited and pairs_tested:
  /// descends into the nodes whose fat box `enter(fat)` accepts and calls `leaf(id, real)`
  /// at each leaf so reached, with the proxy's real box; stops when it returns false.
  template <class Enter, class Leaf>
  void walk(BroadPhaseStats& st, Enter&& enter, Leaf&& leaf) const;
  /// The box walk of query_aabb (BroadPhaseQueries): both trees, pruned by the fat boxes,
  /// leaves tested on their real boxes.
  template <class Visit>
  void visit_box(const Aabb& box, BroadPhaseStats& st, Visit&& visit) const;

  struct PairTask {
    std::uint32_t a;
    std::uint32_t b;
    bool cross;  ///< a in moving tree, b in static tree
  };
  void collide_task(const PairTask& task, std::vector<ProxyPair>& out, BroadPhaseStats& st) const;
  void split_tasks(std::vector<PairTask>& tasks, std::size_t wanted) const;

  DynamicAabbTreeConfig config_;
  Tree static_;
  Tree moving_;
  std::vector<Proxy> proxies_;
  std::size_t count_ = 0;
  PairSortScratch sort_scratch_;
  PairChunkLists chunk_lists_;  ///< per-chunk pair lists of the parallel find_pairs
  BroadPhaseStats stats_;
};

static_assert(BroadPhaseStructure<DynamicAabbTree>);

// ---- queries (templates on the callback) ------------------------------------------------

template <class Enter, class Leaf>
void DynamicAabbTree::walk(BroadPhaseStats& st, Enter&& enter, Leaf&& leaf) const {
  for (const Tree* tree : {&moving_, &static_}) {
    if (tree->root == kNull) continue;
    detail::TraversalStack<std::uint32_t, 256> stack;
    stack.push(tree->root);
    while (!stack.empty()) {
      const std::uint32_t index = stack.pop();
      const Node& n = tree->nodes[index];
      ++st.nodes_visited;
      if (!enter(n.box)) continue;
      if (!n.is_leaf()) {
        stack.push(n.child1);
        stack.push(n.child2);
        continue;
      }
      ++st.pairs_tested;
      if (!leaf(n.child2, tree->real[index])) return;
    }
  }
}

template <class Visit>
void DynamicAabbTree::visit_box(const Aabb& box, BroadPhaseStats& st, Visit&& visit) const {
  walk(
      st, [&](const Aabb& fat) { return fat.overlaps(box); },
      [&](ProxyId id, const Aabb& real) { return !real.overlaps(box) || visit(id); });
}

template <RayCallback OnRay>
BroadPhaseStats DynamicAabbTree::query_ray(const Ray& ray, Real max_t, OnRay&& on_ray) const {
  BroadPhaseStats st;
  if (!detail::ray_input_ok(ray, max_t)) return st;
  const detail::SlabRay slab(ray);
  Real limit = max_t;
  walk(
      st,
      [&](const Aabb& fat) {
        Real t;
        return slab.enter(fat, limit, t);
      },
      [&](ProxyId id, const Aabb& real) {
        const auto hit = geometry::ray_aabb(ray, limit, real);
        if (!hit) return true;
        ++st.pairs_found;
        return detail::apply_ray_result(on_ray(id, hit->t), limit);
      });
  return st;
}

}  // namespace proxima
