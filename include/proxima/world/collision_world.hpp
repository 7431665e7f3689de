#pragma once
/// @file collision_world.hpp
/// CollisionWorld: the collision module's own state (only collision geometry, no dynamics),
/// one step that finds every contact and reports it through event arrays and callbacks,
/// continuous detection for fast objects, and scene queries over all objects.
///
/// A frame of a game loop:
///   world.move(handle, pose) for every object that moved (or move(batch));
///   world.step(dt);                     // broad phase, narrow phase, events, callbacks
///   read world.events() and world.contacts(), or react in the listeners.
///
/// Objects (object_desc.hpp) are named by handles (object_handle.hpp); a stale or foreign
/// handle is rejected. Every changing call validates its arguments and either applies
/// completely or returns an Error naming the argument and changes nothing (state_hash()
/// proves it in the tests). add / remove / move / set_* cost O(log n) (one broad-phase
/// update), plus the object's attached subtree for move.
///
/// The step (step(), world_step.cpp):
///   1. broad phase: the structure's pairs of boxes (one proxy per attachment tree: a whole
///      tree is rejected by one box), expanded to object pairs and filtered (layers, groups,
///      exclusions, the pair callback); objects of one attachment tree never pair;
///   2. narrow phase on each candidate pair (on the executor): a contact manifold within the
///      contact distance, warm-started from the pair's cache of the last step; sensors test
///      overlap only;
///   3. persistent manifolds: points matched to the previous step's by feature id and parts,
///      keeping their ids and user slots; on_pre_contact may edit or veto each pair;
///   4. events: begin / persist / end and sensor enter / exit from the touching pairs of this
///      step and the previous one (an ended pair is reported whatever the reason: separation,
///      filter, kind or geometry change, removal);
///   5. continuous detection: each fast object (CcdMode Auto or Bullet) is swept from its
///      pose at the previous step to its pose now against the objects its swept box meets
///      (static ones; also moving ones for Bullet, with their motions), by the certified time
///      of impact; the first impact is reported, and a sensor it crosses reports enter and
///      exit even when neither pose overlaps it;
///   6. callbacks, in event order (world_listener.hpp).
/// Poses given by move() between two steps are the motion of the next step: the object
/// moves from its pose at the last step to the last pose given (linearly, and rotating about
/// one axis: ccd/motion.hpp).
///
/// Determinism: the same calls in the same order give bit-identical events, contacts and
/// state hashes, whatever the executor and its thread count (the step's parallel parts
/// write per-item or per-block results merged in item order), and in every build of one
/// precision (the library is compiled without fused multiply-add contraction).
///
/// Thread safety:
///   - const members (queries, the batches, state_hash, save, the accessors) may run at the
///     same time as each other, from any number of threads;
///   - a changing call (add, remove, move, teleport, set_*, attach, the listeners) or step()
///     runs alone: no query and no other change may overlap it, from any thread;
///   - step() calls the pair filter, on_pre_contact and the event callbacks on its own
///     thread only (never on the executor's workers), and they may query the world there;
///     the event callbacks may also change it;
///   - two worlds share nothing: different worlds may be stepped on different threads.
/// Builds with assertions (debug, PROXIMA_ENABLE_ASSERTS: the asan and tsan presets) check
/// these rules and fail PROXIMA_ASSERT on a query during a change or step from another
/// thread, or on two overlapping changes.
#include <proxima/core/executor.hpp>
#include <proxima/core/result.hpp>
#include <proxima/core/transform.hpp>
#include <proxima/geometry/aabb.hpp>
#include <proxima/geometry/ray.hpp>
#include <proxima/shapes/shape.hpp>
#include <proxima/shapes/shape_ref.hpp>
#include <proxima/world/collision_filter.hpp>
#include <proxima/world/object_desc.hpp>
#include <proxima/world/object_handle.hpp>
#include <proxima/world/scene_query.hpp>
#include <proxima/world/world_events.hpp>
#include <proxima/world/world_listener.hpp>
#include <proxima/world/world_settings.hpp>

