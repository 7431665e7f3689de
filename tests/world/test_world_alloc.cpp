// Allocations per step: once a world has seen its largest pair table, event arrays and
// continuous-detection work, a step (and a batch move) allocates nothing, on one thread or
// on a pool. The scene repeats itself: every mover follows a triangle wave of a fixed
// period, so after two periods of warm-up each step meets a configuration already seen and
// every scratch vector already has the capacity it needs.
//
// Allocations are counted by replacing the global operator new: this file is an executable
// of its own (proxima_tests_world_alloc, tests/CMakeLists.txt), left out of the sanitizer
// builds, whose runtimes own operator new.
#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <new>

#include "world/world_scene.hpp"

// GCC sees the replaced operator delete's free() inlined against the operator new of the
// call site and warns of a mismatch; here both are this file's malloc/free pair.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
#endif

namespace {

std::atomic<std::size_t> g_allocations{0};

void* counted(std::size_t size, std::size_t align) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  if (size == 0) size = 1;
  void* p = align <= alignof(std::max_align_t) ? std::malloc(size)
                                               : std::aligned_alloc(align, (size + align - 1) / align * align);
  if (p == nullptr) throw std::bad_alloc();
  return p;
}

}  // namespace

void* operator new(std::size_t size) { return counted(size, 0); }
void* operator new[](std::size_t size) { return counted(size, 0); }
void* operator new(std::size_t size, std::align_val_t align) { return counted(size, std::size_t(align)); }
void* operator new[](std::size_t size, std::align_val_t align) { return counted(size, std::size_t(align)); }
void* operator new(std::size_t size, const std::nothrow_t&) noexcept {
  try {
    return counted(size, 0);
  } catch (...) {
    return nullptr;
  }
}
void* operator new[](std::size_t size, const std::nothrow_t&) noexcept {
  try {
    return counted(size, 0);
  } catch (...) {
    return nullptr;
  }
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
void operator delete(void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete(void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }

namespace proxima::test {
namespace test_world_alloc {

constexpr int kPeriod = 24;

/// Where mover k is at frame f: its start plus a triangle wave of period kPeriod along its
/// velocity (so frame f and f + kPeriod place every object alike).
Transform wave_pose(const Transform& start, const Mover& m, int f) {
  const int phase = f % kPeriod;
  const int t = phase <= kPeriod / 2 ? phase : kPeriod - phase;
  return Transform{start.position + m.velocity * Real(t), start.rotation};
}

/// Allocations per step over one period after two periods of warm-up.
std::vector<std::size_t> allocations_per_step(Executor& executor) {
  CollisionWorld world = make_world();
  Random rng(31);
  std::vector<Mover> movers = populate(world, rng, 200, kExtent);
  std::vector<Transform> starts;
  for (const Mover& m : movers) starts.push_back(world.pose(m.handle));
  std::vector<ObjectMove> moves(movers.size());
  std::vector<std::size_t> counts;
  std::size_t impacts = 0, contacts = 0;
  for (int f = 1; f <= 3 * kPeriod; ++f) {
    for (std::size_t k = 0; k < movers.size(); ++k) moves[k] = {movers[k].handle, wave_pose(starts[k], movers[k], f)};
    const std::size_t before = g_allocations.load();
    EXPECT_FALSE(world.move(moves, executor).has_value());
    EXPECT_FALSE(world.step(Real(1) / Real(60), executor).has_value());
    const std::size_t after = g_allocations.load();
    if (f > 2 * kPeriod) {
      counts.push_back(after - before);
      impacts += world.events().impacts.size();
      contacts += world.contacts().size();
    }
  }
  EXPECT_GT(impacts, 0u) << "the scene must exercise the continuous pass";
  EXPECT_GT(contacts, 0u) << "the scene must keep pairs touching";
  return counts;
}

TEST(WorldAllocations, SteadyStateStepAllocatesNothingOnOneThread) {
  const std::vector<std::size_t> counts = allocations_per_step(serial_executor());
  EXPECT_EQ(counts, std::vector<std::size_t>(counts.size(), 0));
}

TEST(WorldAllocations, SteadyStateStepAllocatesNothingOnAPool) {
  ThreadPool pool(2);
  const std::vector<std::size_t> counts = allocations_per_step(pool);
  EXPECT_EQ(counts, std::vector<std::size_t>(counts.size(), 0));
}

TEST(WorldAllocations, TheCounterSeesAllocations) {
  const std::size_t before = g_allocations.load();
  std::vector<int>* volatile kept = new std::vector<int>(100);
  delete kept;
  EXPECT_GE(g_allocations.load() - before, 2u);
}

}  // namespace test_world_alloc
}  // namespace proxima::test
