#pragma once
/// @file tree_pair_descent.hpp
/// Internal: every overlapping pair of the boxes stored in a tree, by a simultaneous descent
/// of the tree against itself (Ericson, Real-Time Collision Detection 6.5.3, BVH-BVH
/// traversal, applied to one tree), for trees whose nodes hold boxes at any level (BSP tree)
/// or only at leaves (kd-tree). Not installed.
///
/// Steps: self(N) = N's own boxes among themselves, each own box against each child subtree
/// (descending while the box overlaps the subtree bounds), self of each child, cross of each
/// pair of children; cross(A, B) = nothing when the subtree bounds are disjoint, else A's own
/// boxes against B's subtree, B's own boxes against A's child subtrees, cross of each child
/// pair. Every pair of stored boxes is met exactly once. O(node pairs with overlapping bounds
/// + candidate tests); no per-box query from the root.
///
/// The tree is read through an adapter T with
///   std::uint32_t root() const;                    (valid when the tree is not empty)
///   const Aabb& bounds(std::uint32_t n) const;     (contains every box of n's subtree)
///   template <class F> void children(std::uint32_t n, F f) const;   f(std::uint32_t child)
///   std::size_t item_count(std::uint32_t n) const;
///   template <class F> void items(std::uint32_t n, F f) const;      f(const Aabb&, ProxyId)
///   bool accept(ProxyId a, ProxyId b) const;       (kinds and filters allow the pair)
/// Children and items are visited in a fixed order, so the output order is deterministic.

#include <proxima/broadphase/broadphase.hpp>
#include <proxima/broadphase/parallel_pairs.hpp>

#include <cstdint>
#include <vector>

namespace proxima::detail {

/// True when two proxy records (members `kind` and `filter`) form a pair: one of them is
/// Moving and their filters accept each other (broadphase.hpp). The adapters' accept.
template <class Proxy>
bool kinds_and_filters_pair(const Proxy& p, const Proxy& q) {
  return (p.kind == ProxyKind::Moving || q.kind == ProxyKind::Moving) && can_pair(p.filter, q.filter);
}

/// One unit of the descent: self(a) when b == a, cross(a, b) otherwise.
struct DescentTask {
  std::uint32_t a;
  std::uint32_t b;
};

template <class T>
class TreePairDescent {
 public:
  TreePairDescent(const T& tree, std::vector<ProxyPair>& out, BroadPhaseStats& st) : t_(tree), out_(out), st_(st) {}

  /// Every pair of self(node) (node == root: the whole tree).
  void self(std::uint32_t node) {
    ++st_.nodes_visited;
    own(node);
    std::uint32_t kids[kMaxChildren];
    const int count = children_of(node, kids);
    for (int i = 0; i < count; ++i) {
      self(kids[i]);
      for (int j = i + 1; j < count; ++j) cross(kids[i], kids[j]);
    }
  }

  /// Every pair between the subtrees of a and b (disjoint subtrees).
  void cross(std::uint32_t a, std::uint32_t b) {
    ++st_.nodes_visited;
    if (!t_.bounds(a).overlaps(t_.bounds(b))) return;
    if (t_.item_count(a) != 0) t_.items(a, [&](const Aabb& box, ProxyId id) { box_vs_subtree(box, id, b); });
    std::uint32_t ka[kMaxChildren];
    const int na = children_of(a, ka);
    if (t_.item_count(b) != 0) {
      t_.items(b, [&](const Aabb& box, ProxyId id) {
        for (int i = 0; i < na; ++i) box_vs_subtree(box, id, ka[i]);
      });
    }
    std::uint32_t kb[kMaxChildren];
    const int nb = children_of(b, kb);
    for (int i = 0; i < na; ++i) {
      if (!t_.bounds(ka[i]).overlaps(t_.bounds(b))) continue;
      for (int j = 0; j < nb; ++j) cross(ka[i], kb[j]);
    }
  }

  /// Runs one task (see split).
  void run(const DescentTask& task) {
    if (task.a == task.b) {
      self(task.a);
    } else {
      cross(task.a, task.b);
    }
  }

