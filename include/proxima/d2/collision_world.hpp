#pragma once
/// @file collision_world.hpp
/// d2::CollisionWorld: the 2D collision world — objects by handle, filters, a step that
/// reports contact manifolds and begin / persist / end, sensor and continuous-impact events
/// (arrays and listener callbacks), and scene queries.
///
/// It shares with the 3D world (world/) everything whose meaning does not depend on the
/// dimension: handles and pairs (ObjectHandle, ObjectPair), kinds and continuous modes
/// (ObjectKind, CcdMode), filters (CollisionFilter, QueryFilter), the settings
/// (WorldSettings; max_contacts is capped at 2 in the plane), contact and sensor events
/// (ContactEvent, SensorEvent), the executor, and the broad-phase structures, which get each
/// object's rectangle as a flat box (z = 0).
///
/// Step (step()):
///   1. the broad phase gets the rectangles of the objects moved since the last step and
///      reports candidate pairs, sorted;
///   2. on the executor, each candidate pair that passes the filters and is not excluded
///      (set_pair_excluded) gets its manifolds
///      (collide_all: one per touching chain segment) or, with a sensor, an overlap test;
///   3. events from the touching pairs of this step and the last (sorted by handles);
///   4. continuous detection: an object moved farther than ccd_safety_factor times its
///      smallest extent is swept (time_of_impact, from its previous pose to its new one)
///      against the objects its swept rectangle meets (Auto: static ones; Bullet: all, each
///      along its own motion); its first impact is reported;
///   5. listener callbacks, in the arrays' order.
/// Every array is sorted by handles, whatever the broad phase or the executor.
///
/// Snapshots (save / load): the whole world as versioned binary data (magic "PROXWR2D"), so
/// that a loaded world, given the same calls, steps with bit-identical events and manifolds;
/// state_hash() is a digest of the same data. The 3D world's snapshots (world/) use the same
/// encoding with their own magic.

#include <proxima/core/executor.hpp>
#include <proxima/d2/contact.hpp>
#include <proxima/d2/shape.hpp>
#include <proxima/world/collision_filter.hpp>
#include <proxima/world/object_desc.hpp>
#include <proxima/world/world_events.hpp>
#include <proxima/world/world_settings.hpp>

#include <iosfwd>
#include <memory>
#include <optional>
#include <span>
#include <vector>

namespace proxima::d2 {

using proxima::CcdMode;
using proxima::CollisionFilter;
using proxima::ContactEvent;
using proxima::ObjectHandle;
using proxima::ObjectKind;
using proxima::ObjectPair;
using proxima::QueryFilter;
using proxima::SensorEvent;
using proxima::WorldSettings;

/// Description of a new 2D object (see CollisionWorld::add).
struct ObjectDesc {
  Shape shape = Circle::create(Real(1)).value();  ///< any 2D shape; a chain only as a Static object
  Pose pose{};                                    ///< local -> world
  ObjectKind kind = ObjectKind::Moving;           ///< static or moving
  CollisionFilter filter{};                       ///< which objects it may pair with
  bool sensor = false;                            ///< reports enter / exit, never contacts
  CcdMode ccd = CcdMode::Auto;                    ///< continuous detection when fast
  std::uint64_t user_data = 0;                    ///< the caller's value, returned in events and queries
};

/// The contact manifold of a touching pair (one per touching chain segment), world frame.
struct WorldManifold {
  ObjectPair pair;    ///< a < b; the normal points from a to b
  Manifold manifold;  ///< points, normal, depths, feature ids, chain segments
};

/// A continuous-detection impact: fast object `a` first comes within the contact distance of
/// `b` at fraction `toi` of the step.
struct ImpactEvent {
  ObjectHandle a;                 ///< the fast object
  ObjectHandle b;                 ///< what it reaches first
  Real toi = Real(0);             ///< fraction of the step in [0, 1]
  Vec2 point{Real(0)};            ///< contact point at toi, world frame
  Vec2 normal{Real(1), Real(0)};  ///< unit, from a to b
  PartIndex part_b = -1;          ///< chain segment of b (-1: convex)
  std::uint64_t user_data_a = 0;  ///< user data of a
  std::uint64_t user_data_b = 0;  ///< user data of b
};

/// Every event of one step, each array sorted by handles.
struct StepEvents {
  std::vector<ContactEvent> begin;        ///< pairs that began touching
  std::vector<ContactEvent> persist;      ///< pairs that touched before and still do
  std::vector<ContactEvent> end;          ///< pairs that stopped touching (or were removed)
  std::vector<SensorEvent> sensor_enter;  ///< objects that entered a sensor
  std::vector<SensorEvent> sensor_exit;   ///< objects that left a sensor
  std::vector<ImpactEvent> impacts;       ///< first impacts of fast objects
};

class CollisionWorld;
namespace detail {
struct WorldState;
}

/// Callbacks of a step, called after it in the order of StepEvents' arrays. The world may
/// be read but not changed from a callback (changes are refused with an Error).
class WorldListener {
 public:
  /// A listener is destroyed through this base.
  virtual ~WorldListener() = default;
  /// A pair began touching.
  virtual void on_contact_begin(const CollisionWorld& world, const ContactEvent& event) { (void)world, (void)event; }
  /// A pair touches again.
  virtual void on_contact_persist(const CollisionWorld& world, const ContactEvent& event) { (void)world, (void)event; }
  /// A pair stopped touching.
  virtual void on_contact_end(const CollisionWorld& world, const ContactEvent& event) { (void)world, (void)event; }
  /// An object entered a sensor.
  virtual void on_sensor_enter(const CollisionWorld& world, const SensorEvent& event) { (void)world, (void)event; }
  /// An object left a sensor.
  virtual void on_sensor_exit(const CollisionWorld& world, const SensorEvent& event) { (void)world, (void)event; }
  /// A fast object's first impact.
  virtual void on_impact(const CollisionWorld& world, const ImpactEvent& event) { (void)world, (void)event; }
};

/// A ray query's answer: the object hit first and the hit.
struct WorldRayHit {
  ObjectHandle object;  ///< the object hit
  RayHit hit;           ///< parameter, point, normal, chain segment
};

/// The 2D collision world (see the file comment).
class CollisionWorld {
 public:
  /// A world with these settings; errors name "settings.<field>" (validate_world_settings)
  /// or "settings.broadphase" (no such structure).
  static Result<CollisionWorld> create(const WorldSettings& settings = {});
  /// Worlds move (their objects and handles with them); they are not copied.
  CollisionWorld(CollisionWorld&&) noexcept;
  /// Move assignment (the moved-from world may only be destroyed or assigned).
  CollisionWorld& operator=(CollisionWorld&&) noexcept;
  /// Releases the world.
  ~CollisionWorld();

