/// @file bsp_tree.cpp
/// BspTree: arbitrary-plane binary space partition; straddling boxes stay at the node.
///
/// Steps:
/// 1. build(node's proxies): if few, make a leaf. Otherwise, for each candidate normal (PCA
///    principal axis of the centres by power iteration, x, y, z, four cube diagonals), put the
///    plane at the median projected centre and count the boxes entirely behind, entirely in
///    front and straddling; keep the plane with the fewest straddlers (then the best balance);
///    recurse on both sides; straddlers stay at the node, or, when more than leaf_size of
///    them, form a third ("middle") subtree built the same way with other planes.
/// 2. projections of a box on a normal use the corner that minimises (maximises) n . x and are
///    padded by a bound on the dot product's rounding, so they contain the exact projection.
/// 3. insert/update: descend from the root, growing each visited node's subtree box and the
///    back_max / front_min bound of the side taken; at a straddled plane continue into the
///    middle subtree if there is one, else stop there; stop at a leaf.
/// 4. queries visit a node when its subtree box overlaps the query, test the node's proxies,
///    and go behind when the query's projection reaches back_max, in front when it reaches
///    front_min. Rays prune by the subtree boxes.
/// 5. find_pairs: rebuild when the search work grew past rebuild_work times its value after
///    the last build, when edits accumulated, or when a leaf overflowed; then the tree against
///    itself (tree_pair_descent.hpp: simultaneous descent on the subtree boxes, Ericson
///    6.5.3), each pair met once; radix-sorted.
/// References: H. Fuchs, Z. Kedem, B. Naylor, "On visible surface generation by a priori tree
/// structures", SIGGRAPH 1980; C. Ericson, Real-Time Collision Detection, chapter 8 (BSP trees)
/// and 7.3.

#include <proxima/broadphase/bsp_tree.hpp>
#include <proxima/broadphase/parallel_pairs.hpp>
#include <proxima/core/tolerance.hpp>
#include <proxima/geometry/raycast.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

#include "broadphase/batch_update_check.hpp"
#include "broadphase/tree_pair_descent.hpp"

