#pragma once
/// @file object_handle.hpp
/// ObjectHandle: how a CollisionWorld names its objects. A handle is a slot index and the
/// generation of that slot; removing an object bumps its slot's generation, so a handle kept
/// after the removal (a stale handle) no longer matches and every call given it is rejected
/// instead of reaching whatever object reuses the slot. Handles order by index, then
/// generation; the world reports pairs and events in that order.
#include <compare>
#include <cstdint>

namespace proxima {

/// Names one object of one CollisionWorld (see the file comment). A default handle names
/// nothing (index kNoObject).
struct ObjectHandle {
  /// Marks "no object" in `index`.
  static constexpr std::uint32_t kNoObject = 0xffffffffu;

  std::uint32_t index = kNoObject;  ///< slot of the object in its world
  std::uint32_t generation = 0;     ///< generation of the slot when the object was added

  /// False for the default handle (it can never name an object).
  constexpr bool is_set() const { return index != kNoObject; }

  /// The handle as one integer (generation in the high 32 bits, index in the low 32): how the
  /// CLI and snapshots write it.
  constexpr std::uint64_t to_integer() const { return (std::uint64_t(generation) << 32) | index; }
  /// The handle written by to_integer().
  static constexpr ObjectHandle from_integer(std::uint64_t value) {
    return ObjectHandle{static_cast<std::uint32_t>(value & 0xffffffffu), static_cast<std::uint32_t>(value >> 32)};
  }

  friend constexpr bool operator==(const ObjectHandle&, const ObjectHandle&) = default;
  friend constexpr auto operator<=>(const ObjectHandle&, const ObjectHandle&) = default;
};

/// Two objects of a pair, ordered: a < b (by index; two live objects never share an index).
struct ObjectPair {
  ObjectHandle a;  ///< the object with the lower index
  ObjectHandle b;  ///< the object with the higher index

  friend constexpr bool operator==(const ObjectPair&, const ObjectPair&) = default;
  friend constexpr auto operator<=>(const ObjectPair&, const ObjectPair&) = default;
};

}  // namespace proxima
