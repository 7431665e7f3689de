#pragma once
/// @file world_listener.hpp
/// WorldListener: the callbacks of a CollisionWorld. A world listener (set_listener) hears
/// every event; an object listener (set_object_listener) hears the events that involve its
/// object. Both are called on the thread that runs step(), after the step has computed
/// everything, in the order of the event arrays (world_events.hpp): contact begin, persist,
/// end, sensor enter, exit, impacts; for each event the world listener first, then the
/// listeners of a and of b.
///
/// on_pre_contact is the exception: it is called during the step, once per touching pair
/// in pair order, before the events are derived; it may edit the manifold (drop or move
/// points, change the user slots) or veto the pair for this step (return false: the pair
/// counts as not touching this step, so it begins, persists or ends accordingly).
///
/// During the event callbacks the world may be changed (objects added, removed, moved,
/// refiltered): the change applies at once, the events already computed are still delivered
/// (their handles may then be stale: check CollisionWorld::contains), and the pairs it ends
/// are reported as ended by the next step. on_pre_contact must not change the world (such
/// calls are rejected with an error).
#include <proxima/world/object_handle.hpp>
#include <proxima/world/world_events.hpp>

namespace proxima {

class CollisionWorld;

/// Callbacks of a CollisionWorld (see the file comment). Every member has an empty default.
class WorldListener {
 public:
  virtual ~WorldListener() = default;
  /// A pair began touching.
  virtual void on_contact_begin(CollisionWorld& world, const ContactEvent& event) {
    (void)world;
    (void)event;
  }
  /// A pair touched in the previous step and still does.
  virtual void on_contact_persist(CollisionWorld& world, const ContactEvent& event) {
    (void)world;
    (void)event;
  }
  /// A pair stopped touching (or was filtered out, or lost an object).
  virtual void on_contact_end(CollisionWorld& world, const ContactEvent& event) {
    (void)world;
    (void)event;
  }
  /// An object entered a sensor.
  virtual void on_sensor_enter(CollisionWorld& world, const SensorEvent& event) {
    (void)world;
    (void)event;
  }
  /// An object left a sensor.
  virtual void on_sensor_exit(CollisionWorld& world, const SensorEvent& event) {
    (void)world;
    (void)event;
  }
  /// A fast object's first impact in the step.
  virtual void on_impact(CollisionWorld& world, const ImpactEvent& event) {
    (void)world;
    (void)event;
  }
  /// Called for every touching pair during the step (world listener only): edit `manifold`
  /// or return false to veto the pair for this step.
  virtual bool on_pre_contact(const CollisionWorld& world, WorldManifold& manifold) {
    (void)world;
    (void)manifold;
    return true;
  }
};

/// A custom pair filter (CollisionWorld::set_pair_filter): asked, after the layers, groups
/// and exclusions have allowed a pair, whether the pair may collide. Used by the step (broad
/// phase candidates, continuous detection) and by nothing else; it must not change the world.
class PairFilterCallback {
 public:
  virtual ~PairFilterCallback() = default;
  /// True when the objects `pair.a` and `pair.b` may collide.
  virtual bool can_collide(const CollisionWorld& world, ObjectPair pair) = 0;
};

}  // namespace proxima
