// sort_pairs against std::sort, and the pair delta against std::set_difference.
#include <gtest/gtest.h>

#include <proxima/broadphase/pair_tracker.hpp>

#include <algorithm>
#include <iterator>
#include <random>
#include <set>
#include <vector>

namespace proxima {
namespace test_pair_tracker {

TEST(SortPairs, MatchesStdSortOnRandomLists) {
  std::mt19937_64 rng(7);
  PairSortScratch scratch;
  for (int round = 0; round < 60; ++round) {
    const std::size_t n = round < 20 ? static_cast<std::size_t>(round) : static_cast<std::size_t>(rng() % 20000);
    const std::uint32_t range = round % 3 == 0 ? 50u : (round % 3 == 1 ? 100000u : 0xffffffffu);
    std::vector<ProxyPair> pairs(n);
    for (ProxyPair& p : pairs) {
      p.lo = static_cast<ProxyId>(rng() % range);
      p.hi = static_cast<ProxyId>(rng() % range);
    }
    std::vector<ProxyPair> want = pairs;
    std::sort(want.begin(), want.end());
    if (round % 2) {
      sort_pairs(pairs, scratch);
    } else {
      sort_pairs(pairs);
    }
    EXPECT_EQ(pairs, want) << "round " << round;
  }
}

TEST(SortPairs, KeysOrderLoBeforeHi) {
  std::vector<ProxyPair> pairs;
  for (ProxyId i = 0; i < 600; ++i) pairs.push_back({600 - i, i * 1000003u});
  sort_pairs(pairs);
  EXPECT_TRUE(std::is_sorted(pairs.begin(), pairs.end()));
  EXPECT_EQ(pairs.front(), (ProxyPair{1, 599u * 1000003u}));
}

TEST(PairTracker, DeltaMatchesSetDifference) {
  std::mt19937_64 rng(11);
  PairTracker tracker;
  std::vector<ProxyPair> previous;
  for (int frame = 0; frame < 50; ++frame) {
    std::set<ProxyPair> set;
    const int n = static_cast<int>(rng() % 400);
    for (int k = 0; k < n; ++k) {
      const ProxyId a = static_cast<ProxyId>(rng() % 60);
      const ProxyId b = static_cast<ProxyId>(rng() % 60);
      if (a != b) set.insert({std::min(a, b), std::max(a, b)});
    }
    if (frame == 10) set.clear();
    const std::vector<ProxyPair> current(set.begin(), set.end());
    std::vector<ProxyPair> begun;
    std::vector<ProxyPair> ended;
    std::set_difference(current.begin(), current.end(), previous.begin(), previous.end(), std::back_inserter(begun));
    std::set_difference(previous.begin(), previous.end(), current.begin(), current.end(), std::back_inserter(ended));
    const PairDelta& d = tracker.update(current);
    EXPECT_EQ(d.begun, begun) << frame;
    EXPECT_EQ(d.ended, ended) << frame;
    EXPECT_EQ(tracker.pairs(), current);
    previous = current;
  }
  tracker.clear();
  const std::vector<ProxyPair> one{{1, 2}};
  EXPECT_EQ(tracker.update(one).begun, one);
  EXPECT_TRUE(tracker.delta().ended.empty());
}

}  // namespace test_pair_tracker
}  // namespace proxima
