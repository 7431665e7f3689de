// Sort-and-sweep over world AABBs (Ericson, Real-Time Collision Detection, 7.5.2; Baraff,
// "Dynamic Simulation of Non-penetrating Rigid Bodies", 1992, sweep and prune).
// Steps: 1. order the boxes by min on the sweep axis (stable: ties keep index order);
// 2. sweep: drop open boxes whose max lies before the new box's min; 3. test the new box
// against the open ones on the other two axes; 4. sort the pairs for determinism.
#include "sort_and_sweep.hpp"

#include <algorithm>

namespace proxima::tool {

void SortAndSweep::find_pairs(std::span<const Aabb> boxes, std::vector<IndexPair>& pairs, int axis) {
  pairs.clear();
  order_.clear();
  for (std::uint32_t i = 0; i < boxes.size(); ++i) {
    if (boxes[i].is_valid()) order_.push_back(i);
  }
  std::stable_sort(order_.begin(), order_.end(),
                   [&](std::uint32_t a, std::uint32_t b) { return boxes[a].min[axis] < boxes[b].min[axis]; });
  const int other1 = (axis + 1) % 3;
  const int other2 = (axis + 2) % 3;
  open_.clear();
  for (const std::uint32_t i : order_) {
    const Aabb& box = boxes[i];
    // Close the intervals that end before this one starts (closed boxes: equal touches).
    std::erase_if(open_, [&](std::uint32_t j) { return boxes[j].max[axis] < box.min[axis]; });
    for (const std::uint32_t j : open_) {
      const Aabb& other = boxes[j];
      if (box.min[other1] <= other.max[other1] && other.min[other1] <= box.max[other1] &&
          box.min[other2] <= other.max[other2] && other.min[other2] <= box.max[other2]) {
        pairs.emplace_back(std::min(i, j), std::max(i, j));
      }
    }
    open_.push_back(i);
  }
  std::sort(pairs.begin(), pairs.end());
}

}  // namespace proxima::tool
