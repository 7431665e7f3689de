#pragma once
/// @file region_quadtree.hpp
/// RegionQuadtree ("region_quadtree"): the bucket region quadtree over x and y (Samet, The
/// Design and Analysis of Spatial Data Structures, 1990, ch. 1-2; Ericson, Real-Time
/// Collision Detection, 7.3), for flat and 2.5D worlds: the 2D module's rectangles (boxes with
/// z = [0, 0]), terrain levels, top-down games. z is never split, but every overlap test is
/// the full closed 3D test, so the answers are exactly the brute force's for any boxes.
///
/// Cells are squares (up to rounding) split at their centre lines into four quadrant
/// children. A box is stored in every leaf whose closed cell its x-y extent overlaps (not at
/// the smallest cell containing it: a box straddling a centre line would then sit at the
/// root, whatever its size; the loose quadtree, "quadtree", is the one-node-per-box answer to
/// that). A leaf splits when more than `bucket` of its boxes do not cover its whole cell
/// (boxes covering the cell go to every child, so splitting never separates them) and the
/// split at least halves the pair tests (sum over the quadrants of the squared box counts,
/// boxes straddling the centre lines counted in each quadrant they meet): coincident boxes,
/// or a crowd straddling the centre lines, are not split at all (the region quadtree's
/// blow-up on heavily overlapping boxes), unless it is at the maximum depth below the root or
/// its cell is too small to halve. A refused split is weighed again after count / 2 more
/// insertions into the leaf (amortised O(1) per insertion). Leaves are
/// deleted when they empty; the root region doubles towards a box that leaves it (no fixed
/// world region, no overflow list). Nodes and leaf entries live in pools addressed by index.
///
/// Once-only rule (no per-query allocation, no marks): cells own the half-open
/// [lo, hi) x [lo, hi) (the root's upper edges closed), so each point of the root region has
/// one owner leaf. A pair is reported only by the leaf owning the lower corner of its two
/// boxes' x-y intersection; a box query reports a proxy only in the leaf owning the lower
/// corner of the proxy's and the query's intersection; a ray query only in the leaf owning
/// the entry point (clamped into the box). Both boxes contain that point, so both are stored
/// in its owner leaf.
///
/// Steps of find_pairs: 1. the boxes of every leaf holding two or more are gathered into one
/// array (sorted on x when the leaf holds many); 2. each leaf tests its boxes pairwise (a
/// sweep on x), keeping the pairs it owns; leaves are independent, so the executor of
/// find_pairs(out, executor) runs chunks of them; 3. the pairs are radix-sorted.
/// O(entries + sum over leaves of their box pairs). Queries walk the cells the box or ray
/// meets, in O(depth + cells met + entries in them).

#include <proxima/broadphase/broadphase.hpp>
#include <proxima/broadphase/broadphase_queries.hpp>
#include <proxima/broadphase/pair_tracker.hpp>
#include <proxima/broadphase/proxy_table.hpp>
#include <proxima/core/executor.hpp>

#include <algorithm>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

namespace proxima {

/// Bucket region quadtree over x and y. See the file comment.
class RegionQuadtree : public BroadPhaseQueries<RegionQuadtree> {
 public:
  /// A leaf splits when more than `bucket` (>= 1) of its boxes do not cover its cell and it
  /// is less than `max_depth` (0..30) levels below the root; out-of-range values are clamped.
  explicit RegionQuadtree(std::uint32_t bucket = 8, int max_depth = 12);

  /// Adds a proxy to every leaf its box overlaps. O(depth + leaves overlapped).
  BroadPhaseStatus insert(ProxyId id, const Aabb& box, ProxyKind kind = ProxyKind::Moving, ProxyFilter filter = {});
  /// Removes a proxy (leaves left empty are deleted). O(leaves it was in).
  BroadPhaseStatus remove(ProxyId id);
  /// Moves a proxy: its entries are kept when the new box meets the same leaves (the common
  /// case of small moves), else it is taken out of its leaves and added again.
  /// O(depth + leaves overlapped).
  BroadPhaseStatus update(ProxyId id, const Aabb& box);
  /// Moves many proxies, all or nothing. O(m (depth + leaves overlapped)).
  BroadPhaseStatus update(std::span<const ProxyUpdate> updates);
  /// Rebuilds the tree around the current boxes (a root fitted to their x-y extent).
  void rebuild();
  /// find_pairs(out): the serial form of the one below (BroadPhaseQueries).
  using BroadPhaseQueries<RegionQuadtree>::find_pairs;
  /// Every pair, sorted (broadphase.hpp), the leaves cut into chunks run by `executor` (same
  /// output for every executor).
  void find_pairs(std::vector<ProxyPair>& out, Executor& executor);
  /// Proxies whose box the ray enters at t <= the current max fraction (t of
  /// geometry::ray_aabb), each once, by a walk of the cells the clipped ray meets.
  template <RayCallback OnRay>
  BroadPhaseStats query_ray(const Ray& ray, Real max_t, OnRay&& on_ray) const;
  /// Checks the node links, the leaf lists and counts, and that every box is stored in
  /// exactly the leaves it overlaps. O(entries + nodes).
  bool validate() const;
  /// Number of proxies.
  std::size_t size() const { return proxies_.size(); }
  /// Number of live nodes (leaves and internal nodes).
  std::size_t node_count() const { return nodes_.size() - free_nodes_.size(); }
  /// Number of leaf entries (a box is counted once per leaf holding it).
  std::size_t entry_count() const { return entries_.size() - free_entries_.size(); }
  /// Depth of the deepest live node (root = 0). O(nodes).
  int depth() const;
  /// Bytes held by the structure's buffers (capacity).
  std::size_t memory_bytes() const;