  /// Adds an object; its handle, or an Error naming the field ("desc.pose" not finite,
  /// "desc.kind": a chain must be Static). O(log n) in the broad phase.
  Result<ObjectHandle> add(const ObjectDesc& desc);
  /// Removes an object (its touching pairs end at the next step). Error: "handle" stale.
  std::optional<Error> remove(ObjectHandle handle);
  /// Moves an object; the next step sweeps it from its previous pose to this one. Errors:
  /// "handle", "pose".
  std::optional<Error> move(ObjectHandle handle, const Pose& pose);
  /// Places an object with no motion: the next step does not sweep it.
  std::optional<Error> teleport(ObjectHandle handle, const Pose& pose);
  /// Changes an object's filter (pairs it no longer allows end at the next step).
  std::optional<Error> set_filter(ObjectHandle handle, const CollisionFilter& filter);
  /// Excludes the pair (a, b) from pairing (contacts, sensing and continuous detection), or
  /// allows it again; an excluded pair that touched ends at the next step. Removing either
  /// object forgets the exclusion. Errors: "a", "b" (stale handles, or a == b).
  std::optional<Error> set_pair_excluded(ObjectHandle a, ObjectHandle b, bool excluded);
  /// True when the handle names a live object of this world.
  bool contains(ObjectHandle handle) const;
  /// The pose of a live object (nothing for a stale handle).
  std::optional<Pose> pose(ObjectHandle handle) const;
  /// The number of live objects.
  std::size_t size() const;
  /// The handles of the live objects, by slot index (the order of the snapshot).
  std::vector<ObjectHandle> objects() const;
  /// What a live object is now (its shape, current pose, kind, filter, sensor flag,
  /// continuous mode and user data); nothing for a stale handle.
  std::optional<ObjectDesc> object(ObjectHandle handle) const;

  /// Runs a step (see the file comment) on `executor`. Error: called from a callback.
  std::optional<Error> step(Executor& executor = serial_executor());
  /// The events of the last step.
  const StepEvents& events() const;
  /// The manifolds of the pairs touching after the last step, sorted by pair then part.
  std::span<const WorldManifold> manifolds() const;
  /// Sets (or clears, with nullptr) the listener called after each step.
  void set_listener(WorldListener* listener);

  /// The first object hit by `ray` within [0, max_t] that `filter` accepts.
  std::optional<WorldRayHit> raycast(const Ray& ray, Real max_t, const QueryFilter& filter = {}) const;
  /// Appends to `out` the objects `filter` accepts that overlap `shape` at `pose` (sorted by
  /// handle); returns how many.
  int overlap(const Shape& shape, const Pose& pose, const QueryFilter& filter, std::vector<ObjectHandle>& out) const;

  /// Writes the whole world to `out` as a versioned binary snapshot: the settings, every
  /// slot (generation; for a live object its shape of any kind, pose and pose at the last
  /// step (world frame), filter, kind, sensor flag, continuous mode, user data, whether it
  /// moved since), the free list, the exclusions, the pairs touching and sensing after the
  /// last step, its manifolds and its events. The listener is the caller's and is not
  /// written. Error: "out" when the stream fails.
  std::optional<Error> save(std::ostream& out) const;
  /// A world read from a snapshot written by save(): the same state_hash(), and the same
  /// calls then give bit-identical events and manifolds. Everything is checked; an Error
  /// names what is wrong ("snapshot": not a 2D world snapshot, another version, truncated or
  /// inconsistent data; "snapshot.objects[3].shape": a shape that does not validate;
  /// "snapshot.settings.<field>"), never a crash.
  static Result<CollisionWorld> load(std::istream& in);
  /// A 64-bit digest of everything save() writes: equal hashes mean equal worlds.
  std::uint64_t state_hash() const;

 private:
  explicit CollisionWorld(std::unique_ptr<detail::WorldState> state);
  std::unique_ptr<detail::WorldState> state_;
};

}  // namespace proxima::d2
