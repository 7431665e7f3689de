/// @file kd_tree.cpp
/// KdTree: median-split kd-tree over box centres with two clip planes per node (bounding
/// interval hierarchy).
///
/// Steps:
/// 1. build: split the records at the median centre (std::nth_element) along the axis of
///    largest centre spread until a leaf holds at most leaf_size records; then refit.
/// 2. refit (bottom-up): each node's clip_left = max along its axis of the left subtree's boxes,
///    clip_right = min of the right subtree's; also measures the mean slab overlap.
/// 3. update: write the record's box and widen the clip planes on its path (conservative).
/// 4. queries descend into the left child when the query reaches below clip_left and into the
///    right child when it reaches above clip_right; leaves test the records' boxes.
/// 5. find_pairs: rebuild if needed (pending inserts, many removals, degraded slabs), else exact
///    refit (which also stores every subtree's box); then the tree against itself
///    (tree_pair_descent.hpp: simultaneous descent on the subtree boxes, Ericson 6.5.3);
///    radix-sorted.
/// References: C. Wächter, A. Keller, "Instant ray tracing: the bounding interval hierarchy",
/// EGSR 2006; C. Ericson, Real-Time Collision Detection, 7.3 (k-d trees).

#include <proxima/broadphase/kd_tree.hpp>
#include <proxima/broadphase/parallel_pairs.hpp>
#include <proxima/core/tolerance.hpp>
#include <proxima/geometry/raycast.hpp>

#include <algorithm>

#include "broadphase/batch_update_check.hpp"
#include "broadphase/tree_pair_descent.hpp"

