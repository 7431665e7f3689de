#pragma once
/// @file parallel_pairs.hpp
/// Generic helper for parallel pair finding with output identical to the serial run, on any
/// Executor (core/executor.hpp): the index range [0, count) is cut into chunks (about 16 per
/// thread of the executor), the executor runs the chunks, each chunk appends pairs to its own
/// list, and the lists are concatenated in chunk order. Callers sort the result
/// (sort_pairs), so the final output depends neither on the executor, its thread count nor
/// on scheduling. With an executor of concurrency 1 or a small range it runs inline.

#include <proxima/broadphase/broadphase.hpp>
#include <proxima/core/executor.hpp>

#include <algorithm>
#include <cstddef>
#include <vector>

namespace proxima {

/// Per-chunk pair lists kept between calls, so that steady-state frames allocate nothing.
using PairChunkLists = std::vector<std::vector<ProxyPair>>;

/// Runs `work(begin, end, pairs)` over `chunks` equal chunks of [0, count) on `executor`,
/// chunk c appending to lists[c] (cleared first; `lists` grows to `chunks`), then appends the
/// lists to `out` in chunk order. `work` must only read shared data.
template <class Work>
void run_pair_chunks(std::size_t count, std::size_t chunks, Executor& executor, PairChunkLists& lists,
                     std::vector<ProxyPair>& out, Work&& work) {
  chunks = std::clamp<std::size_t>(chunks, 1, std::max<std::size_t>(count, 1));
  const std::size_t chunk_size = (count + chunks - 1) / chunks;
  if (lists.size() < chunks) lists.resize(chunks);
  executor.run(chunks, [&](std::size_t first, std::size_t last) {
    for (std::size_t c = first; c < last; ++c) {
      lists[c].clear();
      const std::size_t begin = std::min(count, c * chunk_size);
      const std::size_t end = std::min(count, begin + chunk_size);
      if (begin < end) work(begin, end, lists[c]);
    }
  });
  std::size_t total = out.size();
  for (std::size_t c = 0; c < chunks; ++c) total += lists[c].size();
  out.reserve(total);
  for (std::size_t c = 0; c < chunks; ++c) out.insert(out.end(), lists[c].begin(), lists[c].end());
}

/// Runs `work(begin, end, pairs)` over chunks of [0, count) on `executor` and appends every
/// chunk's pairs to `out` in chunk order (see the file comment). `work` must only read
/// shared data. Ranges shorter than `grain`, and executors of concurrency 1, run inline on
/// the calling thread. Allocates per chunk; meant for large ranges.
template <class Work>
void parallel_pair_chunks(std::size_t count, Executor& executor, std::vector<ProxyPair>& out, Work&& work,
                          std::size_t grain = 2048) {
  const std::size_t threads = executor.concurrency();
  if (threads <= 1 || count < grain || count < 2) {
    work(std::size_t{0}, count, out);
    return;
  }
  PairChunkLists lists;
  run_pair_chunks(count, std::min(count, threads * 16), executor, lists, out, work);
}

}  // namespace proxima
