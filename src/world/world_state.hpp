#pragma once
// Internal: the state behind CollisionWorld (collision_world.hpp) and the helpers its
// translation units share: object slots, attachment trees, the pair table of the step, and
// the filters.
//
// Layout: one slot per object index (a free list reuses slots, last freed first); one
// broad-phase proxy per attachment tree, named by the root's index, whose box covers the
// tree; one PairState per candidate pair of the last step, sorted by (lo, hi) index, holding
// the pair's narrow-phase cache and the index of its manifold in `contacts` when touching.
#include <proxima/broadphase/any_broadphase.hpp>
#include <proxima/narrowphase/contact.hpp>
#include <proxima/world/collision_world.hpp>

#include <cstdint>
#include <memory>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "world/access_check.hpp"

namespace proxima {

/// A slot index naming no object: no parent, no first child, no next sibling.
inline constexpr std::uint32_t kNoSlot = ObjectHandle::kNoObject;

/// One object (or a free slot: alive false).
struct ObjectSlot {
  Shape geometry = *Point::create();
  Transform pose;       ///< world pose now
  Transform step_pose;  ///< world pose at the last step: the start of the next step's motion
  Aabb box;             ///< world box of the geometry at `pose`, padded by half the contact distance
  CollisionFilter filter;
  std::uint64_t user_data = 0;
  std::uint32_t generation = 0;
  std::uint32_t parent = ObjectHandle::kNoObject;
  std::uint32_t first_child = ObjectHandle::kNoObject;
  std::uint32_t next_sibling = ObjectHandle::kNoObject;
  std::uint32_t root = ObjectHandle::kNoObject;  ///< root of its attachment tree (itself when not attached)
  std::uint32_t exclusions = 0;                  ///< number of excluded pairs naming it
  Real radius = Real(0);                         ///< farthest point of the geometry from its origin
  Real min_extent = Real(0);                     ///< thinnest side of its local box
  ObjectKind kind = ObjectKind::Moving;          ///< the kind of its tree's root
  CcdMode ccd = CcdMode::Auto;
  bool sensor = false;
  bool alive = false;
  bool moved = false;             ///< moved since the last step (in Impl::moved)
  bool geometry_changed = false;  ///< geometry replaced since the last step: its pairs' caches are reset

  ObjectHandle handle(std::uint32_t index) const { return {index, generation}; }
};

/// A candidate pair of the last step (objects lo < hi by index).
struct PairState {
  std::uint32_t lo = 0, hi = 0;            ///< object indices
  std::uint32_t gen_lo = 0, gen_hi = 0;    ///< their generations
  std::uint64_t user_lo = 0, user_hi = 0;  ///< their user data (for end events after removal)
  PairCache cache;                         ///< narrow-phase warm start, A = lo
  std::int32_t contact = -1;               ///< index of its manifold in Impl::contacts, -1: not touching
  std::uint32_t next_point_id = 0;         ///< next id for a new manifold point
  std::uint8_t sensor = 0;                 ///< bit 0: lo is a sensor, bit 1: hi is (non-zero: overlap only)
  bool touching = false;                   ///< touching (sensors: overlapping) after the step
  bool was_touching = false;               ///< touching before the step (valid during a step)

  std::uint64_t key() const { return (std::uint64_t(lo) << 32) | hi; }
  ObjectPair pair() const { return {{lo, gen_lo}, {hi, gen_hi}}; }
};

/// One block of the continuous pass (world_ccd.cpp): the scratch of its sweeps and its
/// events, merged in block order after the parallel sweeps. Kept across steps.
struct CcdChunk {
  std::vector<std::uint32_t> roots;        ///< proxies met by one swept box
  std::vector<std::uint32_t> candidates;   ///< objects one fast object may reach
  std::vector<ImpactEvent> impacts;        ///< the block's first impacts, by object
  std::vector<SensorEvent> sensor_events;  ///< the sensors crossed: enter and exit alike
};

/// Key of an unordered index pair (lo in the high half).
inline std::uint64_t pair_key(std::uint32_t a, std::uint32_t b) {
  return a < b ? (std::uint64_t(a) << 32) | b : (std::uint64_t(b) << 32) | a;
}

struct CollisionWorld::Impl {
  WorldSettings settings;
  std::unique_ptr<AnyBroadPhase> broadphase;
  std::vector<ObjectSlot> slots;
  std::vector<std::uint32_t> free_slots;  ///< reused last freed first
  std::size_t live = 0;
  std::unordered_map<std::uint32_t, Transform> local_poses;  ///< attached objects' poses in their parent's frame
  std::unordered_set<std::uint64_t> excluded;                ///< pair_key of excluded pairs
  std::unordered_map<std::uint32_t, WorldListener*> object_listeners;
  WorldListener* listener = nullptr;
  PairFilterCallback* pair_filter = nullptr;
  std::vector<std::uint32_t> moved;  ///< objects moved since the last step (slot.moved set)

  std::vector<PairState> pairs;         ///< candidate pairs of the last step, sorted by key
  std::vector<WorldManifold> contacts;  ///< touching pairs' manifolds, sorted by pair
  StepEvents events;
  std::uint64_t steps = 0;
  bool in_callback = false;     ///< true while step() runs callbacks (a nested step is refused)
  bool in_pre_contact = false;  ///< true during on_pre_contact (changes are refused)
  detail::AccessCheck access;   ///< debug checks of the thread-safety rules (access_check.hpp)

