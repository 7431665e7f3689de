#pragma once
/// @file sweep_and_prune.hpp
/// Sweep-and-prune broad phases (Baraff 1992; Cohen et al., I-COLLIDE 1995; Terdiman,
/// "Box pruning revisited" 2017; PhysX MBP/ABP):
///
/// 1. Boxes are stored by id. Moving and static proxies are kept in two separate lists, so
///    static-static pairs are never swept.
/// 2. The sweep axis is the axis of largest variance of the box centres.
/// 3. Each list is sorted by the boxes' min on the sweep axis: `SweepAndPrune` ("sap") keeps
///    the order from the previous frame and repairs it by insertion sort (temporal coherence:
///    O(n + swaps)), falling back to a radix sort when the budget of swaps is exceeded or
///    many proxies were added; `SortedSweep` ("sap_oneshot") radix-sorts from scratch every
///    time (for mass changes and all-pairs from scratch).
/// 4. The sorted boxes are gathered into contiguous records and swept: for each moving box i,
///    the following boxes j with min_j <= max_i (a +inf sentinel ends the loop) are tested on
///    the two other axes and the filters; moving-static pairs come from a two-list sweep.
/// 5. The pairs are radix-sorted (sort_pairs).
/// `MultiBoxPruning` ("mbp") handles the single-axis clustering problem (many boxes
/// overlapping on every axis projection, e.g. a flat world): a grid of G x G cells over the
/// two axes other than the sweep axis, one sorted sweep per cell; a pair found in several
/// cells is reported only by the cell holding the min corner of the two boxes' intersection.
///
/// Parallel pair finding: `find_pairs(out, executor)` splits the sweep into chunks of boxes
/// (mbp: of cells) run by the executor; each chunk fills its own list; the lists are
/// concatenated in chunk order and sorted, so the output is identical to the serial one.
/// Queries (aabb, point, ray) scan the stored boxes linearly (O(n)).

#include <proxima/broadphase/broadphase.hpp>
#include <proxima/broadphase/pair_tracker.hpp>
#include <proxima/core/executor.hpp>
#include <proxima/geometry/raycast.hpp>

#include <algorithm>
#include <cstdint>
#include <span>
#include <vector>

namespace proxima {

/// One box of a sorted sweep list, gathered contiguously (the sweep axis is "a", the
/// others "b" and "c"; the min on "a" is stored apart, in SweepList::min_a).
struct SweepRecord {
  Real max_a;
  Real min_b;
  Real max_b;
  Real min_c;
  Real max_c;
  ProxyId id;
  std::uint32_t layer;
  std::uint32_t mask;
};

/// A list of boxes sorted by min on the sweep axis, with a +inf sentinel after the last.
struct SweepList {
  std::vector<Real> min_a;          ///< sorted; size() + 1 entries (sentinel last)
  std::vector<SweepRecord> record;  ///< same order; size() entries
  std::size_t size() const { return record.size(); }
};

/// Storage shared by the sweep structures: boxes, kinds and filters indexed by id, the
/// moving and static id lists, the linear queries and validate().
class SweepStorage {
 public:
  /// Adds a proxy. Rejects bad boxes (check_box) and ids already present.
  BroadPhaseStatus insert(ProxyId id, const Aabb& box, ProxyKind kind, ProxyFilter filter = {});
  /// Removes a proxy.
  BroadPhaseStatus remove(ProxyId id);
  /// Replaces the box of a proxy.
  BroadPhaseStatus update(ProxyId id, const Aabb& box);
  /// Replaces several boxes; all or nothing; a repeated id ends with its last box.
  BroadPhaseStatus update(std::span<const ProxyUpdate> updates);
  /// Proxies whose box overlaps or touches `box` (linear scan); returns the counters.
  template <OverlapCallback OnOverlap>
  BroadPhaseStats query_aabb(const Aabb& box, OnOverlap&& on_overlap) const {
    return scan([&](const Aabb& b) { return b.overlaps(box); }, on_overlap);
  }
  /// Proxies whose box contains `point` (linear scan); returns the counters.
  template <OverlapCallback OnOverlap>
  BroadPhaseStats query_point(const Vec3& point, OnOverlap&& on_overlap) const {
    return scan([&](const Aabb& b) { return b.contains(point); }, on_overlap);
  }
  /// Proxies hit by the ray at t <= the current max fraction (linear scan, ray_aabb's t);
  /// returns the counters.
  template <RayCallback OnRay>
  BroadPhaseStats query_ray(const Ray& ray, Real max_t, OnRay&& on_ray) const;
  /// Checks the lists against the id table and every stored box.
  bool validate() const;
  /// Counters of the last find_pairs.
  BroadPhaseStats stats() const { return stats_; }
  /// Number of proxies.
  std::size_t size() const { return count_; }