#include <cstdint>
#include <iosfwd>
#include <memory>
#include <optional>
#include <span>
#include <vector>

namespace proxima {

/// One entry of a batch move: the object and its new world pose.
struct ObjectMove {
  ObjectHandle object;  ///< the object to move
  Transform pose;       ///< its new pose (local -> world)
};

/// The collision world (see the file comment). Movable, not copyable.
class CollisionWorld {
 public:
  /// A world with `settings`; an Error naming the bad field (validate_world_settings, or
  /// "settings.broadphase" for an unknown structure, listing the names).
  static Result<CollisionWorld> create(const WorldSettings& settings = {});

  CollisionWorld(CollisionWorld&&) noexcept;
  CollisionWorld& operator=(CollisionWorld&&) noexcept;
  CollisionWorld(const CollisionWorld&) = delete;
  CollisionWorld& operator=(const CollisionWorld&) = delete;
  ~CollisionWorld();

  /// The settings given to create().
  const WorldSettings& settings() const;

  // ---- objects ----------------------------------------------------------------------

  /// Adds an object. Errors name the field: "desc.pose" (not finite or not unit),
  /// "desc.geometry" (a half-space or an empty mesh that is not Static, a compound
  /// holding nothing), "desc.filter" (a layer or mask with no bits), "desc.parent" (stale or
  /// unknown), "desc.local_pose". An attached object takes the kind of its tree's root.
  Result<ObjectHandle> add(const ObjectDesc& desc);
  /// Removes an object and every object attached below it; their pairs end at the next
  /// step. Error: "object" (stale or unknown handle).
  std::optional<Error> remove(ObjectHandle object);
  /// Sets an object's world pose (an attached object: its local pose follows from its
  /// parent's); the objects attached below it follow. Errors: "object", "pose".
  std::optional<Error> move(ObjectHandle object, const Transform& pose);
  /// Moves many objects; all or nothing (the first bad entry is named: "moves[3].pose").
  /// The new boxes of objects neither attached nor carrying attached ones are computed on
  /// `executor`; the result is the serial one (entries apply in order; a later entry for
  /// the same object wins).
  std::optional<Error> move(std::span<const ObjectMove> moves, Executor& executor = serial_executor());
  /// Sets an object's world pose with no motion (a warp, like Box2D's b2Body_SetTransform or
  /// Jolt's SetPosition beside MoveKinematic): the next step's motion of the object and of
  /// its attached subtree starts at this pose, so continuous detection sweeps nothing up to
  /// it; contacts are re-tested at the next step. Errors: "object", "pose".
  std::optional<Error> teleport(ObjectHandle object, const Transform& pose);
  /// Replaces an object's geometry (its pairs are re-tested at the next step; a pair that no
  /// longer touches ends). Errors: "object", "geometry" (as for add).
  std::optional<Error> set_geometry(ObjectHandle object, const Shape& geometry);
  /// Replaces an object's filter. Errors: "object", "filter".
  std::optional<Error> set_filter(ObjectHandle object, const CollisionFilter& filter);
  /// Changes the kind of an object that is not attached (its tree follows). Errors:
  /// "object", "kind" (an attached object, or a half-space or mesh made Moving).
  std::optional<Error> set_kind(ObjectHandle object, ObjectKind kind);
  /// Sets an object's continuous-detection mode. Error: "object".
  std::optional<Error> set_ccd(ObjectHandle object, CcdMode mode);
  /// Sets an object's user data. Error: "object".
  std::optional<Error> set_user_data(ObjectHandle object, std::uint64_t user_data);
  /// Attaches `object` to `parent` at `local_pose` (parent = default handle: detaches it,
  /// keeping its world pose). Errors: "object", "parent" (stale, or `object` itself or one
  /// of its descendants), "local_pose".
  std::optional<Error> attach(ObjectHandle object, ObjectHandle parent, const Transform& local_pose);
  /// Excludes the pair (a, b) from colliding (parts of one ragdoll), or allows it again.
  /// Errors: "a", "b" (stale handles, or a == b).
  std::optional<Error> set_pair_excluded(ObjectHandle a, ObjectHandle b, bool excluded);