  // scratch of the step, kept so that a step allocates nothing once warmed up
  std::vector<ProxyPair> proxy_pairs;        ///< the broad phase's pairs of trees
  std::vector<ProxyPair> candidates;         ///< filtered object pairs
  std::vector<PairState> next_pairs;         ///< the pair table being built (swapped with pairs)
  std::vector<ContactManifold> manifolds;    ///< the narrow phase's answer per candidate
  std::vector<std::uint8_t> overlaps;        ///< the narrow phase's answer per sensor candidate
  std::vector<WorldManifold> next_contacts;  ///< the manifolds being built (swapped with contacts)
  std::vector<Aabb> move_boxes;              ///< move(span): the new box of each entry (unattached objects)
  std::vector<std::uint32_t> move_roots;     ///< move(span): the moved trees' roots
  std::vector<ProxyUpdate> move_updates;     ///< move(span): their proxies' new boxes
  std::vector<std::uint32_t> fast;           ///< continuous pass: the fast objects, by index
  std::vector<CcdChunk> ccd_chunks;          ///< continuous pass: one per block of fast objects

  // ---- helpers shared by the translation units ----

  /// The slot of a live handle, or nullptr.
  ObjectSlot* find(ObjectHandle h) {
    return h.index < slots.size() && slots[h.index].alive && slots[h.index].generation == h.generation ? &slots[h.index]
                                                                                                       : nullptr;
  }
  const ObjectSlot* find(ObjectHandle h) const { return const_cast<Impl*>(this)->find(h); }

  /// True when objects i and j may pair: different trees, filters, exclusions, sensors, the
  /// pair callback (`world` is passed to it).
  bool may_pair(const CollisionWorld& world, std::uint32_t i, std::uint32_t j) const;
  /// Recomputes the world box of object i from its pose.
  void refresh_box(std::uint32_t i);
  /// Box covering the tree rooted at r, and the folded filter of its members.
  Aabb tree_box(std::uint32_t r) const;
  /// The broad-phase filter of the tree rooted at r: its members' layers and masks folded
  /// to 32 bits (a superset test: two 64-bit filters that accept each other give folded
  /// filters that do too).
  ProxyFilter tree_filter(std::uint32_t r) const;
  /// Calls f(index) for every member of the tree rooted at r, root first, depth first.
  template <class F>
  void for_each_member(std::uint32_t r, F&& f) const {
    std::uint32_t i = r;
    while (true) {
      f(i);
      if (slots[i].first_child != ObjectHandle::kNoObject) {
        i = slots[i].first_child;
        continue;
      }
      while (i != r && slots[i].next_sibling == ObjectHandle::kNoObject) i = slots[i].parent;
      if (i == r) return;
      i = slots[i].next_sibling;
    }
  }
  /// Updates the box of the broad-phase proxy of the tree rooted at r.
  void refresh_proxy(std::uint32_t r);
  /// Removes (when present) and inserts the proxy of the tree rooted at r: box, kind and filter.
  void reinsert_proxy(std::uint32_t r);
  /// Marks object i as moved since the last step.
  void mark_moved(std::uint32_t i) {
    if (!slots[i].moved) {
      slots[i].moved = true;
      moved.push_back(i);
    }
  }
  /// Sets the world pose of i's children from i's pose, recursively (transforms down), and
  /// refreshes their boxes.
  void propagate_pose(std::uint32_t i);
};

/// Writes vectors and poses as their reals in the one order the state hash and the snapshot
/// share (x, y, z; the position, then the rotation's w, x, y, z) through the derived sink's
/// real(Real) (CRTP).
template <class Sink>
struct RealSequence {
  void vec(const Vec3& v) {
    Sink& sink = static_cast<Sink&>(*this);
    sink.real(v.x);
    sink.real(v.y);
    sink.real(v.z);
  }
  void pose(const Transform& t) {
    vec(t.position);
    Sink& sink = static_cast<Sink&>(*this);
    sink.real(t.rotation.w);
    sink.real(t.rotation.x);
    sink.real(t.rotation.y);
    sink.real(t.rotation.z);
  }
};

/// An Error naming `field`.position or `field`.rotation when the pose is not finite within
/// kMaxCoordinate or its rotation not unit; nothing otherwise.
std::optional<Error> check_pose(const Transform& pose, const std::string& field);

/// Sets s.radius and s.min_extent from s.geometry (0 for unbounded geometry).
void measure_geometry(ObjectSlot& s);

/// The box padded by `pad` on every side and clamped to ±kMaxCoordinate (a half-space's
/// unbounded sides), as the broad phase accepts it.
Aabb proxy_box(const Aabb& box, Real pad);

/// How far a query box grows so that the broad phase (closed boxes) does not drop an object
/// that the narrow phase's touching rule counts (gap within the pair's tolerance): twice
/// linear_tolerance of the box's largest bounded coordinate (length units). Object boxes are
/// not grown (they are the public bounds).
Real touching_pad(const Aabb& box);

}  // namespace proxima
