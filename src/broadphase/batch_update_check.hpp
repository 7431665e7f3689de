#pragma once
/// @file batch_update_check.hpp
/// Internal: the all-or-nothing check of a batch update shared by the trees (kd, BSP,
/// dynamic AABB): every entry is checked before any is applied. Not installed.

#include <proxima/broadphase/broadphase.hpp>

#include <span>

namespace proxima::detail {

/// Status of a batch before it is applied: UnknownId at the first entry whose id `known(id)`
/// rejects, check_box's status at the first entry with a bad box, else Ok. O(updates).
template <class Known>
BroadPhaseStatus check_batch(std::span<const ProxyUpdate> updates, Known known) {
  for (const ProxyUpdate& u : updates) {
    if (!known(u.id)) return BroadPhaseStatus::UnknownId;
    const BroadPhaseStatus s = check_box(u.box);
    if (s != BroadPhaseStatus::Ok) return s;
  }
  return BroadPhaseStatus::Ok;
}

}  // namespace proxima::detail
