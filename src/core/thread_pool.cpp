/// @file thread_pool.cpp
/// ThreadPool and the shared SerialExecutor.
///
/// Steps of ThreadPool::run(count, task):
/// 1. Inline (task(0, count) on the caller) when the pool has one thread, the range has one
///    item, or the caller is already running one of this pool's tasks (nested run).
/// 2. Otherwise publish a PoolJob (the task, the range, an atomic cursor, a grain of about
///    count / (8 threads)) under the mutex with a new generation number and wake the workers.
/// 3. Every participant (the caller and each worker that joins) takes grains from the cursor
///    until it passes count; the first exception of a task (when built with exceptions) is
///    kept, the rest of the range still runs.
/// 4. The caller, its own grains done, waits until no worker is inside the job, withdraws
///    the job (late workers see none) and rethrows the kept exception, if any.
/// Workers sleep on a condition variable between jobs; the destructor stops and joins them.

#include <proxima/core/config.hpp>
#include <proxima/core/executor.hpp>

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace proxima {

namespace detail {

/// One run() in progress.
struct PoolJob {
  RangeTask task;
  std::size_t count = 0;
  std::size_t grain = 1;
  std::atomic<std::size_t> cursor{0};
  std::mutex error_mutex;
  std::exception_ptr error;

  PoolJob(RangeTask t, std::size_t n, std::size_t g) : task(t), count(n), grain(g) {}

  /// Takes grains until the range is exhausted (step 3).
  void work() {
    for (;;) {
      const std::size_t begin = cursor.fetch_add(grain, std::memory_order_relaxed);
      if (begin >= count) return;
      const std::size_t end = std::min(count, begin + grain);
#if PROXIMA_EXCEPTIONS
      try {
        task(begin, end);
      } catch (...) {
        const std::lock_guard<std::mutex> lock(error_mutex);
        if (!error) error = std::current_exception();
      }
#else
      task(begin, end);  // built without exceptions: a task cannot throw
#endif
    }
  }
};

}  // namespace detail

struct ThreadPool::Shared {
  std::size_t concurrency = 1;
  std::vector<std::thread> workers;
  std::mutex run_mutex;              ///< serves run() calls from several threads one after another
  std::mutex mutex;                  ///< guards the fields below
  std::condition_variable wake;      ///< workers: a new job or stop
  std::condition_variable finished;  ///< caller: the last worker left the job
  std::uint64_t generation = 0;      ///< number of jobs published
  detail::PoolJob* job = nullptr;    ///< the job workers may join, or none
  std::size_t active = 0;            ///< workers inside `job`
  bool stop = false;

  void worker_loop();
};

namespace {

/// The pool whose task the current thread is running (nested runs go inline).
thread_local const void* t_running_pool = nullptr;

/// Sets t_running_pool for a scope.
class RunningPool {
 public:
  explicit RunningPool(const void* pool) : previous_(t_running_pool) { t_running_pool = pool; }
  ~RunningPool() { t_running_pool = previous_; }
  RunningPool(const RunningPool&) = delete;
  RunningPool& operator=(const RunningPool&) = delete;

 private:
  const void* previous_;
};

}  // namespace

void ThreadPool::Shared::worker_loop() {
  const RunningPool running(this);
  std::uint64_t seen = 0;
  for (;;) {
    detail::PoolJob* current = nullptr;
    {
      std::unique_lock<std::mutex> lock(mutex);
      wake.wait(lock, [&] { return stop || (job != nullptr && generation != seen); });
      if (stop) return;
      seen = generation;
      current = job;
      ++active;
    }
    current->work();
    const std::lock_guard<std::mutex> lock(mutex);
    if (--active == 0) finished.notify_one();
  }
}

SerialExecutor& serial_executor() {
  static SerialExecutor instance;
  return instance;
}

ThreadPool::ThreadPool(std::size_t threads) : shared_(std::make_unique<Shared>()) {
  if (threads == 0) threads = std::max(1u, std::thread::hardware_concurrency());
  shared_->concurrency = threads;
  shared_->workers.reserve(threads - 1);
  for (std::size_t i = 1; i < threads; ++i) shared_->workers.emplace_back([s = shared_.get()] { s->worker_loop(); });
}

ThreadPool::~ThreadPool() {
  {
    const std::lock_guard<std::mutex> lock(shared_->mutex);
    shared_->stop = true;
  }
  shared_->wake.notify_all();
  for (std::thread& t : shared_->workers) t.join();
}

std::size_t ThreadPool::concurrency() const { return shared_->concurrency; }

void ThreadPool::run(std::size_t count, RangeTask task) {
  if (count == 0) return;
  Shared& s = *shared_;
  if (s.concurrency <= 1 || count == 1 || t_running_pool == &s) {
    task(0, count);
    return;
  }
  const std::lock_guard<std::mutex> serve(s.run_mutex);
  detail::PoolJob job(task, count, std::max<std::size_t>(1, count / (8 * s.concurrency)));
  {
    const std::lock_guard<std::mutex> lock(s.mutex);
    s.job = &job;
    ++s.generation;
  }
  s.wake.notify_all();
  {
    const RunningPool running(&s);
    job.work();
  }
  {
    std::unique_lock<std::mutex> lock(s.mutex);
    s.finished.wait(lock, [&] { return s.active == 0; });
    s.job = nullptr;
  }
#if PROXIMA_EXCEPTIONS
  if (job.error) std::rethrow_exception(job.error);
#endif
}

}  // namespace proxima
