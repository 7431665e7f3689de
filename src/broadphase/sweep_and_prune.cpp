/// @file sweep_and_prune.cpp
/// Sweep-and-prune: storage, radix and insertion sorts, the sorted sweep kernels, and the
/// three structures (see sweep_and_prune.hpp for the steps and references).

#include <proxima/broadphase/parallel_pairs.hpp>
#include <proxima/broadphase/sweep_and_prune.hpp>
#include <proxima/geometry/raycast.hpp>

#include <algorithm>
#include <array>
#include <atomic>
#include <bit>
#include <cmath>
#include <limits>

namespace proxima {

namespace {

/// Order-preserving 32-bit key of a coordinate: exact for float; for double the top 32 bits
/// of the order-preserving 64-bit key (ties are then resolved by an insertion-sort pass).
std::uint32_t sort_key(Real x) {
  if constexpr (sizeof(Real) == 4) {
    const std::uint32_t u = std::bit_cast<std::uint32_t>(static_cast<float>(x));
    return (u & 0x80000000u) ? ~u : (u | 0x80000000u);
  } else {
    const std::uint64_t u = std::bit_cast<std::uint64_t>(static_cast<double>(x));
    const std::uint64_t k = (u & 0x8000000000000000ull) ? ~u : (u | 0x8000000000000000ull);
    return static_cast<std::uint32_t>(k >> 32);
  }
}

/// Insertion sort of ids by keys (both permuted together). Gives up (returns false) once
/// more than `budget` element moves were made; the arrays are then still a permutation.
bool insertion_sort(std::vector<Real>& keys, std::vector<ProxyId>& ids, std::size_t budget) {
  std::size_t moves = 0;
  const std::size_t n = keys.size();
  for (std::size_t i = 1; i < n; ++i) {
    const Real k = keys[i];
    if (!(k < keys[i - 1])) continue;
    const ProxyId id = ids[i];
    std::size_t j = i;
    while (j > 0 && k < keys[j - 1]) {
      keys[j] = keys[j - 1];
      ids[j] = ids[j - 1];
      --j;
    }
    keys[j] = k;
    ids[j] = id;
    moves += i - j;
    if (moves > budget) return false;
  }
  return true;
}

inline bool overlaps_bc(const SweepRecord& a, const SweepRecord& b) {
  return (b.min_b <= a.max_b) & (a.min_b <= b.max_b) & (b.min_c <= a.max_c) & (a.min_c <= b.max_c);
}

inline bool filters_accept(const SweepRecord& a, const SweepRecord& b) {
  return (a.layer & b.mask) != 0 && (b.layer & a.mask) != 0;
}

inline void emit(const SweepRecord& a, const SweepRecord& b, std::vector<ProxyPair>& out) {
  out.push_back(a.id < b.id ? ProxyPair{a.id, b.id} : ProxyPair{b.id, a.id});
}

struct AcceptAll {
  bool operator()(const SweepRecord&, const SweepRecord&) const { return true; }
};

/// Moving-moving: for i in [begin, end), every j > i with min_j <= max_i.
template <class Accept>
std::uint64_t sweep_self(const SweepList& list, std::size_t begin, std::size_t end, std::vector<ProxyPair>& out,
                         const Accept& accept) {
  std::uint64_t tested = 0;
  const Real* min_a = list.min_a.data();
  const SweepRecord* rec = list.record.data();
  for (std::size_t i = begin; i < end; ++i) {
    const SweepRecord& ri = rec[i];
    const Real max_a = ri.max_a;
    std::size_t j = i + 1;
    for (; min_a[j] <= max_a; ++j) {
      const SweepRecord& rj = rec[j];
      if (overlaps_bc(ri, rj) && filters_accept(ri, rj) && accept(ri, rj)) emit(ri, rj, out);
    }
    tested += j - i - 1;
  }
  return tested;
}

/// Moving side of the moving-static sweep: for moving i in [begin, end), statics with
/// min_i <= min_s <= max_i.
template <class Accept>
std::uint64_t sweep_moving_side(const SweepList& moving, const SweepList& statics, std::size_t begin, std::size_t end,
                                std::vector<ProxyPair>& out, const Accept& accept) {
  if (statics.size() == 0 || begin >= end) return 0;
  std::uint64_t tested = 0;
  const Real* s_min = statics.min_a.data();
  std::size_t k =
      static_cast<std::size_t>(std::lower_bound(s_min, s_min + statics.size(), moving.min_a[begin]) - s_min);
  for (std::size_t i = begin; i < end; ++i) {
    const Real lo = moving.min_a[i];
    while (s_min[k] < lo) ++k;  // the sentinel stops it
    const SweepRecord& ri = moving.record[i];
    std::size_t j = k;
    for (; s_min[j] <= ri.max_a; ++j) {
      const SweepRecord& rj = statics.record[j];
      if (overlaps_bc(ri, rj) && filters_accept(ri, rj) && accept(ri, rj)) emit(ri, rj, out);
    }
    tested += j - k;
  }
  return tested;
}

/// Static side: for static s in [begin, end), moving boxes with min_s < min_m <= max_s.
template <class Accept>
std::uint64_t sweep_static_side(const SweepList& moving, const SweepList& statics, std::size_t begin, std::size_t end,
                                std::vector<ProxyPair>& out, const Accept& accept) {
  if (moving.size() == 0 || begin >= end) return 0;
  std::uint64_t tested = 0;
  const Real* m_min = moving.min_a.data();
  std::size_t k =
      static_cast<std::size_t>(std::upper_bound(m_min, m_min + moving.size(), statics.min_a[begin]) - m_min);
  for (std::size_t s = begin; s < end; ++s) {
    const Real lo = statics.min_a[s];
    while (m_min[k] <= lo) ++k;
    const SweepRecord& rs = statics.record[s];
    std::size_t j = k;
    for (; m_min[j] <= rs.max_a; ++j) {
      const SweepRecord& rj = moving.record[j];
      if (overlaps_bc(rs, rj) && filters_accept(rs, rj) && accept(rs, rj)) emit(rs, rj, out);
    }
    tested += j - k;
  }
  return tested;
}

/// All pairs of one moving list and one static list, on `executor` (unsorted).
template <class Accept>
std::uint64_t sweep_all(const SweepList& moving, const SweepList& statics, Executor& executor,
                        std::vector<ProxyPair>& out, const Accept& accept) {
  std::atomic<std::uint64_t> tested{0};
  parallel_pair_chunks(moving.size(), executor, out, [&](std::size_t b, std::size_t e, std::vector<ProxyPair>& o) {
    tested += sweep_self(moving, b, e, o, accept) + sweep_moving_side(moving, statics, b, e, o, accept);
  });
  if (moving.size() > 0) {
    parallel_pair_chunks(statics.size(), executor, out, [&](std::size_t b, std::size_t e, std::vector<ProxyPair>& o) {
      tested += sweep_static_side(moving, statics, b, e, o, accept);
    });
  }
  return tested.load();
}

}  // namespace

// ---- storage -----------------------------------------------------------------------------

BroadPhaseStatus SweepStorage::insert(ProxyId id, const Aabb& box, ProxyKind kind, ProxyFilter filter) {
  if (const BroadPhaseStatus s = check_box(box); s != BroadPhaseStatus::Ok) return s;
  if (id < state_.size() && state_[id] != kAbsent) return BroadPhaseStatus::DuplicateId;
  if (id >= state_.size()) {
    const std::size_t n = std::size_t{id} + 1;
    box_.resize(n);
    filter_.resize(n);
    state_.resize(n, kAbsent);
    listed_.resize(n, 0);
  }
  const std::uint8_t k = kind == ProxyKind::Static ? kStatic : kMoving;
  box_[id] = box;
  filter_[id] = filter;
  state_[id] = k;
  if (!(listed_[id] & k)) {
    listed_[id] = static_cast<std::uint8_t>(listed_[id] | k);
    (k == kStatic ? static_ : moving_).push_back(id);
  }
  if (k == kStatic) {
    static_dirty_ = true;
  } else {
    ++moving_added_;
  }
  ++count_;
  return BroadPhaseStatus::Ok;
}

BroadPhaseStatus SweepStorage::remove(ProxyId id) {
  if (id >= state_.size() || state_[id] == kAbsent) return BroadPhaseStatus::UnknownId;
  if (state_[id] == kStatic) static_dirty_ = true;
  state_[id] = kAbsent;
  --count_;
  return BroadPhaseStatus::Ok;
}

BroadPhaseStatus SweepStorage::update(ProxyId id, const Aabb& box) {
  if (const BroadPhaseStatus s = check_box(box); s != BroadPhaseStatus::Ok) return s;
  if (id >= state_.size() || state_[id] == kAbsent) return BroadPhaseStatus::UnknownId;
  box_[id] = box;
  if (state_[id] == kStatic) static_dirty_ = true;
  return BroadPhaseStatus::Ok;
}

BroadPhaseStatus SweepStorage::update(std::span<const ProxyUpdate> updates) {
  for (const ProxyUpdate& u : updates) {
    if (const BroadPhaseStatus s = check_box(u.box); s != BroadPhaseStatus::Ok) return s;
    if (u.id >= state_.size() || state_[u.id] == kAbsent) return BroadPhaseStatus::UnknownId;
  }
  for (const ProxyUpdate& u : updates) {
    box_[u.id] = u.box;
    if (state_[u.id] == kStatic) static_dirty_ = true;
  }
  return BroadPhaseStatus::Ok;
}

bool SweepStorage::validate() const {
  const std::size_t n = state_.size();
  if (box_.size() != n || filter_.size() != n || listed_.size() != n) return false;
  std::vector<std::uint8_t> seen(n, 0);
  for (const auto* list : {&moving_, &static_}) {
    const std::uint8_t bit = list == &moving_ ? kMoving : kStatic;
    for (ProxyId id : *list) {
      if (id >= n || (seen[id] & bit) || !(listed_[id] & bit)) return false;
      seen[id] = static_cast<std::uint8_t>(seen[id] | bit);
    }
  }
  std::size_t present = 0;
  for (std::size_t id = 0; id < n; ++id) {
    if (seen[id] != listed_[id]) return false;
    if (state_[id] == kAbsent) continue;
    ++present;
    if (!(listed_[id] & state_[id])) return false;
    if (check_box(box_[id]) != BroadPhaseStatus::Ok) return false;
  }
  return present == count_;
}

std::size_t SweepStorage::compact(std::vector<ProxyId>& list, std::uint8_t kind) {
  std::size_t w = 0;
  for (ProxyId id : list) {
    if (state_[id] == kind) {
      list[w++] = id;
    } else {
      listed_[id] = static_cast<std::uint8_t>(listed_[id] & ~kind);
    }
  }
  const std::size_t dropped = list.size() - w;
  list.resize(w);
  return dropped;
}

int SweepStorage::variance_axis() const {
  double sum[3] = {0, 0, 0};
  double sum2[3] = {0, 0, 0};
  double n = 0;
  for (const auto* list : {&moving_, &static_}) {
    for (ProxyId id : *list) {
      const Aabb& b = box_[id];
      for (int a = 0; a < 3; ++a) {
        const double c = 0.5 * (static_cast<double>(b.min[a]) + static_cast<double>(b.max[a]));
        sum[a] += c;
        sum2[a] += c * c;
      }
      n += 1;
    }
  }
  if (n == 0) return 0;
  int best = 0;
  double best_var = -1;
  for (int a = 0; a < 3; ++a) {
    const double mean = sum[a] / n;
    const double var = sum2[a] / n - mean * mean;
    if (var > best_var) {
      best_var = var;
      best = a;
    }
  }
  return best;
}

void SweepStorage::gather(const std::vector<ProxyId>& order, int axis, SweepList& list) const {
  const int b = (axis + 1) % 3;
  const int c = (axis + 2) % 3;
  const std::size_t n = order.size();
  list.min_a.resize(n + 1);
  list.record.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const ProxyId id = order[i];
    const Aabb& box = box_[id];
    list.min_a[i] = box.min[axis];
    list.record[i] = {box.max[axis], box.min[b], box.max[b],        box.min[c],
                      box.max[c],    id,         filter_[id].layer, filter_[id].mask};
  }
  list.min_a[n] = std::numeric_limits<Real>::infinity();
}

