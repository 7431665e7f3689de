#pragma once
/// @file bsp_tree.hpp
/// BspTree ("bsp"): a binary space partition with arbitrary (not only axis-aligned) splitting
/// planes, meant for scenes dominated by static geometry (levels, terrain pieces, walls along
/// diagonal directions).
///
/// Design:
/// - Each internal node holds a plane n . x = d. Candidate normals are the principal axis of
///   the node's box centres (power iteration on their covariance), the three coordinate axes
///   and the four cube diagonals; each candidate's offset is the median of the projected
///   centres; the plane that straddles the fewest boxes (ties: the most balanced) wins.
/// - Straddling boxes STAY AT THE NODE (no reference splitting): every proxy is stored at
///   exactly one node, so pairs are never produced twice and need no dedupe set. A box goes to
///   the back child when its projection lies entirely below d, to the front child when
///   entirely above, else it stays. When the build finds more than `leaf_size` straddlers at a
///   node, they form the node's third, "middle" subtree, partitioned by other planes (they all
///   cross this one), so queries never scan a long straddler list.
/// - Each node keeps, besides the plane, `back_max` (the largest projection of any box in its
///   back subtree) and `front_min` (the smallest of its front subtree), so queries visit a side
///   only when the query's projection reaches it, and the AABB of its whole subtree (ray
///   queries use it). Projections are padded by a rounding bound, so the pruning is exact.
/// - Moving proxies are supported: an update detaches the proxy and re-descends from the root
///   (O(depth)); bounds only grow, so after many updates the tree is loose. find_pairs rebuilds
///   when its own work has grown by `rebuild_work` since the last build, or when the edits
///   since the last build exceed `rebuild_edits` times the proxy count.
/// - Pair finding: one box query per Moving proxy (moving-moving pairs kept by id order).
///
/// Complexity: build O(n log n) (seven candidate planes per node); insert/update/remove
/// O(depth + node occupancy); queries O(depth + visited occupancy + k). Queries may run
/// concurrently with each other, not with changes.

#include <proxima/broadphase/broadphase.hpp>
#include <proxima/broadphase/broadphase_queries.hpp>
#include <proxima/broadphase/detail/query_support.hpp>
#include <proxima/broadphase/pair_tracker.hpp>
#include <proxima/core/executor.hpp>
#include <proxima/core/tolerance.hpp>
#include <proxima/geometry/raycast.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

namespace proxima {

/// Tuning of a BspTree.
struct BspTreeConfig {
  /// Largest number of proxies a node keeps before the build splits it (>= 1).
  int leaf_size = 8;
  /// find_pairs rebuilds once inserts + updates + removes since the last build exceed this
  /// many times the proxy count (plus 16).
  Real rebuild_edits = Real(16);
  /// find_pairs rebuilds once its work (nodes visited + boxes tested) exceeds this many times
  /// the work of the first find_pairs after the last build.
  Real rebuild_work = Real(1.5);
};

/// BSP-tree broad phase (see the file comment). Satisfies BroadPhaseStructure.
class BspTree : public BroadPhaseQueries<BspTree> {
 public:
  /// Creates an empty tree.
  explicit BspTree(const BspTreeConfig& config = {});

  /// Adds a proxy by descent from the root. O(depth).
  BroadPhaseStatus insert(ProxyId id, const Aabb& box, ProxyKind kind, ProxyFilter filter = {});
  /// Removes a proxy. O(node occupancy).
  BroadPhaseStatus remove(ProxyId id);
  /// Moves a proxy (detach and re-descend). O(depth).
  BroadPhaseStatus update(ProxyId id, const Aabb& box);
  /// Moves many proxies, all or nothing.
  BroadPhaseStatus update(std::span<const ProxyUpdate> updates);
  /// Rebuilds the planes over the current boxes. O(n log n).
  void rebuild();
  /// find_pairs(out): the serial form of the one below (BroadPhaseQueries).
  using BroadPhaseQueries::find_pairs;
  /// Every pair (see broadphase.hpp), sorted, with the tree descent split into tasks run by
  /// `executor` (same output for every executor). May rebuild first.
  void find_pairs(std::vector<ProxyPair>& out, Executor& executor);

  /// Every proxy whose box the ray enters within [0, max_t]; the callback clips the ray.
  /// Returns the query's counters.
  template <RayCallback OnRay>
  BroadPhaseStats query_ray(const Ray& ray, Real max_t, OnRay&& on_ray) const;

  /// Checks the invariants: each proxy at one node, each box on the proper side of every
  /// ancestor plane and within the ancestors' side bounds and subtree boxes, parent links.
  bool validate() const;
  /// Number of proxies.
  std::size_t size() const { return count_; }
  /// Number of nodes.
  std::size_t node_count() const { return nodes_.size(); }
  /// Number of internal nodes whose plane is not axis-aligned.
  std::size_t oblique_plane_count() const;
  /// Number of rebuilds done so far (explicit and automatic).
  std::size_t rebuild_count() const { return rebuilds_; }