 private:
  friend class BroadPhaseQueries<RegionQuadtree>;
  static constexpr std::int32_t kNil = -1;
  static constexpr std::uint32_t kNone = 0xffffffffu;
  /// A cell: [lo, hi] on x (index 0) and y (index 1), world frame.
  struct Cell {
    Real lo[2];
    Real hi[2];
  };
  struct Node {
    Cell cell{};
    Real mid[2] = {0, 0};                              // split lines of an internal node
    std::int32_t child[4] = {kNil, kNil, kNil, kNil};  // quadrant q: x upper when q & 1, y when q & 2
    std::int32_t parent = kNil;
    std::uint32_t first = kNone;  // leaf: first entry of its list
    std::uint32_t count = 0;      // leaf: entries
    std::uint32_t partial = 0;    // leaf: entries whose box does not cover the cell
    std::uint32_t children = 0;   // internal: live children
    std::uint32_t retry_in = 0;   // leaf: insertions before a refused split is weighed again
    bool leaf = true;
    bool live = true;
  };
  /// One box in one leaf.
  struct Entry {
    ProxyId id = 0;
    std::int32_t leaf = kNil;
    std::uint32_t prev = kNone;      // in the leaf's list
    std::uint32_t next = kNone;      // in the leaf's list
    std::uint32_t next_own = kNone;  // the proxy's next entry
    bool covers = false;             // the box covers the leaf's cell
  };
  struct Item {
    Aabb box;
    ProxyId id;
  };

  std::int32_t new_node(const Cell& cell, std::int32_t parent);
  /// Quadrant q of `cell` cut at `mid`.
  static Cell quadrant_of(const Cell& cell, const Real (&mid)[2], int q) {
    Cell c = cell;
    for (int k = 0; k < 2; ++k) {
      if ((q >> k) & 1) {
        c.lo[k] = mid[k];
      } else {
        c.hi[k] = mid[k];
      }
    }
    return c;
  }
  Cell quadrant(std::int32_t node, int q) const;
  /// The box's x-y extent overlaps the closed cell.
  static bool meets(const Cell& cell, const Aabb& box) {
    return box.min.x <= cell.hi[0] && box.max.x >= cell.lo[0] && box.min.y <= cell.hi[1] && box.max.y >= cell.lo[1];
  }
  /// The box's x-y extent contains the cell.
  static bool covers(const Aabb& box, const Cell& cell) {
    return box.min.x <= cell.lo[0] && box.max.x >= cell.hi[0] && box.min.y <= cell.lo[1] && box.max.y >= cell.hi[1];
  }
  /// The cell contains the box's x-y extent.
  static bool holds(const Cell& cell, const Aabb& box) {
    return cell.lo[0] <= box.min.x && box.max.x <= cell.hi[0] && cell.lo[1] <= box.min.y && box.max.y <= cell.hi[1];
  }
  /// The cell contains the box's x-y extent off its edges (the box meets no other cell).
  static bool inside(const Cell& cell, const Aabb& box) {
    return cell.lo[0] < box.min.x && box.max.x < cell.hi[0] && cell.lo[1] < box.min.y && box.max.y < cell.hi[1];
  }
  bool owns(std::int32_t node, Real x, Real y) const;
  void make_room(const Aabb& box);
  void grow_root(const Aabb& box);
  void add(std::int32_t node, int depth, ProxyId id, const Aabb& box);
  std::uint32_t own_entry(ProxyId id);
  void add_entry(std::int32_t leaf, ProxyId id, const Aabb& box, std::uint32_t entry);
  std::int32_t child_for(std::int32_t node, int q);
  bool split_pays(std::int32_t leaf, const Real (&mid)[2]) const;
  void split(std::int32_t leaf, int depth);
  void unlink_entry(std::uint32_t entry);
  void remove_entries(ProxyId id);
  void prune(std::int32_t node);
  void gather();
  void leaf_pairs(std::size_t leaf, std::vector<ProxyPair>& out, std::uint64_t& tested) const;
  bool same_leaves(ProxyId id, const Aabb& box) const;
  bool check_node(std::int32_t node, std::size_t& entries) const;
  bool check_proxy(ProxyId id) const;
  std::size_t leaves_met(std::int32_t node, const Aabb& box, bool& complete) const;
  template <class Visit>
  void visit_box(const Aabb& box, BroadPhaseStats& st, Visit&& visit) const;
  template <class Visit>
  bool visit_node(std::int32_t node, const Aabb& box, BroadPhaseStats& st, Visit& visit) const;
  template <class OnRay>
  bool ray_node(std::int32_t node, const Ray& ray, Real& limit, BroadPhaseStats& st, OnRay& on_ray) const;
  static bool ray_meets(const Ray& ray, Real max_t, const Cell& cell);

