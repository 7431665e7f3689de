#pragma once
/// @file world_events.hpp
/// What a CollisionWorld's step reports: persistent contact manifolds, and the events of a
/// step (contact begin / persist / end, sensor enter / exit, continuous impacts), delivered
/// as arrays read after the step and through listeners (world_listener.hpp).
///
/// Order: every array is sorted by its pair of handles (contacts by (a, b) with a < b;
/// sensor events by (sensor, other); impacts by (a, b)), whatever the broad phase or the
/// executor, so two runs of the same scene report identical arrays.
///
/// Points and normals are in the world frame; a normal is unit and points from A to B (the
/// narrow phase's convention, docs/conventions.md); depth > 0 is a penetration, depth < 0 a
/// speculative gap (within the world's contact distance).
#include <proxima/core/math.hpp>
#include <proxima/core/sub_shape_id.hpp>
#include <proxima/narrowphase/contact.hpp>
#include <proxima/world/object_handle.hpp>

#include <array>
#include <cstdint>
#include <vector>

namespace proxima {

/// One point of a persistent manifold: the narrow phase's contact point, plus what the world
/// keeps across steps. A point persists when the next step finds a point with the same
/// feature id on the same parts (sub-shape ids) of the pair (Lin and Canny's observation that
/// the closest features rarely change between frames); it then keeps its id and its user
/// slots (a solver's accumulated impulses, for warm starting).
struct WorldContactPoint {
  ContactPoint contact;                        ///< points, normal, depth, feature id and parts (world frame)
  std::uint32_t id = 0;                        ///< stable while the point persists; unique within its manifold's life
  bool persisted = false;                      ///< true when the point existed in the previous step
  std::array<Real, 2> user{Real(0), Real(0)};  ///< caller's slots, carried over while the point persists
};

/// The contact manifold of a touching pair (objects within the contact distance), kept from
/// step to step while the pair touches.
struct WorldManifold {
  ObjectPair pair;                                            ///< the two objects, a < b; the normal points from a to b
  Vec3 normal{Real(0), Real(0), Real(1)};                     ///< unit, world frame, from a to b
  int count = 0;                                              ///< valid entries in `points` (1..4 while touching)
  std::array<WorldContactPoint, kMaxContactPoints> points{};  ///< the points (first `count`)
};

/// A contact event of a pair of non-sensor objects: begin (the pair touches and did not in
/// the previous step), persist (touches in both), end (touched in the previous step and does
/// not now, was filtered out, or one of its objects was removed; then that handle is stale).
struct ContactEvent {
  ObjectPair pair;                ///< a < b
  std::uint64_t user_data_a = 0;  ///< user data of a (as it was when a was last seen)
  std::uint64_t user_data_b = 0;  ///< user data of b
  friend bool operator==(const ContactEvent&, const ContactEvent&) = default;
};

/// A sensor event: `other` entered (began to overlap) or exited the sensor object `sensor`.
struct SensorEvent {
  ObjectHandle sensor;                 ///< the sensor object
  ObjectHandle other;                  ///< the object that entered or exited
  std::uint64_t user_data_sensor = 0;  ///< user data of the sensor
  std::uint64_t user_data_other = 0;   ///< user data of the other object
  friend bool operator==(const SensorEvent&, const SensorEvent&) = default;
};

/// A continuous-detection impact: the fast object `a`, moving from its previous pose to its
/// new one over the step, first comes within the contact distance of `b` at fraction `toi`
/// of the step (the certified time of impact, ccd/time_of_impact.hpp). Point and normal at
/// that time, world frame; the normal points from a to b.
struct ImpactEvent {
  ObjectHandle a;                          ///< the fast object
  ObjectHandle b;                          ///< what it reaches first
  Real toi = Real(0);                      ///< fraction of the step in [0, 1] (t_upper of the certificate)
  Vec3 point{Real(0)};                     ///< contact point at toi, world frame
  Vec3 normal{Real(0), Real(0), Real(1)};  ///< unit, from a to b, world frame
  SubShapeId sub_a{};                      ///< part of a at the contact
  SubShapeId sub_b{};                      ///< part of b at the contact
  std::uint64_t user_data_a = 0;           ///< user data of a
  std::uint64_t user_data_b = 0;           ///< user data of b
};

/// Every event of one step, each array sorted (see the file comment).
struct StepEvents {
  std::vector<ContactEvent> begin;        ///< pairs that began touching
  std::vector<ContactEvent> persist;      ///< pairs that touched before and still do
  std::vector<ContactEvent> end;          ///< pairs that stopped touching
  std::vector<SensorEvent> sensor_enter;  ///< objects that entered a sensor
  std::vector<SensorEvent> sensor_exit;   ///< objects that left a sensor
  std::vector<ImpactEvent> impacts;       ///< first impacts of fast objects

  /// Empties every array (keeps their capacity).
  void clear() {
    begin.clear();
    persist.clear();
    end.clear();
    sensor_enter.clear();
    sensor_exit.clear();
    impacts.clear();
  }
};

}  // namespace proxima