 private:
  friend class BroadPhaseQueries<BspTree>;
  static constexpr std::uint32_t kNull = 0xffffffffu;

  struct Node {
    Vec3 normal{Real(0)};   ///< unit plane normal (internal nodes)
    Real offset = Real(0);  ///< plane offset d
    Real back_max = -kRealMax;
    Real front_min = kRealMax;
    Aabb bounds;  ///< contains every box of the subtree (grown, exact after rebuild)
    std::uint32_t back = kNull;
    std::uint32_t front = kNull;
    std::uint32_t middle = kNull;  ///< subtree of the straddlers (kNull: they are in `items`)
    std::uint32_t parent = kNull;
    std::vector<ProxyId> items;  ///< proxies stored here
    bool internal() const { return back != kNull; }
  };
  struct Proxy {
    Aabb box;
    ProxyFilter filter;
    std::uint32_t node = kNull;  ///< kNull when unused
    std::uint32_t index = 0;     ///< position in the node's items
    ProxyKind kind = ProxyKind::Static;
  };

  /// An interval of projections on a plane normal.
  struct Interval {
    Real lo;
    Real hi;
  };
  /// Projection of a box on a unit normal, padded to contain the exact projection.
  static Interval project(const Vec3& n, const Aabb& b) {
    Real lo = Real(0);
    Real hi = Real(0);
    Real scale = Real(0);
    for (int a = 0; a < 3; ++a) {
      if (n[a] >= Real(0)) {
        lo += n[a] * b.min[a];
        hi += n[a] * b.max[a];
      } else {
        lo += n[a] * b.max[a];
        hi += n[a] * b.min[a];
      }
      scale += std::abs(n[a]) * std::max(std::abs(b.min[a]), std::abs(b.max[a]));
    }
    const Real pad = Real(8) * kEpsilon * scale + std::numeric_limits<Real>::min();
    return {lo - pad, hi + pad};
  }

  struct DescentView;  // the tree as seen by the pair descent (bsp_tree.cpp)
  void place(ProxyId id);
  void detach(ProxyId id);
  std::uint32_t build(std::vector<ProxyId>& ids, std::uint32_t parent, int depth);
  template <class Visit>
  void visit_box(const Aabb& box, BroadPhaseStats& st, Visit&& visit) const;

  BspTreeConfig config_;
  std::vector<Node> nodes_;
  std::vector<Proxy> proxies_;
  std::size_t count_ = 0;
  std::size_t edits_ = 0;
  std::size_t rebuilds_ = 0;
  bool overfull_ = false;
  bool degraded_ = false;  ///< the last find_pairs found the tree degraded
  double baseline_work_ =
      0;  ///< work of the first find_pairs after the last build  ///< a leaf grew past 4 leaf_size + 16 by insertion
  PairSortScratch sort_scratch_;
  BroadPhaseStats stats_;
};

static_assert(BroadPhaseStructure<BspTree>);

// ---- queries (templates on the callback) ------------------------------------------------

template <class Visit>
void BspTree::visit_box(const Aabb& box, BroadPhaseStats& st, Visit&& visit) const {
  if (nodes_.empty()) return;
  detail::TraversalStack<std::uint32_t, 192> stack;
  stack.push(0);
  while (!stack.empty()) {
    const std::uint32_t index = stack.pop();
    const Node& n = nodes_[index];
    ++st.nodes_visited;
    if (!n.bounds.overlaps(box)) continue;
    for (const ProxyId id : n.items) {
      ++st.pairs_tested;
      if (proxies_[id].box.overlaps(box) && !visit(id)) return;
    }
    if (!n.internal()) continue;
    const Interval iv = project(n.normal, box);
    if (n.middle != kNull) stack.push(n.middle);
    if (iv.hi >= n.front_min) stack.push(n.front);
    if (iv.lo <= n.back_max) stack.push(n.back);
  }
}

template <RayCallback OnRay>
BroadPhaseStats BspTree::query_ray(const Ray& ray, Real max_t, OnRay&& on_ray) const {
  BroadPhaseStats st;
  if (!detail::ray_input_ok(ray, max_t) || nodes_.empty()) return st;
  const detail::SlabRay slab(ray);
  Real limit = max_t;
  detail::TraversalStack<std::uint32_t, 192> stack;
  stack.push(0);
  while (!stack.empty()) {
    const Node& n = nodes_[stack.pop()];
    ++st.nodes_visited;
    Real t;
    if (!slab.enter(n.bounds, limit, t)) continue;
    for (const ProxyId id : n.items) {
      ++st.pairs_tested;
      const auto hit = geometry::ray_aabb(ray, limit, proxies_[id].box);
      if (!hit) continue;
      ++st.pairs_found;
      if (!detail::apply_ray_result(on_ray(id, hit->t), limit)) return st;
    }
    if (n.internal()) {
      if (n.middle != kNull) stack.push(n.middle);
      stack.push(n.front);
      stack.push(n.back);
    }
  }
  return st;
}

}  // namespace proxima
