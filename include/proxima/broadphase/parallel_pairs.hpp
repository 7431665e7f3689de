#pragma once
/// @file parallel_pairs.hpp
/// Generic helper for parallel pair finding with output identical to the serial run:
/// the index range [0, count) is cut into chunks taken by `threads` std::threads from an
/// atomic counter; each chunk appends pairs to its own list; the lists are concatenated in
/// chunk order. Callers sort the result (sort_pairs), so the final output does not depend
/// on the thread count or on scheduling. With threads <= 1 or a small range it runs inline.

#include <proxima/broadphase/broadphase.hpp>

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <thread>
#include <vector>

namespace proxima {

/// `threads` with 0 replaced by the hardware concurrency (at least 1).
inline unsigned resolve_thread_count(unsigned threads) {
  if (threads == 0) threads = std::max(1u, std::thread::hardware_concurrency());
  return threads;
}

/// Runs `work(begin, end, pairs)` over chunks of [0, count) on `threads` threads and appends
/// every chunk's pairs to `out` in chunk order (see the file comment). `work` must only
/// read shared data. Ranges shorter than `grain` run inline on the calling thread.
/// Allocates per chunk; meant for large ranges.
template <class Work>
void parallel_pair_chunks(std::size_t count, unsigned threads, std::vector<ProxyPair>& out, Work&& work,
                          std::size_t grain = 2048) {
  threads = resolve_thread_count(threads);
  if (threads <= 1 || count < grain || count < 2) {
    work(std::size_t{0}, count, out);
    return;
  }
  const std::size_t chunks = std::min<std::size_t>(count, std::size_t{threads} * 16);
  const std::size_t chunk_size = (count + chunks - 1) / chunks;
  std::vector<std::vector<ProxyPair>> lists(chunks);
  std::atomic<std::size_t> next{0};
  auto run = [&] {
    for (;;) {
      const std::size_t c = next.fetch_add(1, std::memory_order_relaxed);
      if (c >= chunks) return;
      const std::size_t begin = c * chunk_size;
      const std::size_t end = std::min(count, begin + chunk_size);
      if (begin < end) work(begin, end, lists[c]);
    }
  };
  std::vector<std::thread> pool;
  pool.reserve(threads - 1);
  for (unsigned t = 1; t < threads; ++t) pool.emplace_back(run);
  run();
  for (std::thread& t : pool) t.join();
  std::size_t total = out.size();
  for (const auto& l : lists) total += l.size();
  out.reserve(total);
  for (const auto& l : lists) out.insert(out.end(), l.begin(), l.end());
}

}  // namespace proxima
