#pragma once
/// @file collision_filter.hpp
/// CollisionFilter: which objects of a CollisionWorld may pair. Two objects may pair when
///   - each one's layer bits meet the other's mask (64 bits each), and
///   - they are not in the same non-zero group (a group is a set of objects that never
///     collide with each other: the parts of one ragdoll, a vehicle and its wheels),
/// and the world's per-pair exclusions and its pair callback (collision_world.hpp) allow it.
/// Filters apply alike in the step's broad phase, its continuous detection and the scene
/// queries (a query carries a filter of its own).
#include <proxima/world/object_handle.hpp>

#include <cstdint>

namespace proxima {

/// An object's collision filter (see the file comment). The default collides with everything.
struct CollisionFilter {
  std::uint64_t layer = 1;     ///< the layers this object belongs to
  std::uint64_t mask = ~0ull;  ///< the layers this object collides with
  std::int32_t group = 0;      ///< objects sharing a non-zero group never pair

  /// True when a and b accept each other: layers meet masks both ways, and no shared
  /// non-zero group.
  friend constexpr bool can_collide(const CollisionFilter& a, const CollisionFilter& b) {
    return (a.layer & b.mask) != 0 && (b.layer & a.mask) != 0 && (a.group == 0 || a.group != b.group);
  }
  friend constexpr bool operator==(const CollisionFilter&, const CollisionFilter&) = default;
};

/// A scene query's filter: an object is considered when its layer meets `mask`, it is not
/// in `group` (when non-zero) and it is not `ignore` (a character casting from inside itself).
struct QueryFilter {
  std::uint64_t mask = ~0ull;  ///< the layers the query sees
  std::int32_t group = 0;      ///< objects of this non-zero group are ignored
  ObjectHandle ignore{};       ///< this object is ignored (default: none)

  /// True when the query sees the object `handle` with filter `object`.
  constexpr bool accepts(ObjectHandle handle, const CollisionFilter& object) const {
    return (object.layer & mask) != 0 && (group == 0 || group != object.group) && handle != ignore;
  }
};

}  // namespace proxima