  /// True when `object` names a live object of this world.
  bool contains(ObjectHandle object) const;
  /// Number of live objects.
  std::size_t size() const;
  /// Every live object's handle, by index.
  std::vector<ObjectHandle> objects() const;
  /// The object's description as it is now (pose = its world pose); nothing for a stale handle.
  std::optional<ObjectDesc> object(ObjectHandle object) const;
  /// The object's world pose (identity for a stale handle).
  Transform pose(ObjectHandle object) const;
  /// The object's world box (an empty box for a stale handle).
  Aabb bounds(ObjectHandle object) const;

  // ---- callbacks ---------------------------------------------------------------------

  /// The world listener (not owned; nullptr: none). See world_listener.hpp.
  void set_listener(WorldListener* listener);
  /// A listener for the events of one object (not owned; nullptr removes it); dropped when
  /// the object is removed. Error: "object".
  std::optional<Error> set_object_listener(ObjectHandle object, WorldListener* listener);
  /// The custom pair filter (not owned; nullptr: none).
  void set_pair_filter(PairFilterCallback* filter);

  // ---- the step ----------------------------------------------------------------------

  /// Runs one step (see the file comment): `dt` is the step's duration (seconds, > 0, used
  /// for nothing but the validation of velocities and reported back); the broad phase's
  /// pair finding, the narrow phase and continuous detection run on `executor`, with the
  /// serial answer (the callbacks stay on the calling thread). Error: "dt" (not finite or
  /// <= 0), or a step called from a callback.
  std::optional<Error> step(Real dt, Executor& executor = serial_executor());
  /// The events of the last step.
  const StepEvents& events() const;
  /// The manifolds of the pairs touching after the last step, sorted by pair.
  std::span<const WorldManifold> contacts() const;
  /// The manifold of a touching pair (either order; the normal points from the lower handle
  /// to the higher), or nothing.
  const WorldManifold* contact(ObjectHandle a, ObjectHandle b) const;
  /// Mutable access to the user slots of a touching pair's points (for a solver).
  WorldManifold* contact(ObjectHandle a, ObjectHandle b);
  /// Number of steps run.
  std::uint64_t step_count() const;

  // ---- scene queries -----------------------------------------------------------------
  // Each query sees the objects `filter` accepts (collision_filter.hpp) and collects per
  // `mode` (scene_query.hpp). Errors name the argument: a non-finite or out-of-range ray,
  // point, box, pose, translation or distance; a sweep of a geometry that is not convex.

