#pragma once
/// @file w1_grid_pairs.hpp
/// Every overlapping pair of a set of closed boxes in double precision (the W1 query of
/// shared/bench FORMATS.md), in linear time at constant density: the reference of the
/// broad-phase benchmark (bench_broadphase.cpp) and of `proxima bench broadphase`
/// (tools/bench_command.cpp). Header-only.
///
/// Steps (a uniform grid, Ericson, Real-Time Collision Detection 7.1): 1. the cell is 1.01 x
/// the largest box edge (grown by 1.5x while the grid would have more than 4n + 64 cells),
/// so two overlapping boxes have min corners in cells at most 1 apart per axis, despite
/// rounding (1 % margin); 2. counting sort of the boxes by the cell of their min corner;
/// 3. each box tests the boxes of the 27 cells around its own, larger indices only, so each
/// pair is met once. O(n + cells + tests). A sweep on one axis is O(n^(5/3)) at constant
/// density (10^10 tests per frame at 1M boxes).

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace proxima::bench {

/// Adds every overlapping pair {i, j} (i < j) of `boxes` to `sum` with sum.add(i, j, n).
/// Box: `double lo[3], hi[3]` (closed, lo <= hi). Sum: `add(i, j, n)`.
template <class Box, class Sum>
void w1_grid_pairs(const std::vector<Box>& boxes, Sum& sum) {
  const std::size_t n = boxes.size();
  if (n < 2) return;
  double mn[3] = {1e300, 1e300, 1e300};
  double mx[3] = {-1e300, -1e300, -1e300};
  double extent = 0;
  for (const Box& b : boxes) {
    for (int k = 0; k < 3; ++k) {
      mn[k] = std::min(mn[k], b.lo[k]);
      mx[k] = std::max(mx[k], b.lo[k]);
      extent = std::max(extent, b.hi[k] - b.lo[k]);
    }
  }
  double cell = std::max(extent * 1.01, 1e-300);
  std::int64_t dims[3];
  for (;;) {
    std::int64_t total = 1;
    for (int k = 0; k < 3; ++k) {
      dims[k] = std::int64_t(std::min((mx[k] - mn[k]) / cell, 1e9)) + 1;
      total = total > (std::int64_t(1) << 40) / dims[k] ? (std::int64_t(1) << 40) : total * dims[k];
    }
    if (total <= std::int64_t(4 * n + 64)) break;
    cell *= 1.5;
  }
  auto coord = [&](const Box& b, int k) {
    return std::clamp(std::int64_t((b.lo[k] - mn[k]) / cell), std::int64_t(0), dims[k] - 1);
  };
  const std::size_t cells = std::size_t(dims[0] * dims[1] * dims[2]);
  std::vector<std::uint32_t> start(cells + 1, 0);
  std::vector<std::uint32_t> key(n);
  for (std::size_t i = 0; i < n; ++i) {
    key[i] = std::uint32_t((coord(boxes[i], 0) * dims[1] + coord(boxes[i], 1)) * dims[2] + coord(boxes[i], 2));
    ++start[key[i] + 1];
  }
  for (std::size_t c = 0; c < cells; ++c) start[c + 1] += start[c];
  std::vector<std::uint32_t> items(n);
  {
    std::vector<std::uint32_t> fill(start.begin(), start.end() - 1);
    for (std::size_t i = 0; i < n; ++i) items[fill[key[i]]++] = std::uint32_t(i);
  }
  for (std::size_t i = 0; i < n; ++i) {
    const Box& a = boxes[i];
    const std::int64_t c0 = coord(a, 0), c1 = coord(a, 1), c2 = coord(a, 2);
    for (std::int64_t x = std::max<std::int64_t>(c0 - 1, 0); x <= std::min(c0 + 1, dims[0] - 1); ++x) {
      for (std::int64_t y = std::max<std::int64_t>(c1 - 1, 0); y <= std::min(c1 + 1, dims[1] - 1); ++y) {
        for (std::int64_t z = std::max<std::int64_t>(c2 - 1, 0); z <= std::min(c2 + 1, dims[2] - 1); ++z) {
          const std::size_t c = std::size_t((x * dims[1] + y) * dims[2] + z);
          for (std::uint32_t k = start[c]; k < start[c + 1]; ++k) {
            const std::uint32_t j = items[k];
            if (j <= i) continue;
            const Box& b = boxes[j];
            if (a.lo[0] <= b.hi[0] && b.lo[0] <= a.hi[0] && a.lo[1] <= b.hi[1] && b.lo[1] <= a.hi[1] &&
                a.lo[2] <= b.hi[2] && b.lo[2] <= a.hi[2]) {
              sum.add(i, j, n);
            }
          }
        }
      }
    }
  }
}

}  // namespace proxima::bench