namespace proxima {

namespace {

bool is_oblique(const Vec3& n) {
  int nonzero = 0;
  for (int a = 0; a < 3; ++a) nonzero += n[a] != Real(0) ? 1 : 0;
  return nonzero > 1;
}

}  // namespace

BspTree::BspTree(const BspTreeConfig& config) : config_(config) {
  config_.leaf_size = std::max(1, config_.leaf_size);
  if (!(config_.rebuild_edits >= Real(0))) config_.rebuild_edits = Real(0);
}

// ---- placement --------------------------------------------------------------------------------

void BspTree::place(ProxyId id) {
  Proxy& p = proxies_[id];
  if (nodes_.empty()) nodes_.emplace_back();
  std::uint32_t index = 0;
  for (;;) {
    Node& n = nodes_[index];
    n.bounds.grow(p.box);
    if (!n.internal()) break;
    const Interval iv = project(n.normal, p.box);
    if (iv.hi < n.offset) {
      n.back_max = std::max(n.back_max, iv.hi);
      index = n.back;
    } else if (iv.lo > n.offset) {
      n.front_min = std::min(n.front_min, iv.lo);
      index = n.front;
    } else if (n.middle != kNull) {
      index = n.middle;
    } else {
      break;
    }
  }
  Node& n = nodes_[index];
  p.node = index;
  p.index = static_cast<std::uint32_t>(n.items.size());
  n.items.push_back(id);
  if (!n.internal() && n.items.size() > static_cast<std::size_t>(4 * config_.leaf_size + 16)) overfull_ = true;
}

void BspTree::detach(ProxyId id) {
  Proxy& p = proxies_[id];
  std::vector<ProxyId>& items = nodes_[p.node].items;
  const ProxyId last = items.back();
  items[p.index] = last;
  proxies_[last].index = p.index;
  items.pop_back();
}

// ---- build ------------------------------------------------------------------------------------

std::uint32_t BspTree::build(std::vector<ProxyId>& ids, std::uint32_t parent, int depth) {
  const auto index = static_cast<std::uint32_t>(nodes_.size());
  nodes_.emplace_back();
  nodes_[index].parent = parent;
  Aabb bounds = Aabb::empty();
  for (const ProxyId id : ids) bounds.grow(proxies_[id].box);
  nodes_[index].bounds = bounds;

  auto make_leaf = [&] {
    Node& n = nodes_[index];
    n.items = ids;
    for (std::uint32_t i = 0; i < n.items.size(); ++i) {
      proxies_[n.items[i]].node = index;
      proxies_[n.items[i]].index = i;
    }
    return index;
  };
  if (ids.size() <= static_cast<std::size_t>(config_.leaf_size) || depth >= 40) return make_leaf();

  // Candidate normals: principal axis of the centres, coordinate axes, cube diagonals.
  std::vector<Vec3> centres;
  centres.reserve(ids.size());
  Vec3 mean(Real(0));
  for (const ProxyId id : ids) {
    centres.push_back(proxies_[id].box.center());
    mean += centres.back();
  }
  mean /= static_cast<Real>(ids.size());
  double cov[3][3] = {};
  for (const Vec3& c : centres) {
    const Vec3 d = c - mean;
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) cov[i][j] += static_cast<double>(d[i]) * static_cast<double>(d[j]);
    }
  }
  std::vector<Vec3> candidates;
  {
    double v[3] = {0.577, 0.578, 0.579};
    bool ok = true;
    for (int it = 0; it < 24 && ok; ++it) {
      double w[3] = {0, 0, 0};
      for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) w[i] += cov[i][j] * v[j];
      }
      const double len = std::sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
      if (!(len > 0) || !std::isfinite(len)) {
        ok = false;
        break;
      }
      for (int i = 0; i < 3; ++i) v[i] = w[i] / len;
    }
    if (ok) {
      const Vec3 n(static_cast<Real>(v[0]), static_cast<Real>(v[1]), static_cast<Real>(v[2]));
      const Real len = glm::length(n);
      if (len > Real(0) && std::isfinite(len)) candidates.push_back(n / len);
    }
  }
  const Real s3 = Real(1) / std::sqrt(Real(3));
  for (const Vec3& n : {Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1), Vec3(s3, s3, s3), Vec3(s3, s3, -s3),
                        Vec3(s3, -s3, s3), Vec3(-s3, s3, s3)}) {
    candidates.push_back(n);
  }

  std::vector<Real> proj(ids.size());
  std::size_t best_score = std::numeric_limits<std::size_t>::max();
  Vec3 best_normal(Real(0));
  Real best_offset = Real(0);
  for (const Vec3& n : candidates) {
    for (std::size_t i = 0; i < centres.size(); ++i) proj[i] = glm::dot(n, centres[i]);
    const auto mid = proj.begin() + static_cast<std::ptrdiff_t>(proj.size() / 2);
    std::nth_element(proj.begin(), mid, proj.end());
    const Real offset = *mid;
    std::size_t back = 0;
    std::size_t front = 0;
    for (const ProxyId id : ids) {
      const Interval iv = project(n, proxies_[id].box);
      back += iv.hi < offset ? 1 : 0;
      front += iv.lo > offset ? 1 : 0;
    }
    if (back == 0 || front == 0) continue;
    const std::size_t straddle = ids.size() - back - front;
    const std::size_t imbalance = back > front ? back - front : front - back;
    const std::size_t score = 4 * straddle + imbalance;
    if (score < best_score) {
      best_score = score;
      best_normal = n;
      best_offset = offset;
    }
  }
  if (best_score == std::numeric_limits<std::size_t>::max()) return make_leaf();

  std::vector<ProxyId> back_ids;
  std::vector<ProxyId> front_ids;
  std::vector<ProxyId> stay;
  Real back_max = -kRealMax;
  Real front_min = kRealMax;
  for (const ProxyId id : ids) {
    const Interval iv = project(best_normal, proxies_[id].box);
    if (iv.hi < best_offset) {
      back_ids.push_back(id);
      back_max = std::max(back_max, iv.hi);
    } else if (iv.lo > best_offset) {
      front_ids.push_back(id);
      front_min = std::min(front_min, iv.lo);
    } else {
      stay.push_back(id);
    }
  }
  ids.clear();
  ids.shrink_to_fit();
  {
    Node& n = nodes_[index];
    n.normal = best_normal;
    n.offset = best_offset;
    n.back_max = back_max;
    n.front_min = front_min;
    if (stay.size() <= static_cast<std::size_t>(config_.leaf_size)) {
      n.items = stay;
      for (std::uint32_t i = 0; i < n.items.size(); ++i) {
        proxies_[n.items[i]].node = index;
        proxies_[n.items[i]].index = i;
      }
      stay.clear();
    }
  }
  const std::uint32_t back = build(back_ids, index, depth + 1);
  const std::uint32_t front = build(front_ids, index, depth + 1);
  nodes_[index].back = back;
  nodes_[index].front = front;
  if (!stay.empty()) {
    // Many straddlers: they get a subtree of their own, split by other planes.
    const std::uint32_t middle = build(stay, index, depth + 1);
    nodes_[index].middle = middle;
  }
  return index;
}

