/// @file pair_tracker.cpp
/// Radix sort of pair keys and the linear-merge pair delta (see pair_tracker.hpp).

#include <proxima/broadphase/pair_tracker.hpp>

#include <algorithm>
#include <array>

namespace proxima {

namespace {

constexpr int kDigitBits = 11;
constexpr int kDigitCount = (64 + kDigitBits - 1) / kDigitBits;  // 6
constexpr std::size_t kBuckets = std::size_t{1} << kDigitBits;
constexpr std::size_t kSmallSort = 256;

}  // namespace

void sort_pairs(std::vector<ProxyPair>& pairs, PairSortScratch& scratch) {
  const std::size_t n = pairs.size();
  if (n < 2) return;
  if (n <= kSmallSort) {
    std::sort(pairs.begin(), pairs.end());
    return;
  }
  scratch.keys.resize(n);
  scratch.temp.resize(n);
  std::uint64_t* src = scratch.keys.data();
  std::uint64_t* dst = scratch.temp.data();
  // One pass for every digit's histogram.
  std::array<std::array<std::uint32_t, kBuckets>, kDigitCount> hist{};
  std::uint64_t all_or = 0;
  std::uint64_t all_and = ~std::uint64_t{0};
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint64_t k = pair_key(pairs[i]);
    src[i] = k;
    all_or |= k;
    all_and &= k;
  }
  const std::uint64_t varying = all_or ^ all_and;  // bits that differ between some keys
  std::array<bool, kDigitCount> pass{};
  for (int d = 0; d < kDigitCount; ++d) {
    const std::uint64_t digit_mask = ((std::uint64_t{1} << kDigitBits) - 1) << (d * kDigitBits);
    pass[static_cast<std::size_t>(d)] = (varying & digit_mask) != 0;
  }
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint64_t k = src[i];
    for (int d = 0; d < kDigitCount; ++d) {
      if (pass[static_cast<std::size_t>(d)]) {
        ++hist[static_cast<std::size_t>(d)][(k >> (d * kDigitBits)) & (kBuckets - 1)];
      }
    }
  }
  for (int d = 0; d < kDigitCount; ++d) {
    if (!pass[static_cast<std::size_t>(d)]) continue;
    auto& h = hist[static_cast<std::size_t>(d)];
    std::uint32_t sum = 0;
    for (auto& c : h) {
      const std::uint32_t count = c;
      c = sum;
      sum += count;
    }
    const int shift = d * kDigitBits;
    for (std::size_t i = 0; i < n; ++i) {
      const std::uint64_t k = src[i];
      dst[h[(k >> shift) & (kBuckets - 1)]++] = k;
    }
    std::swap(src, dst);
  }
  for (std::size_t i = 0; i < n; ++i) pairs[i] = pair_from_key(src[i]);
}

void sort_pairs(std::vector<ProxyPair>& pairs) {
  thread_local PairSortScratch scratch;
  sort_pairs(pairs, scratch);
}

void pair_delta(std::span<const ProxyPair> previous, std::span<const ProxyPair> current, PairDelta& delta) {
  delta.begun.clear();
  delta.ended.clear();
  std::size_t i = 0;
  std::size_t j = 0;
  while (i < previous.size() && j < current.size()) {
    const std::uint64_t a = pair_key(previous[i]);
    const std::uint64_t b = pair_key(current[j]);
    if (a == b) {
      ++i;
      ++j;
    } else if (a < b) {
      delta.ended.push_back(previous[i++]);
    } else {
      delta.begun.push_back(current[j++]);
    }
  }
  delta.ended.insert(delta.ended.end(), previous.begin() + static_cast<std::ptrdiff_t>(i), previous.end());
  delta.begun.insert(delta.begun.end(), current.begin() + static_cast<std::ptrdiff_t>(j), current.end());
}

const PairDelta& PairTracker::update(std::span<const ProxyPair> current) {
  pair_delta(previous_, current, delta_);
  previous_.assign(current.begin(), current.end());
  return delta_;
}

}  // namespace proxima
