#pragma once
// The executors that the "identical to serial" tests run every parallel entry point on: the
// serial executor, ThreadPools of 1, 2, 3 and 8 threads, and a ScrambledExecutor that claims
// 4 threads but calls one item at a time in a shuffled order (split shapes and orders no
// thread pool would produce).

#include <proxima/core/executor.hpp>

#include <algorithm>
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <numeric>
#include <random>
#include <string>
#include <vector>

namespace proxima::test {

/// Runs every item as its own call, in a shuffled order, on the calling thread; reports
/// `concurrency` so callers split their work as for that many threads.
class ScrambledExecutor final : public Executor {
 public:
  explicit ScrambledExecutor(std::size_t concurrency, std::uint64_t seed = 7) : concurrency_(concurrency), rng_(seed) {}
  std::size_t concurrency() const override { return concurrency_; }
  void run(std::size_t count, RangeTask task) override {
    std::vector<std::size_t> order(count);
    std::iota(order.begin(), order.end(), std::size_t{0});
    std::shuffle(order.begin(), order.end(), rng_);
    for (const std::size_t i : order) task(i, i + 1);
  }

 private:
  std::size_t concurrency_;
  std::mt19937_64 rng_;
};

/// One executor of the test set with a name for failure messages.
struct NamedExecutor {
  std::string name;
  std::unique_ptr<Executor> executor;
};

/// A ThreadPool of `threads` threads shared by the tests for the whole run (for structures
/// that hold an executor reference, see broadphase_scenes.hpp's OnExecutor).
inline ThreadPool& shared_pool(std::size_t threads) {
  static std::mutex mutex;
  static std::map<std::size_t, std::unique_ptr<ThreadPool>> pools;
  const std::lock_guard<std::mutex> lock(mutex);
  std::unique_ptr<ThreadPool>& pool = pools[threads];
  if (!pool) pool = std::make_unique<ThreadPool>(threads);
  return *pool;
}

/// The test set (see the file comment); the pools live as long as the returned vector.
inline std::vector<NamedExecutor> test_executors() {
  std::vector<NamedExecutor> set;
  set.push_back({"serial", std::make_unique<SerialExecutor>()});
  for (const std::size_t threads : {1, 2, 3, 8}) {
    set.push_back({"pool:" + std::to_string(threads), std::make_unique<ThreadPool>(threads)});
  }
  set.push_back({"scrambled:4", std::make_unique<ScrambledExecutor>(4)});
  return set;
}

}  // namespace proxima::test