 protected:
  enum : std::uint8_t { kAbsent = 0, kMoving = 1, kStatic = 2 };
  /// Drops removed or re-kinded ids from a list (stable); returns the number dropped.
  std::size_t compact(std::vector<ProxyId>& list, std::uint8_t kind);
  /// Sweep axis by the variance of the box centres of both lists.
  int variance_axis() const;
  /// Gathers `order` (sorted ids) into `list` for sweep axis `axis`.
  void gather(const std::vector<ProxyId>& order, int axis, SweepList& list) const;
  /// Sorts `ids` by box min on `axis` (radix sort).
  void radix_sort_ids(std::vector<ProxyId>& ids, int axis);
  /// Reports every present proxy whose box passes `hit` until `on_overlap` returns false.
  template <class Hit, class OnOverlap>
  BroadPhaseStats scan(const Hit& hit, OnOverlap& on_overlap) const;

  std::vector<Aabb> box_;
  std::vector<ProxyFilter> filter_;
  std::vector<std::uint8_t> state_;   // kAbsent / kMoving / kStatic
  std::vector<std::uint8_t> listed_;  // bit kMoving: in moving_, bit kStatic: in static_
  std::vector<ProxyId> moving_;       // ids, possibly with stale entries until compact()
  std::vector<ProxyId> static_;
  std::size_t count_ = 0;
  bool static_dirty_ = true;      // static list changed since static_list_ was built
  std::size_t moving_added_ = 0;  // moving ids appended since the last sort
  BroadPhaseStats stats_;
  // Scratch of the sorts.
  std::vector<std::uint64_t> keys_;
  std::vector<std::uint64_t> keys_tmp_;
  std::vector<ProxyId> ids_tmp_;
  std::vector<Real> exact_keys_;
  PairSortScratch pair_scratch_;
};

/// Incremental sweep-and-prune ("sap"): insertion sort of the previous frame's order.
class SweepAndPrune : public SweepStorage {
 public:
  /// Re-chooses the sweep axis and re-sorts both lists from scratch.
  void rebuild();
  /// Every pair, sorted. O(n + swaps + overlaps on the sweep axis).
  void find_pairs(std::vector<ProxyPair>& out) { find_pairs(out, serial_executor()); }
  /// As above with the sweep run by `executor`; identical output.
  void find_pairs(std::vector<ProxyPair>& out, Executor& executor);
  /// Current sweep axis (0, 1, 2).
  int axis() const { return axis_; }

 private:
  int axis_ = -1;
  int frames_since_axis_check_ = 0;
  SweepList moving_list_;
  SweepList static_list_;
  std::vector<Real> sort_keys_;
};

/// One-shot sorted sweep ("sap_oneshot"): radix sort from scratch every call.
class SortedSweep : public SweepStorage {
 public:
  /// Nothing to rebuild (every find_pairs sorts from scratch).
  void rebuild() {}
  /// Every pair, sorted. O(n + overlaps on the sweep axis).
  void find_pairs(std::vector<ProxyPair>& out) { find_pairs(out, serial_executor()); }
  /// As above with the sweep run by `executor`; identical output.
  void find_pairs(std::vector<ProxyPair>& out, Executor& executor);

 private:
  int static_axis_ = -1;
  SweepList moving_list_;
  SweepList static_list_;
};

/// Box pruning over a grid of sweeps ("mbp"): G x G cells on the two non-sweep axes.
class MultiBoxPruning : public SweepStorage {
 public:
  /// Nothing to rebuild (the grid is laid over the current bounds every call).
  void rebuild() {}
  /// Every pair, sorted.
  void find_pairs(std::vector<ProxyPair>& out) { find_pairs(out, serial_executor()); }
  /// As above with the sweep run by `executor`; identical output.
  void find_pairs(std::vector<ProxyPair>& out, Executor& executor);

 private:
  std::vector<std::vector<ProxyId>> cell_moving_;
  std::vector<std::vector<ProxyId>> cell_static_;
  std::vector<SweepList> cell_lists_;  // 2 per cell: moving, static
};

// ---- queries (templates on the callback) ------------------------------------------------

template <class Hit, class OnOverlap>
BroadPhaseStats SweepStorage::scan(const Hit& hit, OnOverlap& on_overlap) const {
  BroadPhaseStats st;
  for (std::size_t id = 0; id < state_.size(); ++id) {
    if (state_[id] == kAbsent) continue;
    ++st.pairs_tested;
    if (!hit(box_[id])) continue;
    ++st.pairs_found;
    if (!on_overlap(static_cast<ProxyId>(id))) break;
  }
  return st;
}

template <RayCallback OnRay>
BroadPhaseStats SweepStorage::query_ray(const Ray& ray, Real max_t, OnRay&& on_ray) const {
  BroadPhaseStats st;
  for (std::size_t id = 0; id < state_.size(); ++id) {
    if (state_[id] == kAbsent) continue;
    ++st.pairs_tested;
    const auto hit = geometry::ray_aabb(ray, max_t, box_[id]);
    if (!hit || hit->t > max_t) continue;
    ++st.pairs_found;
    const Real r = on_ray(static_cast<ProxyId>(id), hit->t);
    if (r < Real(0)) continue;
    if (r == Real(0)) break;
    max_t = std::min(max_t, r);
  }
  return st;
}

static_assert(BroadPhaseStructure<SweepAndPrune>);
static_assert(BroadPhaseStructure<SortedSweep>);
static_assert(BroadPhaseStructure<MultiBoxPruning>);

}  // namespace proxima
