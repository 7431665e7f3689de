#pragma once
/// @file kd_tree.hpp
/// KdTree ("kdtree"): a kd-tree over box centres in the bounding-interval-hierarchy form
/// (Wächter and Keller, "Instant ray tracing: the bounding interval hierarchy", 2006).
///
/// Design:
/// - Each internal node splits its proxies at the median of their centres along the axis of
///   largest centre spread. Every proxy goes to exactly one side (the side of its centre), so a
///   proxy lives in exactly one leaf and pairs are never duplicated. Straddling is handled by
///   two clip planes per node instead of one: `clip_left` is the largest coordinate, along the
///   node's axis, of any box in the left subtree, `clip_right` the smallest of the right
///   subtree. The two children's slabs may overlap.
/// - Leaves hold up to `leaf_size` proxies in one contiguous array of (box, id) records.
/// - Updates write the box in place and widen the clip planes on the leaf's path: O(depth).
///   find_pairs first refits every clip plane exactly (O(n)) and rebuilds the tree
///   (O(n log n)) when quality has degraded: proxies inserted since the last build (they wait
///   in a pending list scanned linearly by queries), many removals, or clip slabs whose mean
///   overlap grew by more than `rebuild_overlap` of the node widths since the build.
/// - Pair finding: a simultaneous descent of the tree against itself on the subtree boxes
///   kept by the refit (self of a node = self of each child + cross of the children; cross
///   of two nodes with overlapping boxes descends into the children; two leaves test their
///   records), each pair met once; top tasks run by the executor; results sorted.
///
/// Complexity: build O(n log n); update O(log n); queries O(log n + k) for well-spread data;
/// find_pairs O(n log n + k) plus any refit/rebuild. Queries may run concurrently with each
/// other, not with changes.

#include <proxima/broadphase/broadphase.hpp>
#include <proxima/broadphase/broadphase_queries.hpp>
#include <proxima/broadphase/detail/query_support.hpp>
#include <proxima/broadphase/pair_tracker.hpp>
#include <proxima/core/executor.hpp>
#include <proxima/geometry/raycast.hpp>

#include <cstdint>
#include <span>
#include <vector>

namespace proxima {

/// Tuning of a KdTree.
struct KdTreeConfig {
  /// Largest number of proxies in a leaf (>= 1).
  int leaf_size = 6;
  /// Rebuild when the mean overlap of sibling slabs (as a fraction of the node's width along
  /// its axis) exceeds the value at the last build by this much.
  Real rebuild_overlap = Real(0.15);
};

/// kd-tree broad phase (see the file comment). Satisfies BroadPhaseStructure.
class KdTree : public BroadPhaseQueries<KdTree> {
 public:
  /// Creates an empty tree.
  explicit KdTree(const KdTreeConfig& config = {});

  /// Adds a proxy (pending until the next find_pairs or rebuild; queries see it at once).
  BroadPhaseStatus insert(ProxyId id, const Aabb& box, ProxyKind kind, ProxyFilter filter = {});
  /// Removes a proxy. O(1).
  BroadPhaseStatus remove(ProxyId id);
  /// Moves a proxy: box written in place, clip planes widened on its path. O(depth).
  BroadPhaseStatus update(ProxyId id, const Aabb& box);
  /// Moves many proxies, all or nothing.
  BroadPhaseStatus update(std::span<const ProxyUpdate> updates);
  /// Rebuilds the tree from scratch over every proxy (median splits). O(n log n).
  void rebuild();
  /// find_pairs(out): the serial form of the one below (BroadPhaseQueries).
  using BroadPhaseQueries::find_pairs;
  /// Every pair (see broadphase.hpp), sorted, with the tree descent split into tasks run by
  /// `executor` (same output for every executor). May refit or rebuild first.
  void find_pairs(std::vector<ProxyPair>& out, Executor& executor);

  /// Every proxy whose box the ray enters within [0, max_t]; the callback clips the ray.
  /// Returns the query's counters.
  template <RayCallback OnRay>
  BroadPhaseStats query_ray(const Ray& ray, Real max_t, OnRay&& on_ray) const;

  /// Checks the invariants: each proxy in exactly one place, leaf records equal to the proxy
  /// table, every box within the clip planes of all its ancestors, parent links. O(n log n).
  bool validate() const;
  /// Number of proxies.
  std::size_t size() const { return count_; }
  /// Number of rebuilds done so far (explicit and automatic).
  std::size_t rebuild_count() const { return rebuilds_; }
  /// Depth of the tree (0 for a single leaf or an empty tree).
  int depth() const;

 private:
  friend class BroadPhaseQueries<KdTree>;
  static constexpr std::uint32_t kNull = 0xffffffffu;