void BspTree::rebuild() {
  nodes_.clear();
  edits_ = 0;
  overfull_ = false;
  ++rebuilds_;
  std::vector<ProxyId> ids;
  ids.reserve(count_);
  for (std::size_t id = 0; id < proxies_.size(); ++id) {
    if (proxies_[id].node != kNull) ids.push_back(static_cast<ProxyId>(id));
  }
  if (!ids.empty()) build(ids, kNull, 0);
}

// ---- edits ------------------------------------------------------------------------------------

BroadPhaseStatus BspTree::insert(ProxyId id, const Aabb& box, ProxyKind kind, ProxyFilter filter) {
  const BroadPhaseStatus s = check_box(box);
  if (s != BroadPhaseStatus::Ok) return s;
  if (id < proxies_.size() && proxies_[id].node != kNull) return BroadPhaseStatus::DuplicateId;
  if (id >= proxies_.size()) proxies_.resize(static_cast<std::size_t>(id) + 1);
  Proxy& p = proxies_[id];
  p.box = box;
  p.filter = filter;
  p.kind = kind;
  place(id);
  ++count_;
  ++edits_;
  return BroadPhaseStatus::Ok;
}

BroadPhaseStatus BspTree::remove(ProxyId id) {
  if (id >= proxies_.size() || proxies_[id].node == kNull) return BroadPhaseStatus::UnknownId;
  detach(id);
  proxies_[id] = Proxy{};
  --count_;
  ++edits_;
  return BroadPhaseStatus::Ok;
}

BroadPhaseStatus BspTree::update(ProxyId id, const Aabb& box) {
  if (id >= proxies_.size() || proxies_[id].node == kNull) return BroadPhaseStatus::UnknownId;
  const BroadPhaseStatus s = check_box(box);
  if (s != BroadPhaseStatus::Ok) return s;
  Proxy& p = proxies_[id];
  if (p.box.min == box.min && p.box.max == box.max) return BroadPhaseStatus::Ok;
  detach(id);
  p.box = box;
  place(id);
  ++edits_;
  return BroadPhaseStatus::Ok;
}

BroadPhaseStatus BspTree::update(std::span<const ProxyUpdate> updates) {
  const BroadPhaseStatus s =
      detail::check_batch(updates, [&](ProxyId id) { return id < proxies_.size() && proxies_[id].node != kNull; });
  if (s != BroadPhaseStatus::Ok) return s;
  for (const ProxyUpdate& u : updates) update(u.id, u.box);
  return BroadPhaseStatus::Ok;
}

// ---- pairs ------------------------------------------------------------------------------------