void SweepStorage::radix_sort_ids(std::vector<ProxyId>& ids, int axis) {
  const std::size_t n = ids.size();
  if (n < 2) return;
  if (n <= 64) {
    exact_keys_.resize(n);
    for (std::size_t i = 0; i < n; ++i) exact_keys_[i] = box_[ids[i]].min[axis];
    insertion_sort(exact_keys_, ids, std::numeric_limits<std::size_t>::max());
    return;
  }
  keys_.resize(n);
  keys_tmp_.resize(n);
  std::uint64_t all_or = 0;
  std::uint64_t all_and = ~std::uint64_t{0};
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint64_t k = (std::uint64_t{sort_key(box_[ids[i]].min[axis])} << 32) | i;
    keys_[i] = k;
    all_or |= k;
    all_and &= k;
  }
  const std::uint64_t varying = (all_or ^ all_and) >> 32;
  constexpr int kRadixBits = 11;
  constexpr std::size_t kRadixBuckets = std::size_t{1} << kRadixBits;
  std::uint64_t* src = keys_.data();
  std::uint64_t* dst = keys_tmp_.data();
  for (int shift = 0; shift < 32; shift += kRadixBits) {
    if (n <= 2048) {  // small lists: a comparison sort beats clearing the histograms
      std::sort(src, src + n);
      break;
    }
    if (((varying >> shift) & (kRadixBuckets - 1)) == 0) continue;
    std::array<std::uint32_t, kRadixBuckets> hist{};
    for (std::size_t i = 0; i < n; ++i) ++hist[(src[i] >> (32 + shift)) & (kRadixBuckets - 1)];
    std::uint32_t sum = 0;
    for (auto& h : hist) {
      const std::uint32_t c = h;
      h = sum;
      sum += c;
    }
    for (std::size_t i = 0; i < n; ++i) dst[hist[(src[i] >> (32 + shift)) & (kRadixBuckets - 1)]++] = src[i];
    std::swap(src, dst);
  }
  ids_tmp_.resize(n);
  for (std::size_t i = 0; i < n; ++i) ids_tmp_[i] = ids[src[i] & 0xffffffffu];
  ids.swap(ids_tmp_);
  if constexpr (sizeof(Real) != 4) {
    // The 32-bit keys of doubles tie for nearby values: finish with an insertion sort.
    exact_keys_.resize(n);
    for (std::size_t i = 0; i < n; ++i) exact_keys_[i] = box_[ids[i]].min[axis];
    insertion_sort(exact_keys_, ids, std::numeric_limits<std::size_t>::max());
  }
}