  /// Splits self(root) into independent tasks for threads: a self task {n, n} is replaced by
  /// the own part of n (appended to `own_nodes`, run with own), self of each child and cross
  /// of each child pair; repeated `rounds` times or until there are `enough` tasks. The own
  /// parts and the tasks together do the work of self(root), each pair once.
  static void split(const T& tree, int rounds, std::size_t enough, std::vector<DescentTask>& tasks,
                    std::vector<std::uint32_t>& own_nodes) {
    tasks.assign(1, DescentTask{tree.root(), tree.root()});
    own_nodes.clear();
    for (int r = 0; r < rounds && tasks.size() < enough; ++r) {
      std::vector<DescentTask> next;
      for (const DescentTask& task : tasks) {
        if (task.a != task.b) {
          next.push_back(task);
          continue;
        }
        own_nodes.push_back(task.a);
        std::uint32_t kids[kMaxChildren];
        int count = 0;
        tree.children(task.a, [&](std::uint32_t c) { kids[count++] = c; });
        for (int i = 0; i < count; ++i) {
          next.push_back({kids[i], kids[i]});
          for (int j = i + 1; j < count; ++j) next.push_back({kids[i], kids[j]});
        }
      }
      tasks.swap(next);
    }
  }

  /// The own part of self(node): its boxes among themselves and against each child subtree.
  void own(std::uint32_t node) {
    const std::size_t count = t_.item_count(node);
    if (count == 0) return;
    std::size_t i = 0;
    t_.items(node, [&](const Aabb& a, ProxyId ia) {
      std::size_t j = 0;
      t_.items(node, [&](const Aabb& b, ProxyId ib) {
        if (j++ <= i) return;
        test(a, ia, b, ib);
      });
      ++i;
    });
    std::uint32_t kids[kMaxChildren];
    const int nk = children_of(node, kids);
    if (nk == 0) return;
    t_.items(node, [&](const Aabb& box, ProxyId id) {
      for (int k = 0; k < nk; ++k) box_vs_subtree(box, id, kids[k]);
    });
  }

 private:
  static constexpr int kMaxChildren = 8;

  int children_of(std::uint32_t node, std::uint32_t* kids) const {
    int count = 0;
    t_.children(node, [&](std::uint32_t c) { kids[count++] = c; });
    return count;
  }

  void test(const Aabb& a, ProxyId ia, const Aabb& b, ProxyId ib) {
    ++st_.pairs_tested;
    if (a.overlaps(b) && t_.accept(ia, ib)) out_.push_back(ia < ib ? ProxyPair{ia, ib} : ProxyPair{ib, ia});
  }

  void box_vs_subtree(const Aabb& box, ProxyId id, std::uint32_t node) {
    ++st_.nodes_visited;
    if (!box.overlaps(t_.bounds(node))) return;
    if (t_.item_count(node) != 0) t_.items(node, [&](const Aabb& b, ProxyId ib) { test(box, id, b, ib); });
    t_.children(node, [&](std::uint32_t c) { box_vs_subtree(box, id, c); });
  }

  const T& t_;
  std::vector<ProxyPair>& out_;
  BroadPhaseStats& st_;
};

/// Every pair of a non-empty tree into `out` (unsorted; appended), on `executor`: with
/// concurrency 1 self(root) inline; otherwise the split tasks run by the executor
/// (parallel_pair_chunks, which allocates per chunk as the task lists do here).
/// Counters add to `st`.
template <class T>
void descend_pairs(const T& tree, Executor& executor, std::vector<ProxyPair>& out, BroadPhaseStats& st) {
  const std::size_t threads = executor.concurrency();
  if (threads <= 1) {
    TreePairDescent<T>(tree, out, st).self(tree.root());
    return;
  }
  std::vector<DescentTask> tasks;
  std::vector<std::uint32_t> own_nodes;
  TreePairDescent<T>::split(tree, 8, threads * 16, tasks, own_nodes);
  const std::size_t owns = own_nodes.size();
  std::vector<BroadPhaseStats> per(owns + tasks.size());
  parallel_pair_chunks(
      per.size(), executor, out,
      [&](std::size_t begin, std::size_t end, std::vector<ProxyPair>& list) {
        for (std::size_t k = begin; k < end; ++k) {
          TreePairDescent<T> d(tree, list, per[k]);
          if (k < owns) {
            d.own(own_nodes[k]);
          } else {
            d.run(tasks[k - owns]);
          }
        }
      },
      1);
  for (const BroadPhaseStats& s : per) {
    st.nodes_visited += s.nodes_visited;
    st.pairs_tested += s.pairs_tested;
  }
}

}  // namespace proxima::detail
