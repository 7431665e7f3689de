/// @file region_quadtree.cpp
/// Bucket region quadtree over x and y, after Samet (The Design and Analysis of Spatial
/// Data Structures, 1990: region quadtrees, bucket splitting) and Ericson (Real-Time
/// Collision Detection, 7.3: objects straddling cells stored in every cell they overlap,
/// pairs reported once through a reference point as for the grids of 7.1).
///
/// Steps: 1. the root cell covers the boxes' x-y extent, doubling towards any box outside it (the
/// old root becomes one quadrant of the new one, its bounds kept exactly; an empty root is
/// replaced by a cell around the box instead); 2. a box descends into
/// every quadrant whose closed cell its x-y extent overlaps and is linked into each leaf reached
/// (children created on demand); 3. a leaf whose boxes not covering its cell exceed the bucket
/// splits when that at least halves its pair tests (header; a refusal is weighed again after
/// count / 2 insertions): its entries move to the quadrants they overlap (one more entry per extra
/// quadrant), recursively; 4. a move that leaves a box in the same leaves only refreshes its
/// entries' covering flags; 5. child cells are the parent's bounds cut at its stored split lines,
/// so cells nest and tile exactly despite rounding, and the once-only rule (half-open owner cells,
/// header) names one leaf per point; 6. removal unlinks the proxy's entries and deletes the leaves
/// left empty, and internal nodes left childless; 7. find_pairs gathers the leaves' boxes and tests
/// each leaf's boxes pairwise.

#include <proxima/broadphase/pair_tracker.hpp>
#include <proxima/broadphase/parallel_pairs.hpp>
#include <proxima/broadphase/region_quadtree.hpp>

#include <atomic>
#include <cmath>

#include "broadphase/structure_support.hpp"