  struct Node {
    Real clip_left = Real(0);     ///< max coordinate along `axis` of the left subtree's boxes
    Real clip_right = Real(0);    ///< min coordinate along `axis` of the right subtree's boxes
    std::uint32_t right = kNull;  ///< internal: right child (left child = this + 1)
    std::uint32_t begin = 0;      ///< leaf: first record
    std::uint32_t count = 0;      ///< leaf: number of records
    std::uint32_t parent = kNull;
    std::uint8_t axis = 0;
    bool leaf = true;
  };
  struct Record {
    Aabb box;
    ProxyId id;  ///< kDead when removed
  };
  enum class Place : std::uint8_t { None, Tree, Pending };
  struct Proxy {
    Aabb box;
    ProxyFilter filter;
    std::uint32_t slot = kNull;  ///< record index (Tree) or pending index (Pending)
    std::uint32_t leaf = kNull;  ///< leaf node (Tree)
    ProxyKind kind = ProxyKind::Static;
    Place place = Place::None;
  };
  static constexpr ProxyId kDead = 0xffffffffu;

  std::uint32_t build(std::uint32_t begin, std::uint32_t end, std::uint32_t parent, int depth);
  Aabb refit(std::uint32_t node, double& overlap_sum, std::size_t& internal_count);
  void widen(std::uint32_t leaf, const Aabb& box);
  template <class Visit>
  void visit_box(const Aabb& box, BroadPhaseStats& st, Visit&& visit) const;
  /// One entry of the ray query's stack: a node and the parameter interval the ray spends
  /// within its clip planes.
  struct RayEntry {
    std::uint32_t node;
    Real t0;
    Real t1;
  };
  static void push_children(const Node& n, std::uint32_t index, const Ray& ray, const RayEntry& e, Real limit,
                            detail::TraversalStack<RayEntry, 192>& stack);
  struct DescentView;  // the tree as seen by the pair descent (kd_tree.cpp)

  KdTreeConfig config_;
  std::vector<Node> nodes_;
  std::vector<Aabb> bounds_;  ///< by node: box of the subtree (exact after refit)
  std::vector<Record> records_;

  std::vector<ProxyId> pending_;
  std::vector<Proxy> proxies_;
  std::size_t count_ = 0;
  std::size_t dead_ = 0;
  bool dirty_ = false;  ///< clip planes widened since the last exact refit
  double build_overlap_ = 0;
  std::size_t rebuilds_ = 0;
  PairSortScratch sort_scratch_;
  BroadPhaseStats stats_;
};

static_assert(BroadPhaseStructure<KdTree>);

// ---- queries (templates on the callback) ------------------------------------------------

template <class Visit>
void KdTree::visit_box(const Aabb& box, BroadPhaseStats& st, Visit&& visit) const {
  if (!nodes_.empty()) {
    detail::TraversalStack<std::uint32_t, 192> stack;
    stack.push(0);
    while (!stack.empty()) {
      const Node& n = nodes_[stack.pop()];
      ++st.nodes_visited;
      if (n.leaf) {
        for (std::uint32_t i = n.begin; i < n.begin + n.count; ++i) {
          const Record& r = records_[i];
          if (r.id == kDead) continue;
          ++st.pairs_tested;
          if (r.box.overlaps(box) && !visit(r.id)) return;
        }
        continue;
      }
      const auto index = static_cast<std::uint32_t>(&n - nodes_.data());
      if (box.max[n.axis] >= n.clip_right) stack.push(n.right);
      if (box.min[n.axis] <= n.clip_left) stack.push(index + 1);
    }
  }
  for (const ProxyId id : pending_) {
    ++st.pairs_tested;
    if (proxies_[id].box.overlaps(box) && !visit(id)) return;
  }
}

template <RayCallback OnRay>
BroadPhaseStats KdTree::query_ray(const Ray& ray, Real max_t, OnRay&& on_ray) const {
  BroadPhaseStats st;
  if (!detail::ray_input_ok(ray, max_t)) return st;
  Real limit = max_t;
  auto test = [&](ProxyId id, const Aabb& box) {
    ++st.pairs_tested;
    const auto hit = geometry::ray_aabb(ray, limit, box);
    if (!hit) return true;
    ++st.pairs_found;
    return detail::apply_ray_result(on_ray(id, hit->t), limit);
  };
  // Pending proxies first (usually none), then the tree with per-node parameter intervals.
  for (const ProxyId id : pending_) {
    if (!test(id, proxies_[id].box)) return st;
  }
  if (nodes_.empty()) return st;
  detail::TraversalStack<RayEntry, 192> stack;
  stack.push({0, Real(0), max_t});
  while (!stack.empty()) {
    const RayEntry e = stack.pop();
    if (e.t0 > limit) continue;
    const Node& n = nodes_[e.node];
    ++st.nodes_visited;
    if (!n.leaf) {
      push_children(n, e.node, ray, e, limit, stack);
      continue;
    }
    for (std::uint32_t i = n.begin; i < n.begin + n.count; ++i) {
      const Record& r = records_[i];
      if (r.id != kDead && !test(r.id, r.box)) return st;
    }
  }
  return st;
}

}  // namespace proxima
