/// @file proxy_table.cpp
/// The id-indexed proxy store and helpers shared by the cell-based structures and the loose
/// octree (see proxy_table.hpp).

#include <proxima/broadphase/proxy_table.hpp>
#include <proxima/geometry/raycast.hpp>

#include <algorithm>
#include <array>
#include <cstring>
#include <optional>

namespace proxima::detail {

BroadPhaseStatus ProxyTable::insert(ProxyId id, const Aabb& box, ProxyKind kind, ProxyFilter filter) {
  const BroadPhaseStatus status = check_box(box);
  if (status != BroadPhaseStatus::Ok) return status;
  if (contains(id)) return BroadPhaseStatus::DuplicateId;
  if (id >= records_.size()) records_.resize(std::size_t(id) + 1);
  ProxyRecord& r = records_[id];
  r.box = box;
  r.kind = kind;
  r.filter = filter;
  r.dense = static_cast<std::uint32_t>(ids_.size());
  ids_.push_back(id);
  return BroadPhaseStatus::Ok;
}

BroadPhaseStatus ProxyTable::remove(ProxyId id) {
  if (!contains(id)) return BroadPhaseStatus::UnknownId;
  const std::uint32_t slot = records_[id].dense;
  const ProxyId last = ids_.back();
  ids_[slot] = last;
  records_[last].dense = slot;
  ids_.pop_back();
  records_[id].dense = ProxyRecord::kNoSlot;
  return BroadPhaseStatus::Ok;
}

BroadPhaseStatus ProxyTable::check_update(ProxyId id, const Aabb& box) const {
  const BroadPhaseStatus status = check_box(box);
  if (status != BroadPhaseStatus::Ok) return status;
  if (!contains(id)) return BroadPhaseStatus::UnknownId;
  return BroadPhaseStatus::Ok;
}

BroadPhaseStatus ProxyTable::check_updates(std::span<const ProxyUpdate> updates) const {
  for (const ProxyUpdate& u : updates) {
    const BroadPhaseStatus status = check_update(u.id, u.box);
    if (status != BroadPhaseStatus::Ok) return status;
  }
  return BroadPhaseStatus::Ok;
}

bool ProxyTable::validate() const {
  for (std::size_t i = 0; i < ids_.size(); ++i) {
    const ProxyId id = ids_[i];
    if (id >= records_.size() || records_[id].dense != i) return false;
    if (check_box(records_[id].box) != BroadPhaseStatus::Ok) return false;
  }
  std::size_t present = 0;
  for (const ProxyRecord& r : records_) present += r.dense != ProxyRecord::kNoSlot ? 1 : 0;
  return present == ids_.size();
}

bool ray_enters_box(const Ray& ray, Real max_t, const Aabb& box, Real& t) {
  const std::optional<RayHit> hit = geometry::ray_aabb(ray, max_t, box);
  if (!hit) return false;
  t = hit->t;
  return true;
}

void sort_pairs_radix(std::vector<ProxyPair>& pairs, std::vector<ProxyPair>& scratch) {
  const std::size_t n = pairs.size();
  if (n < 256) {
    std::sort(pairs.begin(), pairs.end());
    return;
  }
  scratch.resize(n);
  auto key = [](const ProxyPair& p) { return (std::uint64_t(p.lo) << 32) | p.hi; };
  std::uint64_t all_or = 0;
  std::uint64_t all_and = ~std::uint64_t(0);
  for (const ProxyPair& p : pairs) {
    all_or |= key(p);
    all_and &= key(p);
  }
  const std::uint64_t varying = all_or ^ all_and;
  ProxyPair* src = pairs.data();
  ProxyPair* dst = scratch.data();
  std::array<std::size_t, 2048> count{};
  for (int shift = 0; shift < 64; shift += 11) {
    if (((varying >> shift) & 0x7ffu) == 0) continue;
    count.fill(0);
    for (std::size_t i = 0; i < n; ++i) ++count[(key(src[i]) >> shift) & 0x7ffu];
    std::size_t sum = 0;
    for (std::size_t& c : count) {
      const std::size_t v = c;
      c = sum;
      sum += v;
    }
    for (std::size_t i = 0; i < n; ++i) dst[count[(key(src[i]) >> shift) & 0x7ffu]++] = src[i];
    std::swap(src, dst);
  }
  if (src != pairs.data()) std::memcpy(pairs.data(), src, n * sizeof(ProxyPair));
}

}  // namespace proxima::detail
