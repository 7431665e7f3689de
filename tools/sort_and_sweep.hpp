#pragma once
// The tool's interim broad phase: sort-and-sweep over world AABBs. It stands in for the
// library's broad-phase layer until that layer exists, and is only used by the demo.
#include <proxima/geometry/aabb.hpp>

#include <cstdint>
#include <span>
#include <utility>
#include <vector>

namespace proxima::tool {

/// A candidate pair of box indices, first < second.
using IndexPair = std::pair<std::uint32_t, std::uint32_t>;

/// Sort-and-sweep on one axis (Baraff's "sweep and prune" without the persistent sorted
/// list; Ericson, Real-Time Collision Detection, 7.5.2).
///
/// Steps: 1. sort the boxes by their min on `axis`; 2. walk the sorted list keeping the
/// boxes whose interval on `axis` is still open; 3. each new box is tested on the two other
/// axes against the open boxes, and overlapping pairs are reported. Closed boxes: touching
/// boxes pair. Output pairs are (smaller index, larger index), sorted, so the result is
/// deterministic. O(n log n + k) with k the overlaps on the sweep axis.
class SortAndSweep {
 public:
  /// Finds every overlapping pair of `boxes` (indices into the span) into `pairs`
  /// (cleared first). Empty boxes never pair.
  void find_pairs(std::span<const Aabb> boxes, std::vector<IndexPair>& pairs, int axis = 0);

 private:
  std::vector<std::uint32_t> order_;  // box indices sorted by min on the sweep axis
  std::vector<std::uint32_t> open_;   // boxes whose sweep interval is still open
};

}  // namespace proxima::tool