// ---- SweepAndPrune -----------------------------------------------------------------------

void SweepAndPrune::rebuild() {
  compact(moving_, kMoving);
  compact(static_, kStatic);
  axis_ = variance_axis();
  frames_since_axis_check_ = 0;
  radix_sort_ids(moving_, axis_);
  radix_sort_ids(static_, axis_);
  gather(static_, axis_, static_list_);
  static_dirty_ = false;
  moving_added_ = 0;
}

void SweepAndPrune::find_pairs(std::vector<ProxyPair>& out, Executor& executor) {
  out.clear();
  stats_ = {};
  if (compact(static_, kStatic) > 0) static_dirty_ = true;
  compact(moving_, kMoving);
  bool full_sort = false;
  if (axis_ < 0 || ++frames_since_axis_check_ >= 32) {
    const int best = variance_axis();
    frames_since_axis_check_ = 0;
    if (best != axis_) {
      axis_ = best;
      full_sort = true;
      static_dirty_ = true;
    }
  }
  const std::size_t n = moving_.size();
  if (full_sort || moving_added_ > 64 + n / 16) {
    radix_sort_ids(moving_, axis_);
  } else {
    sort_keys_.resize(n);
    for (std::size_t i = 0; i < n; ++i) sort_keys_[i] = box_[moving_[i]].min[axis_];
    if (!insertion_sort(sort_keys_, moving_, 4 * n + 1024)) radix_sort_ids(moving_, axis_);
  }
  moving_added_ = 0;
  if (static_dirty_) {
    radix_sort_ids(static_, axis_);
    gather(static_, axis_, static_list_);
    static_dirty_ = false;
  }
  gather(moving_, axis_, moving_list_);
  stats_.pairs_tested = sweep_all(moving_list_, static_list_, executor, out, AcceptAll{});
  stats_.nodes_visited = moving_list_.size() + static_list_.size();
  sort_pairs(out, pair_scratch_);
  stats_.pairs_found = out.size();
}

