#pragma once
/// @file world_state.hpp
/// Internal: the 2D collision world's state (object slots, broad phase, exclusions, the last
/// step's touching pairs and events), shared by collision_world.cpp, world_step.cpp,
/// world_queries.cpp and world_snapshot.cpp.

#include <proxima/broadphase/any_broadphase.hpp>
#include <proxima/d2/collision_world.hpp>

#include <memory>
#include <set>
#include <vector>

namespace proxima::d2 {
namespace detail {

/// One object slot.
struct Slot {
  Shape shape = Circle::create(Real(1)).value();
  Pose pose{};
  Pose previous{};  ///< pose at the last step: the start of this step's motion
  ObjectKind kind = ObjectKind::Moving;
  CollisionFilter filter{};
  bool sensor = false;
  CcdMode ccd = CcdMode::Auto;
  std::uint64_t user_data = 0;
  std::uint32_t generation = 0;
  bool alive = false;
  bool moved = false;         ///< moved since the last step (its proxy needs an update)
  Real min_extent = Real(0);  ///< the thinner side of its local rectangle
  Real reach = Real(0);       ///< largest distance of a point of the shape from its origin
};

/// True for a pose with a finite position within kMaxCoordinate and a unit rotation (1e-3).
bool pose_ok(const Pose& pose);
/// Sets s.min_extent and s.reach from s.shape.
void measure(Slot& s);
/// The broad-phase kind of an object kind.
inline ProxyKind proxy_kind(ObjectKind kind) {
  return kind == ObjectKind::Static ? ProxyKind::Static : ProxyKind::Moving;
}
/// The key of the pair of slots i and j (either order): the smaller index in the high half.
inline std::uint64_t pair_key(std::uint32_t i, std::uint32_t j) {
  return i < j ? (std::uint64_t(i) << 32) | j : (std::uint64_t(j) << 32) | i;
}

/// A rectangle as the broad phase's flat box (z = 0).
inline proxima::Aabb flat_box(const Aabb& box) {
  return {Vec3(box.min.x, box.min.y, Real(0)), Vec3(box.max.x, box.max.y, Real(0))};
}

/// Everything a 2D world holds.
struct WorldState {
  WorldSettings settings;
  std::unique_ptr<AnyBroadPhase> broadphase;
  std::vector<Slot> slots;
  std::vector<std::uint32_t> free_slots;  ///< reused last-freed first (deterministic)
  std::size_t live = 0;
  StepEvents events;
  std::vector<WorldManifold> manifolds;
  std::vector<ContactEvent> touching;  ///< touching non-sensor pairs after the last step, sorted
  std::vector<SensorEvent> sensing;    ///< (sensor, other) pairs after the last step, sorted
  std::set<std::uint64_t> excluded;    ///< pair_key of each excluded pair (sorted: deterministic)
  WorldListener* listener = nullptr;
  bool in_callback = false;

  /// The slot of a live handle, or nullptr.
  const Slot* live_slot(ObjectHandle h) const {
    if (h.index >= slots.size()) return nullptr;
    const Slot& s = slots[h.index];
    return s.alive && s.generation == h.generation ? &s : nullptr;
  }
  /// The broad-phase box of an object at `pose`: its rectangle grown by half the contact
  /// distance, so that two objects within the contact distance are candidates.
  proxima::Aabb proxy_box(const Shape& shape, const Pose& pose) const {
    return flat_box(shape.world_aabb(pose).inflated(Real(0.5) * settings.contact_distance));
  }
  /// True unless the pair of slots i and j is excluded.
  bool allowed(std::uint32_t i, std::uint32_t j) const {
    return excluded.empty() || excluded.count(pair_key(i, j)) == 0;
  }
  /// The handle of a live slot.
  ObjectHandle handle(std::uint32_t index) const { return {index, slots[index].generation}; }
  /// An Error when called from a step's callback.
  std::optional<Error> busy() const {
    if (in_callback) return Error{ErrorCode::InvalidArgument, "", "the world cannot change from a step's callback"};
    return std::nullopt;
  }
};

}  // namespace detail
}  // namespace proxima::d2
