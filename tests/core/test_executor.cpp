// Executor, SerialExecutor, ThreadPool and FunctionRef: every item of a range is run exactly
// once for any count and thread count; nested runs, exceptions and runs from several
// threads; the test executor set of core/executor_set.hpp.

#include <gtest/gtest.h>

#include <proxima/core/executor.hpp>
#include <proxima/core/function_ref.hpp>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <stdexcept>
#include <thread>
#include <vector>

#include "core/executor_set.hpp"

namespace proxima {
namespace test_executor {

/// Runs [0, count) on `executor` and checks that every item was called exactly once.
void expect_each_item_once(Executor& executor, std::size_t count) {
  std::vector<std::atomic<int>> calls(count);
  executor.run(count, [&](std::size_t begin, std::size_t end) {
    ASSERT_LT(begin, end);
    ASSERT_LE(end, count);
    for (std::size_t i = begin; i < end; ++i) calls[i].fetch_add(1);
  });
  for (std::size_t i = 0; i < count; ++i) ASSERT_EQ(calls[i].load(), 1) << "item " << i << " of " << count;
}

TEST(FunctionRef, CallsTheReferencedCallable) {
  int state = 2;
  auto add = [&](int x) { return state += x; };
  const FunctionRef<int(int)> ref(add);
  EXPECT_EQ(ref(3), 5);
  EXPECT_EQ(ref(1), 6);
  EXPECT_EQ(state, 6);
  int (*twice)(int) = [](int x) { return 2 * x; };
  EXPECT_EQ(FunctionRef<long(int)>(twice)(21), 42L);
}

TEST(Executor, SerialRunsTheWholeRangeInOneCall) {
  int calls = 0;
  serial_executor().run(17, [&](std::size_t begin, std::size_t end) {
    ++calls;
    EXPECT_EQ(begin, 0u);
    EXPECT_EQ(end, 17u);
  });
  serial_executor().run(0, [&](std::size_t, std::size_t) { ++calls; });
  EXPECT_EQ(calls, 1);
  EXPECT_EQ(serial_executor().concurrency(), 1u);
}

TEST(Executor, EveryItemOnceForAnyCountAndThreadCount) {
  for (test::NamedExecutor& e : test::test_executors()) {
    for (const std::size_t count : {0, 1, 2, 7, 64, 1000, 100003}) {
      SCOPED_TRACE(e.name + " count " + std::to_string(count));
      expect_each_item_once(*e.executor, count);
    }
  }
}

TEST(ThreadPool, ConcurrencyIsTheThreadCount) {
  EXPECT_EQ(ThreadPool(1).concurrency(), 1u);
  EXPECT_EQ(ThreadPool(3).concurrency(), 3u);
  EXPECT_GE(ThreadPool(0).concurrency(), 1u);
}

TEST(ThreadPool, UsesSeveralThreads) {
  ThreadPool pool(4);
  std::vector<std::thread::id> seen(4000);
  pool.run(seen.size(), [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) seen[i] = std::this_thread::get_id();
    std::this_thread::sleep_for(std::chrono::microseconds(200));  // let the workers join in
  });
  std::sort(seen.begin(), seen.end());
  EXPECT_GT(std::unique(seen.begin(), seen.end()) - seen.begin(), 1);
}

TEST(ThreadPool, NestedRunGoesInline) {
  ThreadPool pool(3);
  std::atomic<std::size_t> inner{0};
  pool.run(12, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) {
      pool.run(10, [&](std::size_t b, std::size_t e) { inner.fetch_add(e - b); });
    }
  });
  EXPECT_EQ(inner.load(), 120u);
}

TEST(ThreadPool, RethrowsATaskExceptionAndStaysUsable) {
  ThreadPool pool(3);
  std::atomic<std::size_t> done{0};
  EXPECT_THROW(pool.run(1000,
                        [&](std::size_t begin, std::size_t end) {
                          done.fetch_add(end - begin);
                          if (begin <= 500 && 500 < end) throw std::runtime_error("item 500");
                        }),
               std::runtime_error);
  EXPECT_EQ(done.load(), 1000u);  // the rest of the range still ran
  expect_each_item_once(pool, 5000);
}

TEST(ThreadPool, RunsFromSeveralThreadsAreServedInTurn) {
  ThreadPool pool(3);
  std::vector<std::thread> callers;
  std::atomic<int> failures{0};
  for (int c = 0; c < 4; ++c) {
    callers.emplace_back([&] {
      for (int round = 0; round < 50; ++round) {
        std::atomic<std::size_t> sum{0};
        pool.run(300, [&](std::size_t begin, std::size_t end) {
          for (std::size_t i = begin; i < end; ++i) sum.fetch_add(i);
        });
        if (sum.load() != 300u * 299u / 2u) failures.fetch_add(1);
      }
    });
  }
  for (std::thread& t : callers) t.join();
  EXPECT_EQ(failures.load(), 0);
}

TEST(ThreadPool, ManySmallRunsInARow) {
  ThreadPool pool(8);
  for (int round = 0; round < 2000; ++round) expect_each_item_once(pool, std::size_t(round % 40));
}

}  // namespace test_executor
}  // namespace proxima
