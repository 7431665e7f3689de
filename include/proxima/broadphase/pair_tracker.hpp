#pragma once
/// @file pair_tracker.hpp
/// Pair-list utilities shared by every broad-phase structure:
/// - `sort_pairs`: sorts (lo, hi) pairs by (lo, hi) with an LSD radix sort on 64-bit keys
///   (lo << 32 | hi), 11-bit digits, skipping digits that are equal in every key (ids are
///   usually small, so most passes are skipped). Small lists use std::sort.
/// - `pair_delta` / `PairTracker`: the pairs begun and ended between two successive sorted
///   pair lists, by one linear merge (O(n + m), no hashing).

#include <proxima/broadphase/broadphase.hpp>

#include <cstdint>
#include <span>
#include <vector>

namespace proxima {

/// Reusable scratch for `sort_pairs`, so repeated sorts do not allocate once warmed up.
struct PairSortScratch {
  std::vector<std::uint64_t> keys;  ///< packed keys
  std::vector<std::uint64_t> temp;  ///< ping-pong buffer
};

/// Sorts `pairs` ascending by (lo, hi). O(n) radix passes (at most 6, usually 2-3).
/// Duplicates are kept. Every pair must already have lo < hi (or any order: it sorts as is).
void sort_pairs(std::vector<ProxyPair>& pairs, PairSortScratch& scratch);
/// As above with a scratch owned by the calling thread (allocates on first use only).
void sort_pairs(std::vector<ProxyPair>& pairs);

/// Packs a pair into its 64-bit sort key, lo in the high half.
constexpr std::uint64_t pair_key(const ProxyPair& p) {
  return (static_cast<std::uint64_t>(p.lo) << 32) | static_cast<std::uint64_t>(p.hi);
}
/// Unpacks a key made by pair_key.
constexpr ProxyPair pair_from_key(std::uint64_t key) {
  return {static_cast<ProxyId>(key >> 32), static_cast<ProxyId>(key & 0xffffffffu)};
}

/// Fills `delta` with the pairs of `current` not in `previous` (begun) and of `previous`
/// not in `current` (ended). Both inputs sorted and duplicate-free; outputs sorted. O(n + m).
void pair_delta(std::span<const ProxyPair> previous, std::span<const ProxyPair> current, PairDelta& delta);

/// Remembers the last sorted pair list and reports the delta against each new one.
class PairTracker {
 public:
  /// Computes the delta from the remembered list to `current` (sorted, duplicate-free),
  /// then remembers `current`. The first call reports every pair as begun.
  const PairDelta& update(std::span<const ProxyPair> current);
  /// The last delta computed.
  const PairDelta& delta() const { return delta_; }
  /// The remembered pair list (the argument of the last update).
  const std::vector<ProxyPair>& pairs() const { return previous_; }
  /// Forgets the remembered pairs (the next update reports all as begun).
  void clear() {
    previous_.clear();
    delta_.begun.clear();
    delta_.ended.clear();
  }

 private:
  std::vector<ProxyPair> previous_;
  PairDelta delta_;
};

}  // namespace proxima
