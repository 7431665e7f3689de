/// @file loose_octree.cpp
/// Loose octree and quadtree (looseness 2), after Ulrich, "Loose Octrees" (Game Programming
/// Gems 1, 4.11) and Ericson, Real-Time Collision Detection 7.3.6.
///
/// Steps: 1. the root covers the boxes (doubling towards any box outside its loose bounds; an
/// empty root is replaced by one around the box instead);
/// 2. a box goes down the child holding its centre while that child's loose bounds (centre
/// +- 2 half) contain it, children created on demand; the stored loose bounds are the only
/// numbers the placement, the pair walk and the queries compare with, so "every box lies in
/// its node's loose bounds" holds exactly despite rounding; 3. find_pairs gathers the boxes
/// node by node, fits a tight box to every subtree and descends the tree against itself on
/// those boxes (Ericson 6.5.3; see the header); 4. empty leaves are deleted as boxes leave
/// them.

#include <proxima/broadphase/loose_octree.hpp>
#include <proxima/broadphase/pair_tracker.hpp>
#include <proxima/broadphase/parallel_pairs.hpp>

#include <algorithm>
#include <cmath>

#include "broadphase/structure_support.hpp"

namespace proxima {

template <int Dim>
Aabb LooseTree<Dim>::loose_of(const Vec3& center, Real half) {
  Aabb loose{Vec3(-kRealMax), Vec3(kRealMax)};
  for (int k = 0; k < Dim; ++k) {
    loose.min[k] = center[k] - Real(2) * half;
    loose.max[k] = center[k] + Real(2) * half;
  }
  return loose;
}

template <int Dim>
bool LooseTree<Dim>::contains(const Aabb& outer, const Aabb& inner) {
  for (int k = 0; k < Dim; ++k) {
    if (inner.min[k] < outer.min[k] || inner.max[k] > outer.max[k]) return false;
  }
  return true;
}

template <int Dim>
std::int32_t LooseTree<Dim>::new_node(const Vec3& center, Real half, std::int32_t parent) {
  std::int32_t index;
  if (!free_.empty()) {
    index = free_.back();
    free_.pop_back();
  } else {
    index = std::int32_t(nodes_.size());
    nodes_.emplace_back();
  }
  Node& n = nodes_[std::size_t(index)];
  n.center = center;
  n.half = half;
  n.loose = loose_of(center, half);
  if (parent != kNil) {
    // Clip to the parent's loose bounds, so that nesting holds exactly despite rounding.
    const Aabb& outer = nodes_[std::size_t(parent)].loose;
    n.loose.min = glm::max(n.loose.min, outer.min);
    n.loose.max = glm::min(n.loose.max, outer.max);
  }
  std::fill(std::begin(n.child), std::end(n.child), kNil);
  n.parent = parent;
  n.first = kNone;
  n.count = 0;
  n.children = 0;
  return index;
}

template <int Dim>
void LooseTree<Dim>::make_room(const Aabb& box) {
  // An empty root (the last box removed) is dropped rather than grown around: nested under a
  // new root it would be an empty leaf.
  if (root_ != kNil && nodes_[std::size_t(root_)].count == 0 && nodes_[std::size_t(root_)].children == 0 &&
      !contains(nodes_[std::size_t(root_)].loose, box)) {
    nodes_.clear();
    free_.clear();
    root_ = kNil;
  }
  if (root_ == kNil) {
    Real half = 0;
    const Vec3 h = box.half_extents();
    for (int k = 0; k < Dim; ++k) half = std::max(half, h[k]);
    if (!(half > 0)) half = std::max(Real(1), max_abs_component(box.center()) * Real(1e-6));
    root_ = new_node(box.center(), half, kNil);
    min_half_ = half * Real(1.0 / 1048576.0);
    return;
  }
  while (!contains(nodes_[std::size_t(root_)].loose, box)) {
    const Node old = nodes_[std::size_t(root_)];
    const Vec3 c = box.center();
    Vec3 center = old.center;
    int index = 0;
    for (int k = 0; k < Dim; ++k) {
      if (c[k] < old.center[k]) {
        center[k] = old.center[k] - old.half;  // the old root is the upper child on axis k
        index |= 1 << k;
      } else {
        center[k] = old.center[k] + old.half;
      }
    }
    const std::int32_t top = new_node(center, old.half * Real(2), kNil);
    nodes_[std::size_t(top)].loose.grow(old.loose);  // nesting holds exactly
    nodes_[std::size_t(top)].child[index] = root_;
    nodes_[std::size_t(top)].children = 1;
    nodes_[std::size_t(root_)].parent = top;
    root_ = top;
  }
}

template <int Dim>
std::int32_t LooseTree<Dim>::descend(const Aabb& box) {
  const Vec3 c = box.center();
  std::int32_t node = root_;
  for (;;) {
    const Node& n = nodes_[std::size_t(node)];
    const Real child_half = n.half * Real(0.5);
    if (child_half < min_half_) return node;
    int index = 0;
    Vec3 center = n.center;
    for (int k = 0; k < Dim; ++k) {
      if (c[k] >= n.center[k]) {
        index |= 1 << k;
        center[k] = n.center[k] + child_half;
      } else {
        center[k] = n.center[k] - child_half;
      }
    }
    const std::int32_t existing = n.child[index];
    if (existing != kNil) {
      if (!contains(nodes_[std::size_t(existing)].loose, box)) return node;
      node = existing;
      continue;
    }
    Aabb loose = loose_of(center, child_half);
    loose.min = glm::max(loose.min, n.loose.min);
    loose.max = glm::min(loose.max, n.loose.max);
    if (!contains(loose, box)) return node;
    const std::int32_t created = new_node(center, child_half, node);  // may reallocate nodes_
    nodes_[std::size_t(node)].child[index] = created;
    ++nodes_[std::size_t(node)].children;
    node = created;
  }
}

template <int Dim>
void LooseTree<Dim>::link(ProxyId id, std::int32_t node) {
  Node& n = nodes_[std::size_t(node)];
  node_of_[id] = node;
  prev_[id] = kNone;
  next_[id] = n.first;
  if (n.first != kNone) prev_[n.first] = id;
  n.first = id;
  ++n.count;
}

template <int Dim>
void LooseTree<Dim>::unlink(ProxyId id) {
  Node& n = nodes_[std::size_t(node_of_[id])];
  if (prev_[id] != kNone) {
    next_[prev_[id]] = next_[id];
  } else {
    n.first = next_[id];
  }
  if (next_[id] != kNone) prev_[next_[id]] = prev_[id];
  --n.count;
  node_of_[id] = kNil;
}

template <int Dim>
void LooseTree<Dim>::prune(std::int32_t node) {
  while (node != kNil && node != root_) {
    Node& n = nodes_[std::size_t(node)];
    if (n.count != 0 || n.children != 0) return;
    const std::int32_t parent = n.parent;
    Node& p = nodes_[std::size_t(parent)];
    for (std::int32_t& ch : p.child) {
      if (ch == node) ch = kNil;
    }
    --p.children;
    free_.push_back(node);
    node = parent;
  }
}

template <int Dim>
BroadPhaseStatus LooseTree<Dim>::insert(ProxyId id, const Aabb& box, ProxyKind kind, ProxyFilter filter) {
  const BroadPhaseStatus status = proxies_.insert(id, box, kind, filter);
  if (status != BroadPhaseStatus::Ok) return status;
  if (id >= node_of_.size()) {
    node_of_.resize(std::size_t(id) + 1, kNil);
    next_.resize(std::size_t(id) + 1, kNone);
    prev_.resize(std::size_t(id) + 1, kNone);
  }
  make_room(box);
  link(id, descend(box));
  return status;
}

template <int Dim>
BroadPhaseStatus LooseTree<Dim>::remove(ProxyId id) {
  if (!proxies_.contains(id)) return BroadPhaseStatus::UnknownId;
  const std::int32_t node = node_of_[id];
  unlink(id);
  prune(node);
  return proxies_.remove(id);
}

template <int Dim>
BroadPhaseStatus LooseTree<Dim>::update(ProxyId id, const Aabb& box) {
  const BroadPhaseStatus status = proxies_.check_update(id, box);
  if (status != BroadPhaseStatus::Ok) return status;
  proxies_[id].box = box;
  make_room(box);
  const std::int32_t target = descend(box);
  const std::int32_t current = node_of_[id];
  if (target != current) {
    unlink(id);
    link(id, target);
    prune(current);
  }
  return status;
}

template <int Dim>
BroadPhaseStatus LooseTree<Dim>::update(std::span<const ProxyUpdate> updates) {
  const BroadPhaseStatus status = proxies_.check_updates(updates);
  if (status != BroadPhaseStatus::Ok) return status;
  for (const ProxyUpdate& u : updates) update(u.id, u.box);
  return status;
}

template <int Dim>
void LooseTree<Dim>::rebuild() {
  nodes_.clear();
  free_.clear();
  root_ = kNil;
  const auto ids = proxies_.ids();
  if (ids.empty()) return;
  Aabb world = Aabb::empty();
  Real largest = 0;
  for (const ProxyId id : ids) {
    const Aabb& b = proxies_[id].box;
    world.grow(b);
    const Vec3 h = b.half_extents();
    for (int k = 0; k < Dim; ++k) largest = std::max(largest, h[k]);
  }
  // Root: the world box's centre, half = half the world's largest edge (its loose bounds,
  // twice that, hold every box); depth limit 2^-20 of it (or of the largest box).
  Real half = 0;
  const Vec3 wh = world.half_extents();
  for (int k = 0; k < Dim; ++k) half = std::max(half, wh[k]);
  if (!(half > 0)) half = std::max(Real(1), max_abs_component(world.center()) * Real(1e-6));
  root_ = new_node(world.center(), half, kNil);
  min_half_ = std::max(half, largest) * Real(1.0 / 1048576.0);
  for (const ProxyId id : ids) {
    make_room(proxies_[id].box);
    link(id, descend(proxies_[id].box));
  }
}

template <int Dim>
void LooseTree<Dim>::gather() {
  const std::size_t nn = nodes_.size();
  own_begin_.assign(nn, 0);
  own_fit_.assign(nn, Aabb::empty());
  fit_.resize(nn);
  // Depth-first order from the root; positions of each node's own boxes follow it.
  order_.clear();
  order_.push_back(root_);
  std::uint32_t position = 0;
  for (std::size_t k = 0; k < order_.size(); ++k) {
    const Node& n = nodes_[std::size_t(order_[k])];
    own_begin_[std::size_t(order_[k])] = position;
    position += n.count;
    for (const std::int32_t child : n.child) {
      if (child != kNil) order_.push_back(child);
    }
  }
  items_.resize(position);
  for (const std::int32_t node : order_) {
    const Node& n = nodes_[std::size_t(node)];
    std::uint32_t at = own_begin_[std::size_t(node)];
    Aabb fit = Aabb::empty();
    for (std::uint32_t id = n.first; id != kNone; id = next_[id]) {
      const Aabb& box = proxies_[id].box;
      items_[at++] = {box, id};
      fit.grow(box);
    }
    own_fit_[std::size_t(node)] = fit;
    if (n.count > 16) {
      std::sort(items_.begin() + own_begin_[std::size_t(node)], items_.begin() + at,
                [](const Item& x, const Item& y) { return x.box.min.x < y.box.min.x; });
    }
  }
  // Subtree boxes bottom-up (children come after their parent in order_).
  for (std::size_t k = order_.size(); k-- > 0;) {
    const std::int32_t node = order_[k];
    Aabb fit = own_fit_[std::size_t(node)];
    for (const std::int32_t child : nodes_[std::size_t(node)].child) {
      if (child != kNil) fit.grow(fit_[std::size_t(child)]);
    }
    fit_[std::size_t(node)] = fit;
  }
}

template <int Dim>
void LooseTree<Dim>::test_items(std::uint32_t begin, std::uint32_t end, std::uint32_t begin2, std::uint32_t end2,
                                std::vector<ProxyPair>& out, BroadPhaseStats& st) const {
  for (std::uint32_t i = begin; i < end; ++i) {
    const Item& a = items_[i];
    for (std::uint32_t j = begin2; j < end2; ++j) {
      const Item& b = items_[j];
      ++st.pairs_tested;
      if (a.box.overlaps(b.box) && detail::may_pair(proxies_[a.id], proxies_[b.id]))
        out.push_back(detail::ordered_pair(a.id, b.id));
    }
  }
}

template <int Dim>
void LooseTree<Dim>::items_vs_subtree(std::uint32_t begin, std::uint32_t end, const Aabb& fit, std::int32_t node,
                                      std::vector<ProxyPair>& out, BroadPhaseStats& st) const {
  ++st.nodes_visited;
  if (!fit.overlaps(fit_[std::size_t(node)])) return;
  const Node& n = nodes_[std::size_t(node)];
  if (n.count != 0 && fit.overlaps(own_fit_[std::size_t(node)])) {
    const std::uint32_t b = own_begin_[std::size_t(node)];
    test_items(begin, end, b, b + n.count, out, st);
  }
  for (const std::int32_t child : n.child) {
    if (child != kNil) items_vs_subtree(begin, end, fit, child, out, st);
  }
}

template <int Dim>
void LooseTree<Dim>::own_pairs(std::int32_t node, std::vector<ProxyPair>& out, BroadPhaseStats& st) const {
  const Node& n = nodes_[std::size_t(node)];
  if (n.count == 0) return;
  const std::uint32_t begin = own_begin_[std::size_t(node)];
  const std::uint32_t end = begin + n.count;
  // Own boxes among themselves: a sweep on x (sorted by gather when more than 16).
  for (std::uint32_t i = begin; i < end; ++i) {
    const Item& a = items_[i];
    for (std::uint32_t j = i + 1; j < end; ++j) {
      const Item& b = items_[j];
      if (n.count > 16 && b.box.min.x > a.box.max.x) break;
      ++st.pairs_tested;
      if (a.box.overlaps(b.box) && detail::may_pair(proxies_[a.id], proxies_[b.id]))
        out.push_back(detail::ordered_pair(a.id, b.id));
    }
  }
  for (const std::int32_t child : n.child) {
    if (child != kNil) items_vs_subtree(begin, end, own_fit_[std::size_t(node)], child, out, st);
  }
}

template <int Dim>
void LooseTree<Dim>::self_pairs(std::int32_t node, std::vector<ProxyPair>& out, BroadPhaseStats& st) const {
  ++st.nodes_visited;
  own_pairs(node, out, st);
  const Node& n = nodes_[std::size_t(node)];
  for (int i = 0; i < kChildren; ++i) {
    if (n.child[i] == kNil) continue;
    self_pairs(n.child[i], out, st);
    for (int j = i + 1; j < kChildren; ++j) {
      if (n.child[j] != kNil) cross_pairs(n.child[i], n.child[j], out, st);
    }
  }
}

template <int Dim>
void LooseTree<Dim>::cross_pairs(std::int32_t a, std::int32_t b, std::vector<ProxyPair>& out,
                                 BroadPhaseStats& st) const {
  ++st.nodes_visited;
  if (!fit_[std::size_t(a)].overlaps(fit_[std::size_t(b)])) return;
  const Node& na = nodes_[std::size_t(a)];
  const Node& nb = nodes_[std::size_t(b)];
  // Own boxes of each against the whole other subtree, then the child pairs.
  if (na.count != 0) {
    const std::uint32_t begin = own_begin_[std::size_t(a)];
    items_vs_subtree(begin, begin + na.count, own_fit_[std::size_t(a)], b, out, st);
  }
  if (nb.count != 0) {
    const std::uint32_t begin = own_begin_[std::size_t(b)];
    for (const std::int32_t child : na.child) {
      if (child != kNil) items_vs_subtree(begin, begin + nb.count, own_fit_[std::size_t(b)], child, out, st);
    }
  }
  for (const std::int32_t ca : na.child) {
    if (ca == kNil || !fit_[std::size_t(ca)].overlaps(fit_[std::size_t(b)])) continue;
    for (const std::int32_t cb : nb.child) {
      if (cb != kNil) cross_pairs(ca, cb, out, st);
    }
  }
}

template <int Dim>
void LooseTree<Dim>::run_task(const Task& task, std::vector<ProxyPair>& out, BroadPhaseStats& st) const {
  if (task.b == kNil) {
    self_pairs(task.a, out, st);
  } else if (task.b == task.a) {
    own_pairs(task.a, out, st);
  } else {
    cross_pairs(task.a, task.b, out, st);
  }
}

template <int Dim>
void LooseTree<Dim>::split_tasks(std::size_t wanted) {
  // Split self(root) into tasks (own part, self of each child, cross of each child pair),
  // then split the self tasks again while there are few tasks.
  tasks_.assign(1, Task{root_, kNil});
  for (int round = 0; round < 3 && tasks_.size() < wanted; ++round) {
    std::vector<Task> next;
    for (const Task& t : tasks_) {
      if (t.b != kNil) {
        next.push_back(t);
        continue;
      }
      const Node& nd = nodes_[std::size_t(t.a)];
      next.push_back({t.a, t.a});
      for (int i = 0; i < kChildren; ++i) {
        if (nd.child[i] == kNil) continue;
        next.push_back({nd.child[i], kNil});
        for (int j = i + 1; j < kChildren; ++j) {
          if (nd.child[j] != kNil) next.push_back({nd.child[i], nd.child[j]});
        }
      }
    }
    tasks_.swap(next);
  }
}

template <int Dim>
void LooseTree<Dim>::find_pairs(std::vector<ProxyPair>& out, Executor& executor) {
  out.clear();
  stats_ = {};
  const std::size_t n = proxies_.size();
  if (root_ == kNil || n == 0) return;
  gather();
  const std::size_t threads = std::min(executor.concurrency(), n / 1024 + 1);
  if (threads <= 1) {
    self_pairs(root_, out, stats_);
  } else {
    split_tasks(threads * 16);
    std::vector<BroadPhaseStats> st(tasks_.size());
    parallel_pair_chunks(
        tasks_.size(), executor, out,
        [&](std::size_t begin, std::size_t end, std::vector<ProxyPair>& part) {
          for (std::size_t k = begin; k < end; ++k) run_task(tasks_[k], part, st[k]);
        },
        1);
    for (const BroadPhaseStats& s : st) {
      stats_.nodes_visited += s.nodes_visited;
      stats_.pairs_tested += s.pairs_tested;
    }
  }
  sort_pairs(out, sort_scratch_);
  stats_.pairs_found = out.size();
}

template <int Dim>
bool LooseTree<Dim>::ray_meets(const Ray& ray, Real max_t, const Aabb& loose) {
  // Slab test of the clipped ray against a node's loose bounds on the partitioned axes.
  Real t0 = 0;
  Real t1 = max_t;
  for (int k = 0; k < Dim; ++k) {
    const Real o = ray.origin[k];
    const Real d = ray.direction[k];
    if (d == Real(0)) {
      if (o < loose.min[k] || o > loose.max[k]) return false;
      continue;
    }
    Real ta = (loose.min[k] - o) / d;
    Real tb = (loose.max[k] - o) / d;
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
    if (detail::slab_interval_empty(t0, t1)) return false;
  }
  return true;
}

template <int Dim>
bool LooseTree<Dim>::validate() const {
  if (!proxies_.validate()) return false;
  const auto ids = proxies_.ids();
  if (root_ == kNil) return ids.empty() && node_count() == 0;
  if (nodes_[std::size_t(root_)].parent != kNil) return false;
  std::vector<char> is_free(nodes_.size(), 0);
  for (const std::int32_t f : free_) is_free[std::size_t(f)] = 1;
  std::size_t listed = 0;
  for (std::size_t i = 0; i < nodes_.size(); ++i) {
    if (is_free[i] != 0) continue;
    const Node& n = nodes_[i];
    std::uint32_t children = 0;
    for (const std::int32_t ch : n.child) {
      if (ch == kNil) continue;
      ++children;
      if (is_free[std::size_t(ch)] != 0 || nodes_[std::size_t(ch)].parent != std::int32_t(i)) return false;
      if (!contains(n.loose, nodes_[std::size_t(ch)].loose)) return false;
    }
    if (children != n.children) return false;
    if (std::int32_t(i) != root_ && n.count == 0 && n.children == 0) return false;  // empty leaf kept
    std::uint32_t count = 0;
    std::uint32_t previous = kNone;
    for (std::uint32_t id = n.first; id != kNone; id = next_[id]) {
      if (!proxies_.contains(id) || node_of_[id] != std::int32_t(i) || prev_[id] != previous) return false;
      if (!contains(n.loose, proxies_[id].box)) return false;
      previous = id;
      if (++count > ids.size()) return false;
    }
    if (count != n.count) return false;
    listed += count;
  }
  return listed == ids.size();
}

template <int Dim>
int LooseTree<Dim>::depth() const {
  int deepest = 0;
  std::vector<char> is_free(nodes_.size(), 0);
  for (const std::int32_t f : free_) is_free[std::size_t(f)] = 1;
  for (std::size_t i = 0; i < nodes_.size(); ++i) {
    if (is_free[i] != 0) continue;
    int d = 0;
    for (std::int32_t p = nodes_[i].parent; p != kNil; p = nodes_[std::size_t(p)].parent) ++d;
    deepest = std::max(deepest, d);
  }
  return deepest;
}

template <int Dim>
std::size_t LooseTree<Dim>::memory_bytes() const {
  return detail::capacity_bytes(node_of_) + detail::capacity_bytes(next_) + detail::capacity_bytes(prev_) +
         detail::capacity_bytes(nodes_) + detail::capacity_bytes(free_) + detail::capacity_bytes(items_) +
         detail::capacity_bytes(own_begin_) + detail::capacity_bytes(own_fit_) + detail::capacity_bytes(fit_) +
         detail::capacity_bytes(order_) + sort_scratch_.keys.capacity() * 16 +
         proxies_.size() * (sizeof(detail::ProxyRecord) + sizeof(ProxyId));
}

template class LooseTree<2>;
template class LooseTree<3>;

}  // namespace proxima
