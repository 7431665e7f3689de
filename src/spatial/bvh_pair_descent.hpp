#pragma once
/// @file bvh_pair_descent.hpp
/// Internal: every pair of leaves of two Bvh hierarchies whose nodes pass a node test, by a
/// simultaneous descent of both (Ericson, Real-Time Collision Detection 6.3.2, "descend the
/// larger volume"). Used by mesh against mesh and compound against compound; the broad-phase
/// trees find the pairs of ONE tree against itself (broadphase/tree_pair_descent.hpp), a
/// different walk (self pairs, boxes stored at inner nodes).
///
/// Steps:
///  1. Test the two roots; a pair that fails the node test is never descended.
///  2. Pop a node pair. Two leaves: visit them (the visitor may stop the walk). Otherwise
///     split the larger node by `size_a` / `size_b` (a leaf is never split): the other node
///     is prepared once (`fix_a` / `fix_b`: e.g. mapped into the split side's frame) and
///     tested against both children; the children that pass are pushed, the second child
///     first so that the first is descended first.
///
/// The node test N offers, for nodes i of A and j of B:
///   auto fix_a(i), fix_b(j);                        (one side prepared for many tests)
///   bool overlap(i, fixed_b, margin), overlap(fixed_a, j, margin);
///   Real size_a(i), size_b(j);                      (any monotone measure of node size)
///
/// Stack bound: a pop that pushes two pairs goes one level deeper on one side, so at most
/// depth(A) + depth(B) + 1 pairs are pending: kBvhPairStackSize covers two Bvh of the
/// largest depth. No allocation; the visiting order is fixed, so results are deterministic.

#include <proxima/spatial/bvh.hpp>

#include <cstdint>

namespace proxima::spatial {

/// Pending pairs that a descent of two hierarchies needs at most.
inline constexpr std::uint32_t kBvhPairStackSize = 2 * Bvh::kMaxDepth + 4;

/// Calls visit(leaf of A, leaf of B) for every leaf pair whose nodes all pass
/// `nodes.overlap(.., margin)` on the way down; visit returns false to stop. Returns false
/// when stopped, true when the descent ran to its end (also for an empty hierarchy).
template <class Nodes, class Visit>
bool descend_bvh_pairs(const Bvh& ba, const Bvh& bb, const Nodes& nodes, Real margin, Visit&& visit) {
  if (ba.empty() || bb.empty()) return true;
  const auto na = ba.nodes();
  const auto nb = bb.nodes();
  std::uint32_t stack[kBvhPairStackSize][2];
  std::uint32_t top = 0;
  if (!nodes.overlap(0, nodes.fix_b(0), margin)) return true;
  stack[top][0] = 0;
  stack[top][1] = 0;
  ++top;
  while (top != 0) {
    --top;
    const std::uint32_t ia = stack[top][0];
    const std::uint32_t ib = stack[top][1];
    const BvhNode& a = na[ia];
    const BvhNode& b = nb[ib];
    if (a.is_leaf() && b.is_leaf()) {
      if (!visit(a, b)) return false;
      continue;
    }
    const bool split_a = b.is_leaf() || (!a.is_leaf() && nodes.size_a(ia) >= nodes.size_b(ib));
    if (split_a) {
      const auto fixed = nodes.fix_b(ib);
      for (std::uint32_t c = a.first + 1;; --c) {
        if (nodes.overlap(c, fixed, margin)) {
          stack[top][0] = c;
          stack[top][1] = ib;
          ++top;
        }
        if (c == a.first) break;
      }
    } else {
      const auto fixed = nodes.fix_a(ia);
      for (std::uint32_t c = b.first + 1;; --c) {
        if (nodes.overlap(fixed, c, margin)) {
          stack[top][0] = ia;
          stack[top][1] = c;
          ++top;
        }
        if (c == b.first) break;
      }
    }
  }
  return true;
}

}  // namespace proxima::spatial
