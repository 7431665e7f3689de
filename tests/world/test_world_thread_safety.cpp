// CollisionWorld's thread-safety rules (collision_world.hpp): queries from many threads at
// once give the serial answers; in builds with assertions, a query or a change on another
// thread while a step or a batched query is held open is caught by the debug checks
// (src/world/access_check.hpp), while the step's own callbacks may query and change the
// world. The held-open call waits inside its executor, so the two calls overlap for certain
// and never touch the same data at the same time (the tests are clean under TSan).
#include <gtest/gtest.h>

#include <proxima/core/assert.hpp>

#include <atomic>
#include <future>
#include <thread>

#include "world/access_check.hpp"
#include "world/world_scene.hpp"

namespace proxima::test {
namespace test_world_thread_safety {

std::atomic<int> g_failures{0};

void count_failure(const char*, const char*, int) { g_failures.fetch_add(1); }

/// Routes PROXIMA_ASSERT to a counter for its lifetime.
class CountingAsserts {
 public:
  CountingAsserts() : previous_(set_assert_handler(&count_failure)) { g_failures = 0; }
  ~CountingAsserts() { set_assert_handler(previous_); }
  CountingAsserts(const CountingAsserts&) = delete;
  CountingAsserts& operator=(const CountingAsserts&) = delete;
  int failures() const { return g_failures.load(); }

 private:
  AssertHandler previous_;
};

/// An executor whose first run() reports that it was entered and waits for release() before
/// running its range on the calling thread: it holds the call that uses it open.
class HoldingExecutor final : public Executor {
 public:
  std::size_t concurrency() const override { return 2; }
  void run(std::size_t count, RangeTask task) override {
    if (!held_) {
      held_ = true;
      entered_.set_value();
      released_future_.wait();
    }
    if (count > 0) task(0, count);
  }
  void wait_entered() { entered_future_.wait(); }
  void release() { released_.set_value(); }

