/// @file brute_force.cpp
/// The reference broad phase (see brute_force.hpp for the steps).

#include <proxima/broadphase/brute_force.hpp>

#include <algorithm>

namespace proxima {

namespace {

constexpr std::size_t kBlock = 512;

/// Branch-free overlap of box b against slots [begin, end) of six arrays; one byte per slot.
void overlap_block(const Real* __restrict mnx, const Real* __restrict mny, const Real* __restrict mnz,
                   const Real* __restrict mxx, const Real* __restrict mxy, const Real* __restrict mxz,
                   std::size_t count, Real bmnx, Real bmny, Real bmnz, Real bmxx, Real bmxy, Real bmxz,
                   std::uint8_t* __restrict out) {
  for (std::size_t j = 0; j < count; ++j) {
    const bool hit =
        (mnx[j] <= bmxx) & (bmnx <= mxx[j]) & (mny[j] <= bmxy) & (bmny <= mxy[j]) & (mnz[j] <= bmxz) & (bmnz <= mxz[j]);
    out[j] = static_cast<std::uint8_t>(hit);
  }
}

}  // namespace

void BruteForceBroadPhase::Set::push(ProxyId pid, const Aabb& b, ProxyFilter f) {
  min_x.push_back(b.min.x);
  min_y.push_back(b.min.y);
  min_z.push_back(b.min.z);
  max_x.push_back(b.max.x);
  max_y.push_back(b.max.y);
  max_z.push_back(b.max.z);
  id.push_back(pid);
  layer.push_back(f.layer);
  mask.push_back(f.mask);
}

void BruteForceBroadPhase::Set::set_box(std::size_t slot, const Aabb& b) {
  min_x[slot] = b.min.x;
  min_y[slot] = b.min.y;
  min_z[slot] = b.min.z;
  max_x[slot] = b.max.x;
  max_y[slot] = b.max.y;
  max_z[slot] = b.max.z;
}

ProxyId BruteForceBroadPhase::Set::erase(std::size_t slot) {
  const std::size_t last = id.size() - 1;
  auto move_last = [&](auto& v) {
    v[slot] = v[last];
    v.pop_back();
  };
  move_last(min_x);
  move_last(min_y);
  move_last(min_z);
  move_last(max_x);
  move_last(max_y);
  move_last(max_z);
  move_last(layer);
  move_last(mask);
  move_last(id);
  return slot < id.size() ? id[slot] : ProxyId{0};
}

bool BruteForceBroadPhase::contains(ProxyId id) const { return slot_entry(id) != kNoSlot; }

Aabb BruteForceBroadPhase::get_box(std::uint32_t entry) const {
  return (entry & kStaticBit) ? static_.get_box(entry & ~kStaticBit) : moving_.get_box(entry);
}

void BruteForceBroadPhase::set_box(std::uint32_t entry, const Aabb& b) {
  if (entry & kStaticBit) {
    static_.set_box(entry & ~kStaticBit, b);
  } else {
    moving_.set_box(entry, b);
  }
}

Aabb BruteForceBroadPhase::box(ProxyId id) const { return get_box(slot_entry(id)); }

ProxyKind BruteForceBroadPhase::kind(ProxyId id) const {
  return (slot_entry(id) & kStaticBit) ? ProxyKind::Static : ProxyKind::Moving;
}

ProxyFilter BruteForceBroadPhase::filter(ProxyId id) const {
  const std::uint32_t e = slot_entry(id);
  const Set& s = (e & kStaticBit) ? static_ : moving_;
  const std::size_t slot = e & ~kStaticBit;
  return {s.layer[slot], s.mask[slot]};
}

std::vector<ProxyId> BruteForceBroadPhase::ids() const {
  std::vector<ProxyId> out(moving_.id.begin(), moving_.id.end());
  out.insert(out.end(), static_.id.begin(), static_.id.end());
  std::sort(out.begin(), out.end());
  return out;
}

BroadPhaseStatus BruteForceBroadPhase::insert(ProxyId id, const Aabb& box, ProxyKind kind, ProxyFilter filter) {
  if (const BroadPhaseStatus s = check_box(box); s != BroadPhaseStatus::Ok) return s;
  if (contains(id)) return BroadPhaseStatus::DuplicateId;
  if (id >= slot_of_.size()) slot_of_.resize(std::size_t{id} + 1, kNoSlot);
  if (kind == ProxyKind::Static) {
    slot_of_[id] = static_cast<std::uint32_t>(static_.size()) | kStaticBit;
    static_.push(id, box, filter);
  } else {
    slot_of_[id] = static_cast<std::uint32_t>(moving_.size());
    moving_.push(id, box, filter);
  }
  return BroadPhaseStatus::Ok;
}

BroadPhaseStatus BruteForceBroadPhase::remove(ProxyId id) {
  const std::uint32_t e = slot_entry(id);
  if (e == kNoSlot) return BroadPhaseStatus::UnknownId;
  const bool is_static = (e & kStaticBit) != 0;
  Set& s = is_static ? static_ : moving_;
  const std::uint32_t slot = e & ~kStaticBit;
  const bool had_last = slot + 1 < s.size();
  const ProxyId moved = s.erase(slot);
  if (had_last) slot_of_[moved] = e;
  slot_of_[id] = kNoSlot;
  return BroadPhaseStatus::Ok;
}

BroadPhaseStatus BruteForceBroadPhase::update(ProxyId id, const Aabb& box) {
  if (const BroadPhaseStatus s = check_box(box); s != BroadPhaseStatus::Ok) return s;
  const std::uint32_t e = slot_entry(id);
  if (e == kNoSlot) return BroadPhaseStatus::UnknownId;
  set_box(e, box);
  return BroadPhaseStatus::Ok;
}

BroadPhaseStatus BruteForceBroadPhase::update(std::span<const ProxyUpdate> updates) {
  for (const ProxyUpdate& u : updates) {
    if (const BroadPhaseStatus s = check_box(u.box); s != BroadPhaseStatus::Ok) return s;
    if (!contains(u.id)) return BroadPhaseStatus::UnknownId;
  }
  for (const ProxyUpdate& u : updates) set_box(slot_entry(u.id), u.box);
  return BroadPhaseStatus::Ok;
}

void BruteForceBroadPhase::find_pairs(std::vector<ProxyPair>& out) {
  out.clear();
  stats_ = {};
  hits_.resize(kBlock);
  const std::size_t nm = moving_.size();
  const std::size_t ns = static_.size();
  auto sweep = [&](const Set& other, std::size_t begin, std::size_t end, std::size_t i) {
    const ProxyId id_i = moving_.id[i];
    const std::uint32_t layer_i = moving_.layer[i];
    const std::uint32_t mask_i = moving_.mask[i];
    for (std::size_t b = begin; b < end; b += kBlock) {
      const std::size_t count = std::min(kBlock, end - b);
      overlap_block(other.min_x.data() + b, other.min_y.data() + b, other.min_z.data() + b, other.max_x.data() + b,
                    other.max_y.data() + b, other.max_z.data() + b, count, moving_.min_x[i], moving_.min_y[i],
                    moving_.min_z[i], moving_.max_x[i], moving_.max_y[i], moving_.max_z[i], hits_.data());
      for (std::size_t k = 0; k < count; ++k) {
        if (!hits_[k]) continue;
        const std::size_t j = b + k;
        if ((layer_i & other.mask[j]) == 0 || (other.layer[j] & mask_i) == 0) continue;
        const ProxyId id_j = other.id[j];
        out.push_back(id_i < id_j ? ProxyPair{id_i, id_j} : ProxyPair{id_j, id_i});
      }
    }
    stats_.pairs_tested += end - begin;
  };
  for (std::size_t i = 0; i < nm; ++i) {
    sweep(moving_, i + 1, nm, i);
    sweep(static_, 0, ns, i);
  }
  stats_.nodes_visited = nm;
  sort_pairs(out, sort_scratch_);
  stats_.pairs_found = out.size();
}

bool BruteForceBroadPhase::validate() const {
  std::size_t mapped = 0;
  for (std::size_t id = 0; id < slot_of_.size(); ++id) {
    const std::uint32_t e = slot_of_[id];
    if (e == kNoSlot) continue;
    ++mapped;
    const Set& s = (e & kStaticBit) ? static_ : moving_;
    const std::size_t slot = e & ~kStaticBit;
    if (slot >= s.size() || s.id[slot] != id) return false;
    if (check_box(s.get_box(slot)) != BroadPhaseStatus::Ok) return false;
  }
  if (mapped != size()) return false;
  for (const Set* s : {&moving_, &static_}) {
    const std::size_t n = s->size();
    if (s->min_x.size() != n || s->min_y.size() != n || s->min_z.size() != n || s->max_x.size() != n ||
        s->max_y.size() != n || s->max_z.size() != n || s->layer.size() != n || s->mask.size() != n) {
      return false;
    }
  }
  return true;
}

}  // namespace proxima