// ---- SortedSweep -------------------------------------------------------------------------

void SortedSweep::find_pairs(std::vector<ProxyPair>& out, Executor& executor) {
  out.clear();
  stats_ = {};
  if (compact(static_, kStatic) > 0) static_dirty_ = true;
  compact(moving_, kMoving);
  const int axis = variance_axis();
  radix_sort_ids(moving_, axis);
  if (static_dirty_ || axis != static_axis_) {
    radix_sort_ids(static_, axis);
    gather(static_, axis, static_list_);
    static_axis_ = axis;
    static_dirty_ = false;
  }
  gather(moving_, axis, moving_list_);
  stats_.pairs_tested = sweep_all(moving_list_, static_list_, executor, out, AcceptAll{});
  stats_.nodes_visited = moving_list_.size() + static_list_.size();
  sort_pairs(out, pair_scratch_);
  stats_.pairs_found = out.size();
}

// ---- MultiBoxPruning ---------------------------------------------------------------------

void MultiBoxPruning::find_pairs(std::vector<ProxyPair>& out, Executor& executor) {
  out.clear();
  stats_ = {};
  compact(static_, kStatic);
  compact(moving_, kMoving);
  const int axis = variance_axis();
  const int ax_b = (axis + 1) % 3;
  const int ax_c = (axis + 2) % 3;
  // Grid over the bounds of the centres on axes b and c.
  Real lo_b = kRealMax, hi_b = -kRealMax, lo_c = kRealMax, hi_c = -kRealMax;
  for (const auto* list : {&moving_, &static_}) {
    for (ProxyId id : *list) {
      const Vec3 ctr = box_[id].center();
      lo_b = std::min(lo_b, ctr[ax_b]);
      hi_b = std::max(hi_b, ctr[ax_b]);
      lo_c = std::min(lo_c, ctr[ax_c]);
      hi_c = std::max(hi_c, ctr[ax_c]);
    }
  }
  const std::size_t n = moving_.size() + static_.size();
  const double span_b = static_cast<double>(hi_b) - static_cast<double>(lo_b);
  const double span_c = static_cast<double>(hi_c) - static_cast<double>(lo_c);
  // Cells about kCellBoxes mean box edges wide, at least kMinPerCell boxes per cell on
  // average, at most 64 x 64 cells.
  double mean_edge = 0;
  for (const auto* list : {&moving_, &static_}) {
    for (ProxyId id : *list) {
      const Aabb& b = box_[id];
      mean_edge += static_cast<double>(b.max[ax_b] - b.min[ax_b]) + static_cast<double>(b.max[ax_c] - b.min[ax_c]);
    }
  }
  mean_edge = n == 0 ? 0.0 : mean_edge / (2.0 * static_cast<double>(n));
  constexpr double kCellBoxes = 4.0;
  constexpr double kMinPerCell = 48.0;
  const double by_size = mean_edge > 0 ? std::max(span_b, span_c) / (kCellBoxes * mean_edge) : 1.0;
  const double by_count = std::sqrt(static_cast<double>(n) / kMinPerCell);
  const int g = static_cast<int>(std::clamp(std::min(by_size, by_count), 1.0, 64.0));
  const double inv_b = span_b > 0 ? g / span_b : 0.0;
  const double inv_c = span_c > 0 ? g / span_c : 0.0;
  // Monotone cell index of a coordinate (clamped before the conversion to int, so that
  // boxes reaching kMaxCoordinate, such as a half-space's, stay defined), the same for
  // assignment and ownership.
  const double last = static_cast<double>(g - 1);
  auto cell_b = [&](Real x) {
    return static_cast<int>(std::clamp(std::floor((static_cast<double>(x) - lo_b) * inv_b), 0.0, last));
  };
  auto cell_c = [&](Real x) {
    return static_cast<int>(std::clamp(std::floor((static_cast<double>(x) - lo_c) * inv_c), 0.0, last));
  };
  const std::size_t cells = static_cast<std::size_t>(g) * static_cast<std::size_t>(g);
  cell_moving_.resize(cells);
  cell_static_.resize(cells);
  cell_lists_.resize(2 * cells);
  for (std::size_t c = 0; c < cells; ++c) {
    cell_moving_[c].clear();
    cell_static_[c].clear();
  }
  for (int kind = 0; kind < 2; ++kind) {
    const auto& list = kind == 0 ? moving_ : static_;
    auto& target = kind == 0 ? cell_moving_ : cell_static_;
    for (ProxyId id : list) {
      const Aabb& b = box_[id];
      const int b0 = cell_b(b.min[ax_b]), b1 = cell_b(b.max[ax_b]);
      const int c0 = cell_c(b.min[ax_c]), c1 = cell_c(b.max[ax_c]);
      for (int i = b0; i <= b1; ++i) {
        for (int j = c0; j <= c1; ++j) target[static_cast<std::size_t>(i * g + j)].push_back(id);
      }
    }
  }
  std::uint64_t tested = 0;
  for (std::size_t c = 0; c < cells; ++c) {
    if (cell_moving_[c].empty()) continue;
    radix_sort_ids(cell_moving_[c], axis);
    radix_sort_ids(cell_static_[c], axis);
    gather(cell_moving_[c], axis, cell_lists_[2 * c]);
    gather(cell_static_[c], axis, cell_lists_[2 * c + 1]);
  }
  std::atomic<std::uint64_t> tested_all{0};
  parallel_pair_chunks(
      cells, executor, out,
      [&](std::size_t begin, std::size_t end, std::vector<ProxyPair>& o) {
        std::uint64_t t = 0;
        for (std::size_t c = begin; c < end; ++c) {
          if (cell_moving_[c].empty()) continue;
          const int ci = static_cast<int>(c) / g;
          const int cj = static_cast<int>(c) % g;
          // Report a pair only in the cell holding its intersection's min corner.
          auto owner = [&](const SweepRecord& p, const SweepRecord& q) {
            return cell_b(std::max(p.min_b, q.min_b)) == ci && cell_c(std::max(p.min_c, q.min_c)) == cj;
          };
          t += sweep_all(cell_lists_[2 * c], cell_lists_[2 * c + 1], serial_executor(), o, owner);
        }
        tested_all += t;
      },
      /*grain=*/4);
  tested = tested_all.load();
  stats_.pairs_tested = tested;
  stats_.nodes_visited = cells;
  sort_pairs(out, pair_scratch_);
  stats_.pairs_found = out.size();
}

}  // namespace proxima