  /// Objects hit by the world-frame ray within [0, max_t] (t in units of the direction's
  /// length; the direction need not be unit, but not zero).
  Result<std::vector<WorldHit>> raycast(const Ray& ray, Real max_t, const QueryFilter& filter = {},
                                        QueryMode mode = QueryMode::Closest) const;
  /// True when nothing that `filter` sees touches the segment from `from` to `to` (AI
  /// visibility); from == to tests the point.
  Result<bool> line_of_sight(const Vec3& from, const Vec3& to, const QueryFilter& filter = {}) const;
  /// Objects that `geometry` placed at `pose` touches or overlaps.
  Result<std::vector<WorldOverlap>> overlap(ShapeRef geometry, const Transform& pose, const QueryFilter& filter = {},
                                            QueryMode mode = QueryMode::All) const;
  /// Objects whose geometry meets the closed world-frame box.
  Result<std::vector<WorldOverlap>> overlap_box(const Aabb& box, const QueryFilter& filter = {},
                                                QueryMode mode = QueryMode::All) const;
  /// Objects whose geometry contains or touches the world-frame point (meshes are surfaces).
  Result<std::vector<WorldOverlap>> overlap_point(const Vec3& point, const QueryFilter& filter = {},
                                                  QueryMode mode = QueryMode::All) const;
  /// Objects hit by the convex `geometry` at `pose` translated by `translation` (t is the
  /// fraction of it); an object it overlaps at the start is hit at t = 0 with the push-out
  /// normal (ccd/shape_cast.hpp's contract).
  Result<std::vector<WorldHit>> sweep(ShapeRef geometry, const Transform& pose, const Vec3& translation,
                                      const QueryFilter& filter = {}, QueryMode mode = QueryMode::Closest) const;
  /// The object nearest the point within `max_distance` (>= 0; signed: negative inside a
  /// solid), or nothing.
  Result<std::optional<WorldClosest>> closest_point(const Vec3& point, Real max_distance,
                                                    const QueryFilter& filter = {}) const;
  /// The object nearest `geometry` at `pose` within `max_distance` (>= 0), or nothing.
  Result<std::optional<WorldClosest>> closest(ShapeRef geometry, const Transform& pose, Real max_distance,
                                              const QueryFilter& filter = {}) const;

  // Batches: spans in, spans out (one answer per item, written in place), the items spread
  // over `executor`; the answers equal the single queries' in item order for every executor
  // and thread count. Every item is validated first: an error names the first bad one
  // ("rays[3].direction") or a span of the wrong size, and writes nothing.

  /// The closest hit of each ray: hits[i] for rays[i], a miss leaving hits[i].object unset
  /// (ObjectHandle{}: is_set() false). Returns the number of rays that hit. Error "hits" when
  /// hits.size() != rays.size().
  Result<std::size_t> raycast_batch(std::span<const WorldRay> rays, std::span<WorldHit> hits,
                                    const QueryFilter& filter = {}, Executor& executor = serial_executor()) const;
  /// line_of_sight of each segment: visible[i] = 1 when nothing touches segments[i], else 0.
  /// Returns the number of visible segments. Error "visible" for a size mismatch.
  Result<std::size_t> line_of_sight_batch(std::span<const WorldSegment> segments, std::span<std::uint8_t> visible,
                                          const QueryFilter& filter = {}, Executor& executor = serial_executor()) const;
  /// closest_point of each point within `max_distance`: nearest[i] for points[i], unset
  /// object when nothing is that near. Returns the number found. Error "nearest" for a size
  /// mismatch.
  Result<std::size_t> closest_point_batch(std::span<const Vec3> points, Real max_distance,
                                          std::span<WorldClosest> nearest, const QueryFilter& filter = {},
                                          Executor& executor = serial_executor()) const;

  // ---- state -------------------------------------------------------------------------

  /// A hash of the whole state (objects, poses, filters, modes, attachments, exclusions,
  /// touching pairs and their manifolds, step count): equal hashes mean equal worlds.
  std::uint64_t state_hash() const;

  /// Writes the whole world to `out` as a versioned binary snapshot: settings, every object
  /// (geometry of every kind, poses, pose at the last step, filter, kind, modes, user data,
  /// attachment), the slots' generations and free list, exclusions, the pair table with its
  /// caches, the manifolds and the events of the last step. Listeners and the pair filter are
  /// the caller's code and are not written. Error: "out" when the stream fails.
  std::optional<Error> save(std::ostream& out) const;
  /// A world read from a snapshot written by save(): its state_hash() equals the saved
  /// world's, and the same calls then give the same events. Errors name what is wrong
  /// ("snapshot": not a snapshot, an unsupported version, truncated or inconsistent data;
  /// "snapshot.objects[3].geometry": a geometry that no longer validates).
  static Result<CollisionWorld> load(std::istream& in);

  /// Internal state (src/world/world_state.hpp).
  struct Impl;

 private:
  explicit CollisionWorld(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace proxima