namespace proxima {

namespace {

/// Leaves holding more boxes than this are sorted on x and swept.
constexpr std::uint32_t kSweepAbove = 16;

}  // namespace

RegionQuadtree::RegionQuadtree(std::uint32_t bucket, int max_depth)
    : bucket_(std::max<std::uint32_t>(bucket, 1)), max_depth_(std::clamp(max_depth, 0, 30)) {}

// ---- cells --------------------------------------------------------------------------------

std::int32_t RegionQuadtree::new_node(const Cell& cell, std::int32_t parent) {
  std::int32_t index;
  if (!free_nodes_.empty()) {
    index = free_nodes_.back();
    free_nodes_.pop_back();
  } else {
    index = std::int32_t(nodes_.size());
    nodes_.emplace_back();
  }
  Node& n = nodes_[std::size_t(index)];
  n = Node{};
  n.cell = cell;
  n.parent = parent;
  return index;
}

RegionQuadtree::Cell RegionQuadtree::quadrant(std::int32_t node, int q) const {
  const Node& n = nodes_[std::size_t(node)];
  return quadrant_of(n.cell, n.mid, q);
}

bool RegionQuadtree::owns(std::int32_t node, Real x, Real y) const {
  const Cell& c = nodes_[std::size_t(node)].cell;
  const Cell& root = nodes_[std::size_t(root_)].cell;
  const Real p[2] = {x, y};
  for (int k = 0; k < 2; ++k) {
    if (p[k] < c.lo[k] || p[k] > c.hi[k]) return false;
    if (p[k] == c.hi[k] && c.hi[k] != root.hi[k]) return false;  // upper edges are the neighbour's
  }
  return true;
}

// ---- placement ------------------------------------------------------------------------------

void RegionQuadtree::make_room(const Aabb& box) {
  if (root_ != kNil && nodes_[std::size_t(root_)].leaf && nodes_[std::size_t(root_)].count == 0) {
    // An empty root (its last box removed or moved away) is not grown: a root grown above it
    // would keep it as an empty quadrant. A cell around the box replaces it.
    nodes_[std::size_t(root_)].live = false;
    free_nodes_.push_back(root_);
    root_ = kNil;
  }
  if (root_ == kNil) {
    // A square around the box, never empty (a point gets a small cell).
    const Vec3 c = box.center();
    Real half = std::max(box.half_extents().x, box.half_extents().y);
    if (!(half > 0)) half = std::max(Real(1), std::max(std::abs(c.x), std::abs(c.y)) * Real(1e-6));
    root_ = new_node(Cell{{c.x - half, c.y - half}, {c.x + half, c.y + half}}, kNil);
  }
  while (!holds(nodes_[std::size_t(root_)].cell, box)) grow_root(box);
}

void RegionQuadtree::grow_root(const Aabb& box) {
  // Double the root towards the box: the old root becomes the quadrant on the other side,
  // and its bounds become the new root's split lines, exactly.
  const Cell old = nodes_[std::size_t(root_)].cell;
  Cell cell = old;
  Real mid[2];
  int q = 0;
  for (int k = 0; k < 2; ++k) {
    const Real width = old.hi[k] - old.lo[k];
    if (box.min[k] < old.lo[k]) {
      cell.lo[k] = old.lo[k] - width;
      mid[k] = old.lo[k];
      q |= 1 << k;  // the old root is the upper quadrant on axis k
    } else {
      cell.hi[k] = old.hi[k] + width;
      mid[k] = old.hi[k];
    }
  }
  const std::int32_t top = new_node(cell, kNil);
  Node& t = nodes_[std::size_t(top)];
  t.leaf = false;
  t.mid[0] = mid[0];
  t.mid[1] = mid[1];
  t.child[q] = root_;
  t.children = 1;
  nodes_[std::size_t(root_)].parent = top;
  root_ = top;
  // The old root's edges are inside the new root now: a stored box touching them also meets
  // the new quadrants beyond, so it is placed again.
  for (const ProxyId id : proxies_.ids()) {
    if (first_own_[id] == kNone || inside(old, proxies_[id].box)) continue;
    remove_entries(id);
    add(root_, 0, id, proxies_[id].box);
  }
}

std::int32_t RegionQuadtree::child_for(std::int32_t node, int q) {
  const std::int32_t existing = nodes_[std::size_t(node)].child[q];
  if (existing != kNil) return existing;
  const std::int32_t created = new_node(quadrant(node, q), node);  // may reallocate nodes_
  nodes_[std::size_t(node)].child[q] = created;
  ++nodes_[std::size_t(node)].children;
  return created;
}

void RegionQuadtree::add_entry(std::int32_t leaf, ProxyId id, const Aabb& box, std::uint32_t entry) {
  Node& n = nodes_[std::size_t(leaf)];
  Entry& e = entries_[entry];
  e.id = id;
  e.leaf = leaf;
  e.covers = covers(box, n.cell);
  e.prev = kNone;
  e.next = n.first;
  if (n.first != kNone) entries_[n.first].prev = entry;
  n.first = entry;
  ++n.count;
  if (!e.covers) ++n.partial;
}

std::uint32_t RegionQuadtree::own_entry(ProxyId id) {
  std::uint32_t entry;
  if (!free_entries_.empty()) {
    entry = free_entries_.back();
    free_entries_.pop_back();
  } else {
    entry = std::uint32_t(entries_.size());
    entries_.emplace_back();
  }
  entries_[entry].next_own = first_own_[id];
  first_own_[id] = entry;
  return entry;
}

void RegionQuadtree::add(std::int32_t node, int depth, ProxyId id, const Aabb& box) {
  if (nodes_[std::size_t(node)].leaf) {
    add_entry(node, id, box, own_entry(id));
    split(node, depth);
    return;
  }
  for (int q = 0; q < 4; ++q) {
    if (meets(quadrant(node, q), box)) add(child_for(node, q), depth + 1, id, box);
  }
}

bool RegionQuadtree::split_pays(std::int32_t leaf, const Real (&mid)[2]) const {
  // The pair tests of the four children (n_q boxes each, boxes straddling the split lines
  // counted in every quadrant they meet) must be at most half those of the leaf:
  // sum n_q^2 <= n^2 / 2. Coincident boxes, or a crowd straddling the split lines, would
  // only be copied into the children (and split again there: the region quadtree's blow-up).
  const Node& n = nodes_[std::size_t(leaf)];
  std::uint64_t in[4] = {0, 0, 0, 0};
  for (std::uint32_t e = n.first; e != kNone; e = entries_[e].next) {
    const Aabb& box = proxies_[entries_[e].id].box;
    for (int q = 0; q < 4; ++q) in[q] += meets(quadrant_of(n.cell, mid, q), box) ? 1 : 0;
  }
  const std::uint64_t tests = in[0] * in[0] + in[1] * in[1] + in[2] * in[2] + in[3] * in[3];
  return 2 * tests <= std::uint64_t(n.count) * n.count;
}

void RegionQuadtree::split(std::int32_t leaf, int depth) {
  Node& n = nodes_[std::size_t(leaf)];
  if (n.partial <= bucket_ || depth >= max_depth_) return;
  if (n.retry_in > 0) {
    --n.retry_in;  // a refused split is weighed again after count / 2 more insertions
    return;
  }
  Real mid[2];
  for (int k = 0; k < 2; ++k) {
    mid[k] = n.cell.lo[k] + (n.cell.hi[k] - n.cell.lo[k]) * Real(0.5);
    if (!(mid[k] > n.cell.lo[k] && mid[k] < n.cell.hi[k])) return;  // too small to halve
  }
  if (!split_pays(leaf, mid)) {
    n.retry_in = n.count / 2;
    return;
  }
  std::uint32_t e = n.first;
  n.leaf = false;
  n.mid[0] = mid[0];
  n.mid[1] = mid[1];
  n.first = kNone;
  n.count = 0;
  n.partial = 0;
  // Each entry moves to the first quadrant its box overlaps; the other quadrants it
  // overlaps get new entries. The children split in turn once all are placed.
  while (e != kNone) {
    const std::uint32_t next = entries_[e].next;
    const ProxyId id = entries_[e].id;
    const Aabb& box = proxies_[id].box;
    bool moved = false;
    for (int q = 0; q < 4; ++q) {
      if (!meets(quadrant(leaf, q), box)) continue;
      const std::int32_t child = child_for(leaf, q);
      if (!moved) {
        add_entry(child, id, box, e);
        moved = true;
      } else {
        add_entry(child, id, box, own_entry(id));
      }
    }
    e = next;
  }
  for (int q = 0; q < 4; ++q) {
    const std::int32_t child = nodes_[std::size_t(leaf)].child[q];
    if (child != kNil) split(child, depth + 1);
  }
}

void RegionQuadtree::unlink_entry(std::uint32_t entry) {
  const Entry& e = entries_[entry];
  Node& n = nodes_[std::size_t(e.leaf)];
  if (e.prev != kNone) {
    entries_[e.prev].next = e.next;
  } else {
    n.first = e.next;
  }
  if (e.next != kNone) entries_[e.next].prev = e.prev;
  --n.count;
  if (!e.covers) --n.partial;
}

void RegionQuadtree::remove_entries(ProxyId id) {
  std::uint32_t e = first_own_[id];
  while (e != kNone) {
    const std::uint32_t next = entries_[e].next_own;
    const std::int32_t leaf = entries_[e].leaf;
    unlink_entry(e);
    free_entries_.push_back(e);
    prune(leaf);
    e = next;
  }
  first_own_[id] = kNone;
}

void RegionQuadtree::prune(std::int32_t node) {
  while (node != kNil) {
    Node& n = nodes_[std::size_t(node)];
    if (!n.leaf && n.children == 0) n.leaf = true;  // a childless internal node is an empty leaf
    if (!n.leaf || n.count != 0 || node == root_) return;
    const std::int32_t parent = n.parent;
    Node& p = nodes_[std::size_t(parent)];
    for (std::int32_t& ch : p.child) {
      if (ch == node) ch = kNil;
    }
    --p.children;
    n.live = false;
    free_nodes_.push_back(node);
    node = parent;
  }
}

// ---- interface ------------------------------------------------------------------------------

BroadPhaseStatus RegionQuadtree::insert(ProxyId id, const Aabb& box, ProxyKind kind, ProxyFilter filter) {
  const BroadPhaseStatus status = proxies_.insert(id, box, kind, filter);
  if (status != BroadPhaseStatus::Ok) return status;
  if (id >= first_own_.size()) first_own_.resize(std::size_t(id) + 1, kNone);
  make_room(box);
  add(root_, 0, id, box);
  return status;
}

BroadPhaseStatus RegionQuadtree::remove(ProxyId id) {
  if (!proxies_.contains(id)) return BroadPhaseStatus::UnknownId;
  remove_entries(id);
  return proxies_.remove(id);
}

bool RegionQuadtree::same_leaves(ProxyId id, const Aabb& box) const {
  // The lowest ancestor of an entry's leaf holding the box off its edges (or the root holding
  // it) has every leaf the box meets below it; when each entry's leaf meets the box and their
  // number is that of the leaves met, the two sets are equal.
  const Entry& first = entries_[first_own_[id]];
  std::int32_t top = first.leaf;
  if (first.next_own == kNone && inside(nodes_[std::size_t(top)].cell, box)) return true;  // one leaf, off its edges
  while (top != root_ && !inside(nodes_[std::size_t(top)].cell, box)) top = nodes_[std::size_t(top)].parent;
  if (top == root_ && !holds(nodes_[std::size_t(root_)].cell, box)) return false;
  std::size_t own = 0;
  for (std::uint32_t e = first_own_[id]; e != kNone; e = entries_[e].next_own) {
    if (!meets(nodes_[std::size_t(entries_[e].leaf)].cell, box)) return false;
    ++own;
  }
  bool complete = true;
  return leaves_met(top, box, complete) == own && complete;
}

BroadPhaseStatus RegionQuadtree::update(ProxyId id, const Aabb& box) {
  const BroadPhaseStatus status = proxies_.check_update(id, box);
  if (status != BroadPhaseStatus::Ok) return status;
  proxies_[id].box = box;
  if (same_leaves(id, box)) {
    // Only the covering flags may change (a leaf that gains partial boxes splits at its next
    // insertion).
    for (std::uint32_t e = first_own_[id]; e != kNone; e = entries_[e].next_own) {
      Entry& en = entries_[e];
      Node& leaf = nodes_[std::size_t(en.leaf)];
      const bool now = covers(box, leaf.cell);
      if (now != en.covers) leaf.partial = now ? leaf.partial - 1 : leaf.partial + 1;
      en.covers = now;
    }
    return status;
  }
  remove_entries(id);
  make_room(box);
  add(root_, 0, id, box);
  return status;
}

BroadPhaseStatus RegionQuadtree::update(std::span<const ProxyUpdate> updates) {
  const BroadPhaseStatus status = proxies_.check_updates(updates);
  if (status != BroadPhaseStatus::Ok) return status;
  for (const ProxyUpdate& u : updates) update(u.id, u.box);
  return status;
}

void RegionQuadtree::rebuild() {
  nodes_.clear();
  free_nodes_.clear();
  entries_.clear();
  free_entries_.clear();
  std::fill(first_own_.begin(), first_own_.end(), kNone);
  root_ = kNil;
  const auto ids = proxies_.ids();
  if (ids.empty()) return;
  Aabb world = Aabb::empty();
  for (const ProxyId id : ids) world.grow(proxies_[id].box);
  make_room(world);
  for (const ProxyId id : ids) {
    make_room(proxies_[id].box);  // the fitted root may miss a box by rounding
    add(root_, 0, id, proxies_[id].box);
  }
}

// ---- pairs ----------------------------------------------------------------------------------

void RegionQuadtree::gather() {
  leaves_.clear();
  item_begin_.clear();
  std::uint32_t position = 0;
  for (std::size_t i = 0; i < nodes_.size(); ++i) {
    const Node& n = nodes_[i];
    if (!n.live || !n.leaf || n.count < 2) continue;
    leaves_.push_back(std::int32_t(i));
    item_begin_.push_back(position);
    position += n.count;
  }
  item_begin_.push_back(position);
  items_.resize(position);
  for (std::size_t k = 0; k < leaves_.size(); ++k) {
    const Node& n = nodes_[std::size_t(leaves_[k])];
    std::uint32_t at = item_begin_[k];
    for (std::uint32_t e = n.first; e != kNone; e = entries_[e].next) {
      const ProxyId id = entries_[e].id;
      items_[at++] = {proxies_[id].box, id};
    }
    if (n.count > kSweepAbove) {
      std::sort(items_.begin() + item_begin_[k], items_.begin() + at,
                [](const Item& x, const Item& y) { return x.box.min.x < y.box.min.x; });
    }
  }
}

void RegionQuadtree::leaf_pairs(std::size_t leaf, std::vector<ProxyPair>& out, std::uint64_t& tested) const {
  const std::int32_t node = leaves_[leaf];
  const std::uint32_t begin = item_begin_[leaf];
  const std::uint32_t end = item_begin_[leaf + 1];
  const bool sorted = end - begin > kSweepAbove;
  for (std::uint32_t i = begin; i < end; ++i) {
    const Item& a = items_[i];
    for (std::uint32_t j = i + 1; j < end; ++j) {
      const Item& b = items_[j];
      if (sorted && b.box.min.x > a.box.max.x) break;
      ++tested;
      if (!a.box.overlaps(b.box)) continue;
      if (!owns(node, std::max(a.box.min.x, b.box.min.x), std::max(a.box.min.y, b.box.min.y))) continue;
      if (detail::may_pair(proxies_[a.id], proxies_[b.id])) out.push_back(detail::ordered_pair(a.id, b.id));
    }
  }
}

void RegionQuadtree::find_pairs(std::vector<ProxyPair>& out, Executor& executor) {
  out.clear();
  stats_ = {};
  if (root_ == kNil) return;
  gather();
  std::atomic<std::uint64_t> tested{0};
  parallel_pair_chunks(
      leaves_.size(), executor, out,
      [&](std::size_t begin, std::size_t end, std::vector<ProxyPair>& part) {
        std::uint64_t count = 0;
        for (std::size_t k = begin; k < end; ++k) leaf_pairs(k, part, count);
        tested.fetch_add(count, std::memory_order_relaxed);
      },
      64);
  sort_pairs(out, sort_scratch_);
  stats_.nodes_visited = leaves_.size();
  stats_.pairs_tested = tested.load(std::memory_order_relaxed);
  stats_.pairs_found = out.size();
}

// ---- queries ----------------------------------------------------------------------------

bool RegionQuadtree::ray_meets(const Ray& ray, Real max_t, const Cell& cell) {
  // Slab test of the clipped ray against the cell grown by a margin of many ulps of the
  // coordinates involved: a proxy's owner point (the rounded entry point) lies within
  // rounding of the ray, so its owner leaf is never pruned. The boxes are tested exactly.
  Real t0 = 0;
  Real t1 = max_t;
  for (int k = 0; k < 2; ++k) {
    const Real o = ray.origin[k];
    const Real d = ray.direction[k];
    const Real margin = (std::abs(cell.lo[k]) + std::abs(cell.hi[k]) + std::abs(o)) *
                            (Real(256) * std::numeric_limits<Real>::epsilon()) +
                        std::numeric_limits<Real>::min();
    const Real lo = cell.lo[k] - margin;
    const Real hi = cell.hi[k] + margin;
    if (d == Real(0)) {
      if (o < lo || o > hi) return false;
      continue;
    }
    Real ta = (lo - o) / d;
    Real tb = (hi - o) / d;
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
    if (detail::slab_interval_empty(t0, t1)) return false;
  }
  return true;
}

// ---- checks -------------------------------------------------------------------------------

bool RegionQuadtree::check_node(std::int32_t node, std::size_t& entries) const {
  const Node& n = nodes_[std::size_t(node)];
  if (!n.live) return false;
  if (n.leaf) {
    if (node != root_ && n.count == 0) return false;  // empty leaf kept
    std::uint32_t count = 0;
    std::uint32_t partial = 0;
    std::uint32_t previous = kNone;
    for (std::uint32_t e = n.first; e != kNone; e = entries_[e].next) {
      const Entry& en = entries_[e];
      if (en.leaf != node || en.prev != previous || !proxies_.contains(en.id)) return false;
      if (en.covers != covers(proxies_[en.id].box, n.cell) || ++count > entries_.size()) return false;
      if (!en.covers) ++partial;
      previous = e;
    }
    entries += count;
    return count == n.count && partial == n.partial;
  }
  std::uint32_t children = 0;
  for (int q = 0; q < 4; ++q) {
    const std::int32_t ch = n.child[q];
    if (ch == kNil) continue;
    ++children;
    const Cell want = quadrant(node, q);
    const Cell& got = nodes_[std::size_t(ch)].cell;
    for (int k = 0; k < 2; ++k) {
      if (got.lo[k] != want.lo[k] || got.hi[k] != want.hi[k]) return false;
    }
    if (nodes_[std::size_t(ch)].parent != node || !check_node(ch, entries)) return false;
  }
  return children == n.children && children != 0;
}

std::size_t RegionQuadtree::leaves_met(std::int32_t node, const Aabb& box, bool& complete) const {
  const Node& n = nodes_[std::size_t(node)];
  if (n.leaf) return 1;
  std::size_t met = 0;
  for (int q = 0; q < 4; ++q) {
    if (!meets(quadrant(node, q), box)) continue;
    if (n.child[q] == kNil) {
      complete = false;  // the box overlaps a quadrant that has no node
      continue;
    }
    met += leaves_met(n.child[q], box, complete);
  }
  return met;
}

bool RegionQuadtree::check_proxy(ProxyId id) const {
  const Aabb& box = proxies_[id].box;
  if (!holds(nodes_[std::size_t(root_)].cell, box)) return false;
  std::size_t own = 0;
  for (std::uint32_t e = first_own_[id]; e != kNone; e = entries_[e].next_own) {
    const Entry& en = entries_[e];
    if (en.id != id || !nodes_[std::size_t(en.leaf)].live || !meets(nodes_[std::size_t(en.leaf)].cell, box)) {
      return false;
    }
    if (++own > entries_.size()) return false;
  }
  bool complete = true;
  return own == leaves_met(root_, box, complete) && complete;
}

bool RegionQuadtree::validate() const {
  if (!proxies_.validate()) return false;
  const auto ids = proxies_.ids();
  if (root_ == kNil) return ids.empty() && node_count() == 0 && entry_count() == 0;
  if (nodes_[std::size_t(root_)].parent != kNil) return false;
  std::size_t entries = 0;
  if (!check_node(root_, entries) || entries != entry_count()) return false;
  for (const ProxyId id : ids) {
    if (!check_proxy(id)) return false;
  }
  return true;
}

int RegionQuadtree::depth() const {
  int deepest = 0;
  for (const Node& node : nodes_) {
    if (!node.live) continue;
    int d = 0;
    for (std::int32_t p = node.parent; p != kNil; p = nodes_[std::size_t(p)].parent) ++d;
    deepest = std::max(deepest, d);
  }
  return deepest;
}

std::size_t RegionQuadtree::memory_bytes() const {
  return detail::capacity_bytes(first_own_) + detail::capacity_bytes(nodes_) + detail::capacity_bytes(free_nodes_) +
         detail::capacity_bytes(entries_) + detail::capacity_bytes(free_entries_) + detail::capacity_bytes(leaves_) +
         detail::capacity_bytes(item_begin_) + detail::capacity_bytes(items_) + sort_scratch_.keys.capacity() * 16 +
         proxies_.size() * (sizeof(detail::ProxyRecord) + sizeof(ProxyId));
}

}  // namespace proxima
