#pragma once
/// @file proxy_table.hpp
/// ProxyTable: the id-indexed store of proxies (box, kind, filter) shared by the grid, hash,
/// hierarchical grid and loose octree structures, with the input checks of broadphase.hpp
/// (a rejected call changes nothing), and small helpers they share: the pair acceptance
/// test, the ray-box entry test, and a radix sort of pairs.

#include <proxima/broadphase/broadphase.hpp>

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace proxima::detail {

/// One stored proxy.
struct ProxyRecord {
  Aabb box;                            ///< world box (closed)
  ProxyFilter filter;                  ///< layer / mask
  ProxyKind kind = ProxyKind::Moving;  ///< Static or Moving
  std::uint32_t dense = kNoSlot;       ///< index into ProxyTable::ids(), kNoSlot when absent
  static constexpr std::uint32_t kNoSlot = 0xffffffffu;
};

/// True when two proxies may form a pair regardless of their boxes: at least one Moving and
/// filters accepting each other. O(1).
inline bool may_pair(const ProxyRecord& a, const ProxyRecord& b) {
  return (a.kind == ProxyKind::Moving || b.kind == ProxyKind::Moving) && can_pair(a.filter, b.filter);
}

/// Id-indexed proxy store: O(1) insert, remove (swap with the last dense entry) and update.
/// Memory O(largest id + count).
class ProxyTable {
 public:
  /// Adds a proxy after checking the box and the id.
  BroadPhaseStatus insert(ProxyId id, const Aabb& box, ProxyKind kind, ProxyFilter filter);
  /// Removes a proxy.
  BroadPhaseStatus remove(ProxyId id);
  /// Checks an update without applying it.
  BroadPhaseStatus check_update(ProxyId id, const Aabb& box) const;
  /// Checks a whole batch (all or nothing) without applying it.
  BroadPhaseStatus check_updates(std::span<const ProxyUpdate> updates) const;
  /// True when `id` is present.
  bool contains(ProxyId id) const { return id < records_.size() && records_[id].dense != ProxyRecord::kNoSlot; }
  /// The record of a present id.
  const ProxyRecord& operator[](ProxyId id) const { return records_[id]; }
  /// The record of a present id.
  ProxyRecord& operator[](ProxyId id) { return records_[id]; }
  /// Present ids in dense order (changes on remove).
  std::span<const ProxyId> ids() const { return ids_; }
  /// Number of proxies.
  std::size_t size() const { return ids_.size(); }
  /// Checks the internal links (dense index <-> id). O(n).
  bool validate() const;

 private:
  std::vector<ProxyRecord> records_;  // indexed by id
  std::vector<ProxyId> ids_;          // dense list of present ids
};

/// Entry fraction of the ray origin + t direction, t in [0, max_t], into the closed box:
/// true and `t` set when it hits (t = 0 when the origin is inside); the same t as
/// geometry::ray_aabb, which it calls. O(1).
bool ray_enters_box(const Ray& ray, Real max_t, const Aabb& box, Real& t);

/// Sorts pairs by (lo, hi) with an LSD radix sort on the 64-bit key (lo << 32 | hi), using
/// `scratch` as buffer; O(n) passes skipped when a digit is constant.
void sort_pairs_radix(std::vector<ProxyPair>& pairs, std::vector<ProxyPair>& scratch);

}  // namespace proxima::detail
