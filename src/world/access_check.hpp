#pragma once
// Internal: the debug checks of CollisionWorld's thread-safety rules (collision_world.hpp).
//
// The rules: queries (const calls) may run at the same time as each other, from any number
// of threads; a change (add, remove, move, set_*, attach, ...) or a step runs alone. The
// step's own thread is the exception: its listeners and pair filter run on it and may query
// the world, and its event callbacks may change it (world_listener.hpp).
//
// Steps of the check, in builds where PROXIMA_ASSERT is on (debug, PROXIMA_ENABLE_ASSERTS):
//   1. a change or a step (WriteScope) claims the world for its thread by a compare-exchange
//      of the writer's thread id; it fails PROXIMA_ASSERT when another thread holds the
//      claim (two changes at once) or when a query is counted (a change during a query);
//      the claiming thread may nest further changes (callbacks of the step);
//   2. a query (ReadScope) from a thread other than the writer's is counted among the
//      readers, and fails PROXIMA_ASSERT when a writer holds the claim (a query during a
//      change or a step);
//   3. each scope undoes its claim or its count when it ends.
// The checks are best effort, like the body-lock checks of Jolt Physics: two calls that
// overlap by a hair may slip through, but a test that holds one call open while the other
// runs (tests/world/test_world_thread_safety.cpp) is always caught. In other builds the
// scopes are empty and cost nothing.
#include <proxima/core/assert.hpp>

#include <atomic>
#include <cstdint>
#include <thread>

namespace proxima::detail {

#if !defined(NDEBUG) || defined(PROXIMA_ENABLE_ASSERTS)
/// True when the world's thread-safety checks are compiled in.
inline constexpr bool kWorldAccessChecks = true;

/// The claim of the writer and the count of the readers of one world (see the file comment).
class AccessCheck {
 public:
  /// Step 1: claims the world for this thread; true when this call made the outermost claim.
  bool begin_write() {
    const std::thread::id me = std::this_thread::get_id();
    if (writer_.load(std::memory_order_acquire) == me) {
      ++depth_;
      return true;
    }
    std::thread::id none{};
    const bool claimed = writer_.compare_exchange_strong(none, me, std::memory_order_acq_rel);
    PROXIMA_ASSERT(claimed && "CollisionWorld: a change or step while another thread changes or steps the world");
    PROXIMA_ASSERT(readers_.load(std::memory_order_acquire) == 0 &&
                   "CollisionWorld: a change or step while another thread queries the world");
    if (claimed) depth_ = 1;
    return claimed;
  }
  /// Step 3 of a write scope that begin_write() reported as claimed.
  void end_write() {
    if (--depth_ == 0) writer_.store(std::thread::id{}, std::memory_order_release);
  }
  /// Step 2: counts a query; false (not counted) on the writer's own thread.
  bool begin_read() const {
    if (writer_.load(std::memory_order_acquire) == std::this_thread::get_id()) return false;
    readers_.fetch_add(1, std::memory_order_acq_rel);
    PROXIMA_ASSERT(writer_.load(std::memory_order_acquire) == std::thread::id{} &&
                   "CollisionWorld: a query while another thread changes or steps the world");
    return true;
  }
  /// Step 3 of a counted query.
  void end_read() const { readers_.fetch_sub(1, std::memory_order_acq_rel); }

 private:
  std::atomic<std::thread::id> writer_{};
  mutable std::atomic<std::uint32_t> readers_{0};
  std::uint32_t depth_ = 0;  ///< nesting of the writer's claims (touched by the writer only)
};

/// A change or a step for the scope's lifetime.
class WriteScope {
 public:
  explicit WriteScope(AccessCheck& check) : check_(check), claimed_(check.begin_write()) {}
  ~WriteScope() {
    if (claimed_) check_.end_write();
  }
  WriteScope(const WriteScope&) = delete;
  WriteScope& operator=(const WriteScope&) = delete;

 private:
  AccessCheck& check_;
  bool claimed_;
};

/// A query for the scope's lifetime.
class ReadScope {
 public:
  explicit ReadScope(const AccessCheck& check) : check_(check), counted_(check.begin_read()) {}
  ~ReadScope() {
    if (counted_) check_.end_read();
  }
  ReadScope(const ReadScope&) = delete;
  ReadScope& operator=(const ReadScope&) = delete;

 private:
  const AccessCheck& check_;
  bool counted_;
};
#else
/// True when the world's thread-safety checks are compiled in.
inline constexpr bool kWorldAccessChecks = false;

/// Empty in builds without assertions.
class AccessCheck {};
/// Empty in builds without assertions.
class WriteScope {
 public:
  explicit WriteScope(AccessCheck&) {}
};
/// Empty in builds without assertions.
class ReadScope {
 public:
  explicit ReadScope(const AccessCheck&) {}
};
#endif

}  // namespace proxima::detail