  std::uint32_t bucket_;
  int max_depth_;
  detail::ProxyTable proxies_;
  std::vector<std::uint32_t> first_own_;  // by id: the proxy's first entry
  std::vector<Node> nodes_;
  std::vector<std::int32_t> free_nodes_;
  std::vector<Entry> entries_;
  std::vector<std::uint32_t> free_entries_;
  std::int32_t root_ = kNil;
  // find_pairs scratch, by gathered leaf unless said otherwise.
  std::vector<std::int32_t> leaves_;       // leaves holding two or more boxes
  std::vector<std::uint32_t> item_begin_;  // first gathered position (one extra at the end)
  std::vector<Item> items_;                // by gathered position
  PairSortScratch sort_scratch_;
  BroadPhaseStats stats_;
};

// ---- queries (templates on the callback) ------------------------------------------------

template <class Visit>
bool RegionQuadtree::visit_node(std::int32_t node, const Aabb& box, BroadPhaseStats& st, Visit& visit) const {
  const Node& n = nodes_[std::size_t(node)];
  ++st.nodes_visited;
  if (n.leaf) {
    for (std::uint32_t e = n.first; e != kNone; e = entries_[e].next) {
      const ProxyId id = entries_[e].id;
      const Aabb& b = proxies_[id].box;
      ++st.pairs_tested;
      if (!b.overlaps(box) || !owns(node, std::max(b.min.x, box.min.x), std::max(b.min.y, box.min.y))) continue;
      if (!visit(id)) return false;
    }
    return true;
  }
  for (const std::int32_t child : n.child) {
    if (child == kNil || !meets(nodes_[std::size_t(child)].cell, box)) continue;
    if (!visit_node(child, box, st, visit)) return false;
  }
  return true;
}

template <class Visit>
void RegionQuadtree::visit_box(const Aabb& box, BroadPhaseStats& st, Visit&& visit) const {
  if (root_ == kNil || !meets(nodes_[std::size_t(root_)].cell, box)) return;
  visit_node(root_, box, st, visit);
}

template <class OnRay>
bool RegionQuadtree::ray_node(std::int32_t node, const Ray& ray, Real& limit, BroadPhaseStats& st,
                              OnRay& on_ray) const {
  const Node& n = nodes_[std::size_t(node)];
  if (!ray_meets(ray, limit, n.cell)) return true;
  ++st.nodes_visited;
  if (!n.leaf) {
    for (const std::int32_t child : n.child) {
      if (child != kNil && !ray_node(child, ray, limit, st, on_ray)) return false;
    }
    return true;
  }
  for (std::uint32_t e = n.first; e != kNone; e = entries_[e].next) {
    const ProxyId id = entries_[e].id;
    const Aabb& b = proxies_[id].box;
    ++st.pairs_tested;
    Real t = 0;
    if (!detail::ray_enters_box(ray, limit, b, t)) continue;
    // The entry point, clamped into the box: its owner leaf reports the proxy.
    const Real x = std::clamp(ray.origin.x + ray.direction.x * t, b.min.x, b.max.x);
    const Real y = std::clamp(ray.origin.y + ray.direction.y * t, b.min.y, b.max.y);
    if (!owns(node, x, y)) continue;
    ++st.pairs_found;
    if (!detail::apply_ray_result(on_ray(id, t), limit)) return false;
  }
  return true;
}

template <RayCallback OnRay>
BroadPhaseStats RegionQuadtree::query_ray(const Ray& ray, Real max_t, OnRay&& on_ray) const {
  BroadPhaseStats st;
  if (root_ == kNil || !detail::ray_input_ok(ray, max_t)) return st;
  Real limit = max_t;
  ray_node(root_, ray, limit, st, on_ray);
  return st;
}

static_assert(BroadPhaseStructure<RegionQuadtree>);

}  // namespace proxima
