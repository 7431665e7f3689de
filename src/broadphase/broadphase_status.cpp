/// @file broadphase_status.cpp
/// Status names and the box check shared by every broad-phase structure.

#include <proxima/broadphase/broadphase.hpp>
#include <proxima/core/tolerance.hpp>

#include <cmath>

namespace proxima {

const char* to_string(BroadPhaseStatus status) {
  switch (status) {
    case BroadPhaseStatus::Ok: return "ok";
    case BroadPhaseStatus::NotFinite: return "not_finite";
    case BroadPhaseStatus::InvalidBox: return "invalid_box";
    case BroadPhaseStatus::UnknownId: return "unknown_id";
    case BroadPhaseStatus::DuplicateId: return "duplicate_id";
  }
  return "unknown";
}

BroadPhaseStatus check_box(const Aabb& box) {
  for (int axis = 0; axis < 3; ++axis) {
    if (!std::isfinite(box.min[axis]) || !std::isfinite(box.max[axis])) return BroadPhaseStatus::NotFinite;
  }
  for (int axis = 0; axis < 3; ++axis) {
    if (box.min[axis] > box.max[axis]) return BroadPhaseStatus::InvalidBox;
    if (std::abs(box.min[axis]) > kMaxCoordinate || std::abs(box.max[axis]) > kMaxCoordinate) {
      return BroadPhaseStatus::InvalidBox;
    }
  }
  return BroadPhaseStatus::Ok;
}

}  // namespace proxima
