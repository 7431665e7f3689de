// Pinned state hashes (as Box2D's test_determinism pins its own): a seeded scene of
// spheres, capsules, boxes, hulls and compounds over a mesh floor and a half-space, moved
// and stepped 40 times (fast enough that continuous detection runs every step), must give
// these exact state hashes in every build of one precision (GCC release, GCC -O1 tests,
// PROXIMA_NATIVE=ON, clang ASan + UBSan, clang TSan) and for every executor: the serial
// one, one that runs every item alone in reverse order, and thread pools of 1, 2, 3, 4, 8
// and 16 threads. A change that moves one bit of one contact anywhere fails here; if it is
// meant, pin the new values and say why in the commit.
#include <gtest/gtest.h>

#include <sstream>

#include "world/world_scene.hpp"

namespace proxima::test {
namespace test_world_determinism {

/// The state hashes after steps 10, 20, 30 and 40; `impacts` (when given) counts the
/// continuous pass's impact events.
std::vector<std::uint64_t> hashes_of_the_scene(Executor& executor, std::size_t* impacts = nullptr) {
  CollisionWorld world = make_world();
  Random rng(2026);
  std::vector<Mover> movers = populate(world, rng, 200, kExtent);
  std::vector<std::uint64_t> hashes;
  for (int f = 1; f <= 40; ++f) {
    advance(world, movers, kExtent);
    EXPECT_FALSE(world.step(Real(1) / Real(60), executor).has_value());
    if (impacts != nullptr) *impacts += world.events().impacts.size();
    if (f % 10 == 0) hashes.push_back(world.state_hash());
  }
  return hashes;
}

TEST(WorldDeterminism, PinnedStateHashes) {
  constexpr bool kFloat = sizeof(Real) == sizeof(float);
  const std::vector<std::uint64_t> pinned =
      kFloat ? std::vector<std::uint64_t>{0x2e8f28bc7ee44841ull, 0x23a8aff5d6b0e013ull, 0xfb65594cf795b16full,
                                          0xb23181195cddd8cdull}
             : std::vector<std::uint64_t>{0xcb4f6761b8d3fc3ull, 0x860e3c2b79e1a967ull, 0x3bc7042512a568e6ull,
                                          0x1788e3fb4bcf3319ull};
  std::size_t impacts = 0;
  const std::vector<std::uint64_t> serial = hashes_of_the_scene(serial_executor(), &impacts);
  EXPECT_GT(impacts, 0u) << "the scene must exercise the continuous pass";
  std::ostringstream got;
  for (std::uint64_t h : serial) got << "0x" << std::hex << h << "ull, ";
  EXPECT_EQ(serial, pinned) << "this build's hashes: " << got.str();
  ReverseExecutor reverse;
  EXPECT_EQ(hashes_of_the_scene(reverse), serial) << "items one by one, in reverse order";
}

TEST(WorldDeterminism, EveryThreadCountGivesTheSerialHashes) {
  const std::vector<std::uint64_t> serial = hashes_of_the_scene(serial_executor());
  for (std::size_t threads : {1u, 2u, 3u, 4u, 8u, 16u}) {
    ThreadPool pool(threads);
    EXPECT_EQ(hashes_of_the_scene(pool), serial) << threads << " threads";
  }
}

}  // namespace test_world_determinism
}  // namespace proxima::test
