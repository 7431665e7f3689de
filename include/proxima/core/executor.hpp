#pragma once
/// @file executor.hpp
/// The task-system seam: everything in the library that runs in parallel (find_pairs(out,
/// executor) of the broad phases, raycast_batch) takes an Executor and never starts threads
/// of its own, so an application runs the library on its own task system (oneTBB, a game
/// engine's job system; examples/tbb_executor.cpp adapts oneTBB) or on the library's
/// ThreadPool.
///
/// Contract of Executor::run(count, task): task(begin, end) is called over disjoint ranges
/// that together cover [0, count), each item exactly once, possibly on several threads at
/// once and in any order; run returns when every call has returned. Callers make their
/// output independent of the split (each item writes only its own results, or per-item
/// lists are joined in item order), so every executor and thread count gives the serial
/// answer. concurrency() says how many calls may run at once; callers size their work items
/// by it (a handful of items per thread) and run inline when it is 1.
///
/// SerialExecutor runs the whole range on the calling thread; serial_executor() is a shared
/// instance and the default of every parallel entry point. ThreadPool keeps concurrency() - 1
/// worker threads for its lifetime (no thread start per call) and the calling thread works
/// as one of them.

#include <proxima/core/function_ref.hpp>

#include <cstddef>
#include <memory>

namespace proxima {

/// Body of a parallel loop: processes the items [begin, end) (indices into the caller's
/// work, end > begin).
using RangeTask = FunctionRef<void(std::size_t begin, std::size_t end)>;

/// A parallel-for over an index range (see the file comment for the contract).
class Executor {
 public:
  virtual ~Executor() = default;
  /// How many task calls may run at the same time (>= 1; 1 = everything on the caller).
  virtual std::size_t concurrency() const = 0;
  /// Calls `task` over disjoint ranges covering [0, count), each item once, and returns when
  /// all calls have returned. count = 0 calls nothing. An exception thrown by a call is
  /// rethrown here after the other calls have finished.
  virtual void run(std::size_t count, RangeTask task) = 0;
};

/// Runs everything on the calling thread: task(0, count). Stateless and thread-safe.
class SerialExecutor final : public Executor {
 public:
  /// Always 1.
  std::size_t concurrency() const override { return 1; }
  /// task(0, count) when count > 0.
  void run(std::size_t count, RangeTask task) override {
    if (count > 0) task(0, count);
  }
};

/// A shared SerialExecutor: the default executor of the library's parallel entry points.
SerialExecutor& serial_executor();

/// A pool of persistent worker threads (see the file comment). run() hands out the range in
/// contiguous grains from an atomic counter (about 8 grains per thread); the calling thread
/// takes grains too. Calls of run() from several threads are served one after another; a
/// run() from inside one of this pool's tasks runs its range inline on that thread. Not
/// copyable or movable.
class ThreadPool final : public Executor {
 public:
  /// A pool whose run() uses `threads` threads, the caller of run() included (0 =
  /// std::thread::hardware_concurrency(), at least 1): starts threads - 1 workers.
  explicit ThreadPool(std::size_t threads = 0);
  /// Stops and joins the workers (no run() may be in progress).
  ~ThreadPool() override;
  ThreadPool(const ThreadPool&) = delete;
  ThreadPool& operator=(const ThreadPool&) = delete;

  /// The thread count given to the constructor (0 resolved).
  std::size_t concurrency() const override;
  /// See Executor::run.
  void run(std::size_t count, RangeTask task) override;

 private:
  struct Shared;
  std::unique_ptr<Shared> shared_;
};

}  // namespace proxima