 private:
  bool held_ = false;
  std::promise<void> entered_;
  std::promise<void> released_;
  std::future<void> entered_future_ = entered_.get_future();  ///< taken before any thread runs
  std::shared_future<void> released_future_ = released_.get_future().share();
};

/// A stepped world of `count` random objects.
CollisionWorld scene(int count) {
  CollisionWorld world = make_world();
  Random rng(4242);
  populate(world, rng, count, kExtent);
  EXPECT_FALSE(world.step(Real(1) / Real(60)).has_value());
  return world;
}

const Ray kDown{Vec3(0, 0, 10), Vec3(0, 0, -1)};

TEST(WorldThreadSafety, QueryOrChangeDuringAStepOnAnotherThreadIsCaught) {
  if (!detail::kWorldAccessChecks) GTEST_SKIP() << "the checks are compiled in with assertions only";
  CollisionWorld world = scene(40);
  const ObjectHandle some = world.objects()[5];
  const CountingAsserts asserts;
  HoldingExecutor hold;
  std::thread stepper([&] { EXPECT_FALSE(world.step(Real(1) / Real(60), hold).has_value()); });
  hold.wait_entered();
  EXPECT_EQ(asserts.failures(), 0);
  EXPECT_TRUE(world.raycast(kDown, Real(20)).ok());
  const int after_query = asserts.failures();
  EXPECT_GE(after_query, 1) << "a query during a step on another thread";
  EXPECT_FALSE(world.set_user_data(some, 5).has_value());
  EXPECT_GT(asserts.failures(), after_query) << "a change during a step on another thread";
  hold.release();
  stepper.join();
}

TEST(WorldThreadSafety, ChangeDuringAQueryOnAnotherThreadIsCaughtAndQueriesMayOverlap) {
  if (!detail::kWorldAccessChecks) GTEST_SKIP() << "the checks are compiled in with assertions only";
  CollisionWorld world = scene(40);
  const ObjectHandle some = world.objects()[5];
  const std::vector<WorldRay> rays(8, WorldRay{kDown.origin, kDown.direction, Real(20)});
  std::vector<WorldHit> hits(rays.size());
  const CountingAsserts asserts;
  HoldingExecutor hold;
  std::thread querier([&] { EXPECT_TRUE(world.raycast_batch(rays, hits, {}, hold).ok()); });
  hold.wait_entered();
  EXPECT_TRUE(world.raycast(kDown, Real(20)).ok());
  EXPECT_TRUE(world.overlap_box(Aabb{Vec3(-1), Vec3(1)}).ok());
  EXPECT_EQ(asserts.failures(), 0) << "queries may overlap";
  EXPECT_FALSE(world.set_user_data(some, 9).has_value());
  EXPECT_GE(asserts.failures(), 1) << "a change during a query on another thread";
  hold.release();
  querier.join();
}

/// Queries from the pair filter and queries and changes from the event callbacks: all on
/// the step's thread, all allowed.
class BusyCallbacks final : public WorldListener, public PairFilterCallback {
 public:
  int calls = 0;
  bool can_collide(const CollisionWorld& world, ObjectPair pair) override {
    ++calls;
    return world.contains(pair.a) && world.object(pair.b).has_value();
  }
  void on_contact_begin(CollisionWorld& world, const ContactEvent& event) override {
    ++calls;
    EXPECT_TRUE(world.raycast(kDown, Real(20)).ok());
    if (world.contains(event.pair.b)) {
      EXPECT_FALSE(world.move(event.pair.b, world.pose(event.pair.b)).has_value());
    }
  }
};

TEST(WorldThreadSafety, CallbacksMayQueryAndChangeTheWorldOnTheStepThread) {
  CollisionWorld world = scene(60);
  BusyCallbacks callbacks;
  world.set_listener(&callbacks);
  world.set_pair_filter(&callbacks);
  const CountingAsserts asserts;
  ThreadPool pool(2);
  for (int f = 0; f < 3; ++f) {
    ASSERT_FALSE(world.step(Real(1) / Real(60), pool).has_value());
  }
  EXPECT_GT(callbacks.calls, 0);
  EXPECT_EQ(asserts.failures(), 0);
  world.set_listener(nullptr);
  world.set_pair_filter(nullptr);
}

TEST(WorldThreadSafety, ManyThreadsQueryAtOnceAndGetTheSerialAnswers) {
  CollisionWorld world = scene(120);
  Random rng(99);
  std::vector<Ray> rays;
  std::vector<Aabb> boxes;
  for (int k = 0; k < 64; ++k) {
    rays.push_back(Ray{rng.vec3(-kExtent, kExtent), rng.unit_vector()});
    const Vec3 c = rng.vec3(-kExtent, kExtent);
    boxes.push_back(Aabb{c - Vec3(1), c + Vec3(1)});
  }
  auto answers = [&] {
    std::vector<std::uint64_t> out;
    for (std::size_t k = 0; k < rays.size(); ++k) {
      const auto hits = world.raycast(rays[k], Real(30), {}, QueryMode::All);
      const auto found = world.overlap_box(boxes[k]);
      if (!hits.ok() || !found.ok()) {
        out.push_back(~0ull);
        continue;
      }
      for (const WorldHit& h : *hits) out.push_back(h.object.index);
      for (const WorldOverlap& o : *found) out.push_back(o.object.index + (1ull << 32));
      out.push_back(world.state_hash());
    }
    return out;
  };
  const std::vector<std::uint64_t> serial = answers();
  const CountingAsserts asserts;
  std::vector<std::vector<std::uint64_t>> got(4);
  std::vector<std::thread> threads;
  for (std::size_t t = 0; t < got.size(); ++t) threads.emplace_back([&, t] { got[t] = answers(); });
  for (std::thread& t : threads) t.join();
  for (std::size_t t = 0; t < got.size(); ++t) EXPECT_EQ(got[t], serial) << "thread " << t;
  EXPECT_EQ(asserts.failures(), 0);
}

}  // namespace test_world_thread_safety
}  // namespace proxima::test