namespace proxima {

KdTree::KdTree(const KdTreeConfig& config) : config_(config) {
  config_.leaf_size = std::max(1, config_.leaf_size);
  if (!(config_.rebuild_overlap >= Real(0))) config_.rebuild_overlap = Real(0);
}

// ---- build and refit --------------------------------------------------------------------------

std::uint32_t KdTree::build(std::uint32_t begin, std::uint32_t end, std::uint32_t parent, int depth) {
  const auto index = static_cast<std::uint32_t>(nodes_.size());
  nodes_.emplace_back();
  nodes_[index].parent = parent;
  const std::uint32_t count = end - begin;
  if (count <= static_cast<std::uint32_t>(config_.leaf_size) || depth >= 60) {
    Node& leaf = nodes_[index];
    leaf.leaf = true;
    leaf.begin = begin;
    leaf.count = count;
    for (std::uint32_t i = begin; i < end; ++i) {
      Proxy& p = proxies_[records_[i].id];
      p.slot = i;
      p.leaf = index;
    }
    return index;
  }
  Aabb centres = Aabb::empty();
  for (std::uint32_t i = begin; i < end; ++i) centres.grow(records_[i].box.center());
  const Vec3 e = centres.extents();
  const int axis = e.x >= e.y && e.x >= e.z ? 0 : (e.y >= e.z ? 1 : 2);
  const std::uint32_t mid = begin + count / 2;
  std::nth_element(records_.begin() + begin, records_.begin() + mid, records_.begin() + end,
                   [axis](const Record& a, const Record& b) {
                     const Real ca = a.box.min[axis] + a.box.max[axis];
                     const Real cb = b.box.min[axis] + b.box.max[axis];
                     return ca < cb || (ca == cb && a.id < b.id);
                   });
  nodes_[index].leaf = false;
  nodes_[index].axis = static_cast<std::uint8_t>(axis);
  build(begin, mid, index, depth + 1);  // left child = index + 1
  const std::uint32_t right = build(mid, end, index, depth + 1);
  nodes_[index].right = right;
  return index;
}

Aabb KdTree::refit(std::uint32_t node, double& overlap_sum, std::size_t& internal_count) {
  Node& n = nodes_[node];
  if (bounds_.size() != nodes_.size()) bounds_.resize(nodes_.size());
  if (n.leaf) {
    Aabb box = Aabb::empty();
    for (std::uint32_t i = n.begin; i < n.begin + n.count; ++i) {
      if (records_[i].id != kDead) box.grow(records_[i].box);
    }
    bounds_[node] = box;
    return box;
  }
  const Aabb left = refit(node + 1, overlap_sum, internal_count);
  const Aabb right = refit(nodes_[node].right, overlap_sum, internal_count);
  Node& m = nodes_[node];
  m.clip_left = left.max[m.axis];
  m.clip_right = right.min[m.axis];
  if (left.is_valid() && right.is_valid()) {
    const double width = static_cast<double>(std::max(left.max[m.axis], right.max[m.axis])) -
                         static_cast<double>(std::min(left.min[m.axis], right.min[m.axis]));
    const double overlap = static_cast<double>(m.clip_left) - static_cast<double>(m.clip_right);
    if (width > 0 && overlap > 0) overlap_sum += std::min(1.0, overlap / width);
    ++internal_count;
  }
  bounds_[node] = merge(left, right);
  return bounds_[node];
}

void KdTree::widen(std::uint32_t leaf, const Aabb& box) {
  std::uint32_t child = leaf;
  std::uint32_t parent = nodes_[leaf].parent;
  while (parent != kNull) {
    Node& p = nodes_[parent];
    if (child == parent + 1) {
      p.clip_left = std::max(p.clip_left, box.max[p.axis]);
    } else {
      p.clip_right = std::min(p.clip_right, box.min[p.axis]);
    }
    child = parent;
    parent = p.parent;
  }
  dirty_ = true;
}

void KdTree::rebuild() {
  records_.clear();
  pending_.clear();
  nodes_.clear();
  dead_ = 0;
  for (std::size_t id = 0; id < proxies_.size(); ++id) {
    Proxy& p = proxies_[id];
    if (p.place == Place::None) continue;
    p.place = Place::Tree;
    records_.push_back({p.box, static_cast<ProxyId>(id)});
  }
  build_overlap_ = 0;
  if (!records_.empty()) {
    build(0, static_cast<std::uint32_t>(records_.size()), kNull, 0);
    double sum = 0;
    std::size_t internal = 0;
    refit(0, sum, internal);
    build_overlap_ = internal ? sum / static_cast<double>(internal) : 0.0;
  }
  dirty_ = false;
  ++rebuilds_;
}

// ---- edits ------------------------------------------------------------------------------------

BroadPhaseStatus KdTree::insert(ProxyId id, const Aabb& box, ProxyKind kind, ProxyFilter filter) {
  const BroadPhaseStatus s = check_box(box);
  if (s != BroadPhaseStatus::Ok) return s;
  if (id < proxies_.size() && proxies_[id].place != Place::None) return BroadPhaseStatus::DuplicateId;
  if (id >= proxies_.size()) proxies_.resize(static_cast<std::size_t>(id) + 1);
  Proxy& p = proxies_[id];
  p.box = box;
  p.filter = filter;
  p.kind = kind;
  p.place = Place::Pending;
  p.slot = static_cast<std::uint32_t>(pending_.size());
  p.leaf = kNull;
  pending_.push_back(id);
  ++count_;
  return BroadPhaseStatus::Ok;
}

BroadPhaseStatus KdTree::remove(ProxyId id) {
  if (id >= proxies_.size() || proxies_[id].place == Place::None) return BroadPhaseStatus::UnknownId;
  Proxy& p = proxies_[id];
  if (p.place == Place::Tree) {
    records_[p.slot].id = kDead;
    ++dead_;
  } else {
    const ProxyId last = pending_.back();
    pending_[p.slot] = last;
    proxies_[last].slot = p.slot;
    pending_.pop_back();
  }
  p = Proxy{};
  --count_;
  return BroadPhaseStatus::Ok;
}

BroadPhaseStatus KdTree::update(ProxyId id, const Aabb& box) {
  if (id >= proxies_.size() || proxies_[id].place == Place::None) return BroadPhaseStatus::UnknownId;
  const BroadPhaseStatus s = check_box(box);
  if (s != BroadPhaseStatus::Ok) return s;
  Proxy& p = proxies_[id];
  p.box = box;
  if (p.place == Place::Tree) {
    records_[p.slot].box = box;
    widen(p.leaf, box);
  }
  return BroadPhaseStatus::Ok;
}

BroadPhaseStatus KdTree::update(std::span<const ProxyUpdate> updates) {
  const BroadPhaseStatus s = detail::check_batch(
      updates, [&](ProxyId id) { return id < proxies_.size() && proxies_[id].place != Place::None; });
  if (s != BroadPhaseStatus::Ok) return s;
  for (const ProxyUpdate& u : updates) update(u.id, u.box);
  return BroadPhaseStatus::Ok;
}

// ---- queries ----------------------------------------------------------------------------------

void KdTree::push_children(const Node& n, std::uint32_t index, const Ray& ray, const RayEntry& e, Real limit,
                           detail::TraversalStack<RayEntry, 192>& stack) {
  // Parameter intervals need no slack: a clip plane is one of its subtree's box coordinates
  // and the bound is computed as ray_aabb computes a slab, (plane - origin) / direction,
  // which rounding keeps monotone in the plane.
  const Real o = ray.origin[n.axis];
  const Real d = ray.direction[n.axis];
  const Real t1 = std::min(e.t1, limit);
  // Left child: points with coordinate <= clip_left; right child: >= clip_right.
  auto clip = [&](Real plane, bool below, Real& lo, Real& hi) {
    lo = e.t0;
    hi = t1;
    if (d == Real(0)) return below ? o <= plane : o >= plane;
    const Real t = (plane - o) / d;
    if ((d > Real(0)) == below) {
      hi = std::min(hi, t);  // inside while the parameter is <= t
    } else {
      lo = std::max(lo, t);  // inside once the parameter is >= t
    }
    return lo <= hi;
  };
  Real lo;
  Real hi;
  if (clip(n.clip_right, false, lo, hi)) stack.push({n.right, lo, hi});
  if (clip(n.clip_left, true, lo, hi)) stack.push({index + 1, lo, hi});
}

// ---- pairs ------------------------------------------------------------------------------------

/// The tree for detail::TreePairDescent: records at leaves only, subtree boxes from refit.
struct KdTree::DescentView {
  const KdTree& t;
  std::uint32_t root() const { return 0; }
  const Aabb& bounds(std::uint32_t n) const { return t.bounds_[n]; }
  template <class F>
  void children(std::uint32_t n, F f) const {
    if (t.nodes_[n].leaf) return;
    f(n + 1);
    f(t.nodes_[n].right);
  }
  std::size_t item_count(std::uint32_t n) const { return t.nodes_[n].leaf ? t.nodes_[n].count : 0; }
  template <class F>
  void items(std::uint32_t n, F f) const {
    const Node& node = t.nodes_[n];
    for (std::uint32_t i = node.begin; i < node.begin + node.count; ++i) {
      if (t.records_[i].id != kDead) f(t.records_[i].box, t.records_[i].id);
    }
  }
  bool accept(ProxyId a, ProxyId b) const { return detail::kinds_and_filters_pair(t.proxies_[a], t.proxies_[b]); }
};

void KdTree::find_pairs(std::vector<ProxyPair>& out, Executor& executor) {
  out.clear();
  if (!pending_.empty() || dead_ * 4 > records_.size() || (nodes_.empty() && count_ > 0)) {
    rebuild();
  } else if (dirty_ && !nodes_.empty()) {
    double sum = 0;
    std::size_t internal = 0;
    refit(0, sum, internal);
    dirty_ = false;
    const double mean = internal ? sum / static_cast<double>(internal) : 0.0;
    if (mean > build_overlap_ + static_cast<double>(config_.rebuild_overlap)) rebuild();
  }
  BroadPhaseStats st;
  if (!nodes_.empty()) detail::descend_pairs(DescentView{*this}, executor, out, st);
  sort_pairs(out, sort_scratch_);
  stats_ = {st.nodes_visited, st.pairs_tested, out.size()};
}

// ---- inspection -------------------------------------------------------------------------------

int KdTree::depth() const {
  int best = 0;
  for (std::size_t i = 0; i < nodes_.size(); ++i) {
    if (!nodes_[i].leaf) continue;
    int d = 0;
    for (std::uint32_t p = nodes_[i].parent; p != kNull; p = nodes_[p].parent) ++d;
    best = std::max(best, d);
  }
  return best;
}

bool KdTree::validate() const {
  std::size_t live = 0;
  for (std::size_t id = 0; id < proxies_.size(); ++id) {
    const Proxy& p = proxies_[id];
    if (p.place == Place::None) continue;
    ++live;
    if (p.place == Place::Pending) {
      if (p.slot >= pending_.size() || pending_[p.slot] != id) return false;
      continue;
    }
    if (p.slot >= records_.size() || records_[p.slot].id != id) return false;
    if (records_[p.slot].box.min != p.box.min || records_[p.slot].box.max != p.box.max) return false;
    if (p.leaf >= nodes_.size() || !nodes_[p.leaf].leaf) return false;
    const Node& leaf = nodes_[p.leaf];
    if (p.slot < leaf.begin || p.slot >= leaf.begin + leaf.count) return false;
    // The box lies within the clip planes of every ancestor.
    std::uint32_t child = p.leaf;
    for (std::uint32_t parent = leaf.parent; parent != kNull; parent = nodes_[parent].parent) {
      if (parent >= nodes_.size() || nodes_[parent].leaf) return false;
      const Node& n = nodes_[parent];
      if (child == parent + 1) {
        if (p.box.max[n.axis] > n.clip_left) return false;
      } else {
        if (child != n.right || p.box.min[n.axis] < n.clip_right) return false;
      }
      child = parent;
    }
    if (child != 0) return false;
  }
  if (live != count_) return false;
  std::size_t dead = 0;
  for (const Record& r : records_) dead += r.id == kDead ? 1 : 0;
  if (dead != dead_ || records_.size() - dead + pending_.size() != count_) return false;
  // Leaves tile the record array.
  std::size_t covered = 0;
  for (const Node& n : nodes_) covered += n.leaf ? n.count : 0;
  return covered == records_.size() || (nodes_.empty() && records_.empty());
}

}  // namespace proxima