/// The tree for detail::TreePairDescent: proxies at any node, subtree boxes `bounds`.
struct BspTree::DescentView {
  const BspTree& t;
  std::uint32_t root() const { return 0; }
  const Aabb& bounds(std::uint32_t n) const { return t.nodes_[n].bounds; }
  template <class F>
  void children(std::uint32_t n, F f) const {
    const Node& node = t.nodes_[n];
    if (!node.internal()) return;
    f(node.back);
    f(node.front);
    if (node.middle != kNull) f(node.middle);
  }
  std::size_t item_count(std::uint32_t n) const { return t.nodes_[n].items.size(); }
  template <class F>
  void items(std::uint32_t n, F f) const {
    for (const ProxyId id : t.nodes_[n].items) f(t.proxies_[id].box, id);
  }
  bool accept(ProxyId a, ProxyId b) const { return detail::kinds_and_filters_pair(t.proxies_[a], t.proxies_[b]); }
};

void BspTree::find_pairs(std::vector<ProxyPair>& out, Executor& executor) {
  out.clear();
  bool rebuilt = false;
  if (overfull_ || degraded_ ||
      static_cast<Real>(edits_) > config_.rebuild_edits * static_cast<Real>(count_) + Real(16)) {
    rebuild();
    rebuilt = true;
  }
  BroadPhaseStats found;
  if (!nodes_.empty()) detail::descend_pairs(DescentView{*this}, executor, out, found);
  sort_pairs(out, sort_scratch_);
  const BroadPhaseStats st{found.nodes_visited, found.pairs_tested, out.size()};
  stats_ = st;
  // Quality watch: the work of the first pair search after a build is the baseline; when the
  // work grows past rebuild_work times it (plus slack for the pairs themselves), the next
  // find_pairs rebuilds.
  const double work = static_cast<double>(st.nodes_visited + st.pairs_tested);
  const double slack = 2.0 * static_cast<double>(st.pairs_found) + 64.0;
  if (rebuilt) {
    baseline_work_ = work;
    degraded_ = false;
  } else {
    degraded_ = work > static_cast<double>(config_.rebuild_work) * baseline_work_ + slack;
  }
}

// ---- inspection -------------------------------------------------------------------------------

std::size_t BspTree::oblique_plane_count() const {
  std::size_t count = 0;
  for (const Node& n : nodes_) count += n.internal() && is_oblique(n.normal) ? 1 : 0;
  return count;
}

bool BspTree::validate() const {
  std::size_t live = 0;
  for (std::size_t id = 0; id < proxies_.size(); ++id) {
    const Proxy& p = proxies_[id];
    if (p.node == kNull) continue;
    ++live;
    if (p.node >= nodes_.size()) return false;
    const Node& home = nodes_[p.node];
    if (p.index >= home.items.size() || home.items[p.index] != id) return false;
    if (!home.bounds.contains(p.box)) return false;
    // Straddling at an internal home node.
    if (home.internal()) {
      const Interval iv = project(home.normal, p.box);
      if (iv.hi < home.offset || iv.lo > home.offset) return false;
    }
    std::uint32_t child = p.node;
    for (std::uint32_t parent = home.parent; parent != kNull; parent = nodes_[parent].parent) {
      if (parent >= nodes_.size()) return false;
      const Node& n = nodes_[parent];
      if (!n.bounds.contains(p.box)) return false;
      const Interval iv = project(n.normal, p.box);
      if (child == n.back) {
        if (!(iv.hi < n.offset) || iv.hi > n.back_max) return false;
      } else if (child == n.front) {
        if (!(iv.lo > n.offset) || iv.lo < n.front_min) return false;
      } else if (child == n.middle) {
        if (iv.hi < n.offset || iv.lo > n.offset) return false;
      } else {
        return false;
      }
      child = parent;
    }
    if (child != 0) return false;
  }
  std::size_t stored = 0;
  for (std::size_t i = 0; i < nodes_.size(); ++i) {
    const Node& n = nodes_[i];
    stored += n.items.size();
    if (n.internal() && (n.back >= nodes_.size() || n.front >= nodes_.size() || nodes_[n.back].parent != i ||
                         nodes_[n.front].parent != i ||
                         (n.middle != kNull && (n.middle >= nodes_.size() || nodes_[n.middle].parent != i)))) {
      return false;
    }
  }
  return live == count_ && stored == count_;
}

}  // namespace proxima
