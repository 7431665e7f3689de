// The W1 motion rule and checksum: mix64 against splitmix64's known output, the motion
// rule on hand-made reflections, the sort-and-sweep pair finder against an O(N^2) brute
// force (random boxes with many exact contacts, and whole frames of the shared 10k file),
// and the full 100-frame checksum of broadphase_uniform_10k.txt against the value
// FORMATS.md publishes.
#include <gtest/gtest.h>

#include "support/random.hpp"
#include "workload_test_util.hpp"

namespace proxima::bench {
namespace test_broadphase_checksum {

using Pairs = std::vector<std::pair<std::uint32_t, std::uint32_t>>;

/// Every overlapping pair by testing all N (N - 1) / 2 of them (closed boxes, double).
Pairs brute_force_pairs(const std::vector<BroadphaseBox>& boxes) {
  Pairs pairs;
  for (std::size_t i = 0; i < boxes.size(); ++i) {
    for (std::size_t j = i + 1; j < boxes.size(); ++j) {
      bool overlap = true;
      for (int a = 0; a < 3 && overlap; ++a) {
        const double lo_i = boxes[i].center[a] - boxes[i].half_extents[a];
        const double hi_i = boxes[i].center[a] + boxes[i].half_extents[a];
        const double lo_j = boxes[j].center[a] - boxes[j].half_extents[a];
        const double hi_j = boxes[j].center[a] + boxes[j].half_extents[a];
        overlap = lo_i <= hi_j && lo_j <= hi_i;
      }
      if (overlap) pairs.emplace_back(static_cast<std::uint32_t>(i), static_cast<std::uint32_t>(j));
    }
  }
  return pairs;
}

TEST(BroadphaseChecksum, Mix64IsTheSplitMix64Finaliser) {
  // splitmix64 seeded with 0 outputs mix64(0) first (Vigna's reference values).
  EXPECT_EQ(mix64(0), 0xe220a8397b1dcdafull);
  EXPECT_EQ(mix64(0x9E3779B97F4A7C15ull), 0x6e789e6aa1b965f4ull);
  EXPECT_EQ(mix64(2 * 0x9E3779B97F4A7C15ull), 0x06c45d188009454full);
}

TEST(BroadphaseChecksum, AddIsSymmetricAndWraps) {
  PairChecksum a, b;
  a.add(3, 7, 10);
  b.add(7, 3, 10);
  EXPECT_EQ(a, b);
  EXPECT_EQ(a.pairs, 1u);
  EXPECT_EQ(a.hash, mix64(37));
  PairChecksum c;
  c.hash = ~std::uint64_t{0};
  c.add(0, 1, 2);  // wraps modulo 2^64
  EXPECT_EQ(c.hash, mix64(1) - 1);
  PairChecksum d{720303, 0xc1e09e3295fd3406ull};
  EXPECT_EQ(d.to_string(), "pairs=720303 hash=c1e09e3295fd3406");
  PairChecksum e{1, 0xabc};
  EXPECT_EQ(e.hash_hex(), "0000000000000abc");
  d.merge(e);
  EXPECT_EQ(d.pairs, 720304u);
}

TEST(BroadphaseChecksum, PublishedValues) {
  EXPECT_EQ(published_checksum("broadphase_uniform_10k").checksum.to_string(), "pairs=720303 hash=c1e09e3295fd3406");
  EXPECT_EQ(published_checksum("broadphase_uniform_100k").checksum.to_string(), "pairs=7369738 hash=fca122572cefbcdd");
  EXPECT_EQ(published_checksum("broadphase_clustered_100k").checksum.to_string(),
            "pairs=16152504 hash=68b8cf6bf40bc812");
  EXPECT_FALSE(published_checksum("something_else").found);
}

TEST(BroadphaseChecksum, MotionRuleReflectsTheCentre) {
  std::vector<BroadphaseBox> boxes(2);
  boxes[0].center = {0.05, 5, 9.95};
  boxes[0].velocity = {-0.125, 0.5, 0.125};
  boxes[0].half_extents = {1, 1, 1};
  boxes[1].center = {10, 0, 3};
  boxes[1].velocity = {0, 0, 0};
  advance_frame(boxes, 1.0, 0.0, 10.0);
  // x: 0.05 - 0.125 = -0.075 -> 0.075, v flips; z: 10.075 -> 9.925, v flips.
  EXPECT_DOUBLE_EQ(boxes[0].center.x, 0.075);
  EXPECT_EQ(boxes[0].velocity.x, 0.125);
  EXPECT_EQ(boxes[0].center.y, 5.5);
  EXPECT_EQ(boxes[0].velocity.y, 0.5);
  EXPECT_DOUBLE_EQ(boxes[0].center.z, 9.925);
  EXPECT_EQ(boxes[0].velocity.z, -0.125);
  EXPECT_EQ(boxes[1].center, (Vec3d{10, 0, 3}));  // on the wall, not beyond: unchanged
  EXPECT_EQ(boxes[1].velocity, (Vec3d{0, 0, 0}));
  // Landing exactly on the wall does not reflect.
  boxes[0].center = {0.5, 5, 5};
  boxes[0].velocity = {-0.5, 0, 0};
  advance_frame(boxes, 1.0, 0.0, 10.0);
  EXPECT_EQ(boxes[0].center.x, 0.0);
  EXPECT_EQ(boxes[0].velocity.x, -0.5);
}

TEST(BroadphaseChecksum, SweepEqualsBruteForceWithExactContacts) {
  // Integer coordinates and half extents: many boxes touch exactly (zero overlap).
  test::Random random(20240601);
  for (int trial = 0; trial < 20; ++trial) {
    std::vector<BroadphaseBox> boxes(400);
    for (BroadphaseBox& b : boxes) {
      for (int a = 0; a < 3; ++a) {
        b.center[a] = random.integer(0, 20);
        b.half_extents[a] = random.integer(0, 2) + (trial % 2 == 0 ? 0.0 : 0.5);
      }
    }
    const Pairs expected = brute_force_pairs(boxes);
    EXPECT_EQ(overlapping_pairs(boxes), expected) << "trial " << trial;
    EXPECT_GT(expected.size(), 0u);
  }
  EXPECT_TRUE(overlapping_pairs({}).empty());
}

TEST(BroadphaseChecksum, Uniform10kMatchesPublishedChecksum) {
  const std::string dir = test_util::shared_dir();
  if (dir.empty()) GTEST_SKIP() << "shared workloads not found";
  const auto w = read_broadphase(workload_path(dir, "broadphase_uniform_10k.txt"));
  ASSERT_TRUE(w.ok()) << w.error().what();

  // The sweep against brute force on whole frames of the file (a subset of the 100).
  std::vector<BroadphaseBox> boxes = w->boxes;
  for (int frame = 1; frame <= w->frames; ++frame) {
    advance_frame(boxes, w->dt, w->lo, w->hi);
    if (frame == 1 || frame == 2 || frame == 50 || frame == w->frames) {
      EXPECT_EQ(overlapping_pairs(boxes), brute_force_pairs(boxes)) << "frame " << frame;
    }
  }
  // The whole run with the sweep: the published pairs and hash.
  const KnownChecksum published = published_checksum(w->name);
  ASSERT_TRUE(published.found);
  const PairChecksum run = reference_checksum(*w);
  EXPECT_EQ(run.to_string(), "pairs=720303 hash=c1e09e3295fd3406");
  EXPECT_EQ(run, published.checksum);
}

}  // namespace test_broadphase_checksum
}  // namespace proxima::bench
