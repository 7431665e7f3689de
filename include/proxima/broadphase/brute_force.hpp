#pragma once
/// @file brute_force.hpp
/// BruteForceBroadPhase: the reference structure every other one is tested against.
///
/// Steps of find_pairs:
/// 1. Proxies live in two structure-of-arrays sets, moving and static (six float/double
///    arrays of bounds each), so static-static pairs are never looked at.
/// 2. For each moving proxy i, the overlap test against moving proxies j > i and against
///    every static proxy runs as a branch-free loop over a block of the arrays, writing a
///    0/1 byte per candidate (the compiler vectorises it); the hits are then checked
///    against the layer/mask filter and emitted as (lo, hi).
/// 3. The pairs are radix-sorted (sort_pairs).
/// O(n_moving * n) per find_pairs; O(1) insert, remove (swap with last) and update.
/// Closed boxes: touching counts (Ericson, Real-Time Collision Detection, 4.2.1).

#include <proxima/broadphase/broadphase.hpp>
#include <proxima/broadphase/pair_tracker.hpp>
#include <proxima/geometry/raycast.hpp>

#include <algorithm>
#include <cstdint>
#include <span>
#include <vector>

namespace proxima {

/// The O(n^2) reference broad phase (see the file comment). Satisfies BroadPhaseStructure.
class BruteForceBroadPhase {
 public:
  /// Adds a proxy. Rejects bad boxes (check_box) and ids already present.
  BroadPhaseStatus insert(ProxyId id, const Aabb& box, ProxyKind kind, ProxyFilter filter = {});
  /// Removes a proxy.
  BroadPhaseStatus remove(ProxyId id);
  /// Replaces the box of a proxy (moving or static).
  BroadPhaseStatus update(ProxyId id, const Aabb& box);
  /// Replaces several boxes; all or nothing (any bad entry: nothing changes). Entries are
  /// applied in order, so a repeated id ends with its last box.
  BroadPhaseStatus update(std::span<const ProxyUpdate> updates);
  /// Nothing to rebuild (kept for the concept).
  void rebuild() {}
  /// Every pair, sorted by (lo, hi). O(n_moving * n).
  void find_pairs(std::vector<ProxyPair>& out);
  /// Calls `on_overlap` for every proxy whose box overlaps or touches `box`; returns the
  /// query's counters.
  template <OverlapCallback OnOverlap>
  BroadPhaseStats query_aabb(const Aabb& box, OnOverlap&& on_overlap) const;
  /// Calls `on_overlap` for every proxy whose box contains `point` (boundary included).
  template <OverlapCallback OnOverlap>
  BroadPhaseStats query_point(const Vec3& point, OnOverlap&& on_overlap) const;
  /// Calls `on_ray(id, t)` for every proxy whose box the ray hits at t <= the current max
  /// fraction (t from geometry::ray_aabb; 0 when the origin is inside), in slot order.
  template <RayCallback OnRay>
  BroadPhaseStats query_ray(const Ray& ray, Real max_t, OnRay&& on_ray) const;
  /// Checks the id table against the arrays and every stored box.
  bool validate() const;
  /// Counters of the last find_pairs.
  BroadPhaseStats stats() const { return stats_; }
  /// Number of proxies.
  std::size_t size() const { return moving_.size() + static_.size(); }

  /// True when a proxy with this id exists.
  bool contains(ProxyId id) const;
  /// The stored box of a proxy (the proxy must exist).
  Aabb box(ProxyId id) const;
  /// Kind of a proxy (the proxy must exist).
  ProxyKind kind(ProxyId id) const;
  /// Filter of a proxy (the proxy must exist).
  ProxyFilter filter(ProxyId id) const;
  /// Ids of every proxy, ascending.
  std::vector<ProxyId> ids() const;

 private:
  /// One set of proxies in structure-of-arrays form.
  struct Set {
    std::vector<Real> min_x, min_y, min_z, max_x, max_y, max_z;
    std::vector<ProxyId> id;
    std::vector<std::uint32_t> layer, mask;
    std::size_t size() const { return id.size(); }
    void push(ProxyId pid, const Aabb& b, ProxyFilter f);
    void set_box(std::size_t slot, const Aabb& b);
    Aabb get_box(std::size_t slot) const {
      return {Vec3(min_x[slot], min_y[slot], min_z[slot]), Vec3(max_x[slot], max_y[slot], max_z[slot])};
    }
    /// Removes a slot by moving the last one into it; returns the id moved (or the removed).
    ProxyId erase(std::size_t slot);
  };
  static constexpr std::uint32_t kNoSlot = 0xffffffffu;
  static constexpr std::uint32_t kStaticBit = 0x80000000u;

  std::uint32_t slot_entry(ProxyId id) const { return id < slot_of_.size() ? slot_of_[id] : kNoSlot; }
  void set_box(std::uint32_t entry, const Aabb& b);
  Aabb get_box(std::uint32_t entry) const;
  template <class Visit>
  void for_each_box(Visit&& visit) const;

  Set moving_;
  Set static_;
  std::vector<std::uint32_t> slot_of_;  // id -> slot | kStaticBit, or kNoSlot
  std::vector<std::uint8_t> hits_;      // scratch of find_pairs
  PairSortScratch sort_scratch_;
  BroadPhaseStats stats_;
};

static_assert(BroadPhaseStructure<BruteForceBroadPhase>);

// ---- queries (templates on the callback) ------------------------------------------------

template <class Visit>
void BruteForceBroadPhase::for_each_box(Visit&& visit) const {
  for (const Set* s : {&moving_, &static_}) {
    for (std::size_t i = 0; i < s->size(); ++i) {
      if (!visit(s->id[i], s->get_box(i))) return;
    }
  }
}

template <OverlapCallback OnOverlap>
BroadPhaseStats BruteForceBroadPhase::query_aabb(const Aabb& box, OnOverlap&& on_overlap) const {
  BroadPhaseStats st;
  for_each_box([&](ProxyId id, const Aabb& b) {
    ++st.pairs_tested;
    if (!b.overlaps(box)) return true;
    ++st.pairs_found;
    return static_cast<bool>(on_overlap(id));
  });
  return st;
}

template <OverlapCallback OnOverlap>
BroadPhaseStats BruteForceBroadPhase::query_point(const Vec3& point, OnOverlap&& on_overlap) const {
  BroadPhaseStats st;
  for_each_box([&](ProxyId id, const Aabb& b) {
    ++st.pairs_tested;
    if (!b.contains(point)) return true;
    ++st.pairs_found;
    return static_cast<bool>(on_overlap(id));
  });
  return st;
}

template <RayCallback OnRay>
BroadPhaseStats BruteForceBroadPhase::query_ray(const Ray& ray, Real max_t, OnRay&& on_ray) const {
  BroadPhaseStats st;
  for_each_box([&](ProxyId id, const Aabb& b) {
    ++st.pairs_tested;
    const auto hit = geometry::ray_aabb(ray, max_t, b);
    if (!hit || hit->t > max_t) return true;
    ++st.pairs_found;
    const Real r = on_ray(id, hit->t);
    if (r < Real(0)) return true;
    if (r == Real(0)) return false;
    max_t = std::min(max_t, r);
    return true;
  });
  return st;
}

}  // namespace proxima
