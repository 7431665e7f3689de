#pragma once
/// @file world_rows.hpp
/// What the 3D and the 2D world bindings (bind_world.cpp, bind_world_d2.cpp) share, none of
/// it depending on the dimension:
///   1. handles as Python integers, query filters from keyword arguments, the settings from
///      the constructor's arguments, snapshots as bytes, the calls both world classes bind
///      alike;
///   2. contact and sensor events as rows of numpy structured arrays (CONTACT_EVENT_DTYPE,
///      SENSOR_EVENT_DTYPE, registered by bind_world.cpp);
///   3. ListenerForwarder: calls a Python listener's on_* methods from a step that runs with
///      the GIL released, keeping the first exception one raised and raising it again from
///      step() once the library's step has finished (never thrown through it).
#include <proxima/world/collision_filter.hpp>
#include <proxima/world/world_events.hpp>
#include <proxima/world/world_settings.hpp>

#include <cstdint>
#include <sstream>
#include <string>
#include <vector>

#include "conversions.hpp"

namespace proxima::python {

/// A contact event as a row of CONTACT_EVENT_DTYPE.
struct ContactEventRow {
  std::uint64_t a, b, user_data_a, user_data_b;
};
/// A sensor event as a row of SENSOR_EVENT_DTYPE.
struct SensorEventRow {
  std::uint64_t sensor, other, user_data_sensor, user_data_other;
};

/// The handle a Python integer names.
inline ObjectHandle handle_of(std::uint64_t h) { return ObjectHandle::from_integer(h); }

/// Handles as a uint64 array of their Python integers.
inline py::array_t<std::uint64_t> handle_array(const std::vector<ObjectHandle>& handles) {
  py::array_t<std::uint64_t> out(static_cast<py::ssize_t>(handles.size()));
  for (std::size_t i = 0; i < handles.size(); ++i) out.mutable_data()[i] = handles[i].to_integer();
  return out;
}

/// A query filter from the keyword arguments mask, group and ignore (a handle or None).
inline QueryFilter query_filter(std::uint64_t mask, std::int32_t group, py::handle ignore) {
  QueryFilter f;
  f.mask = mask;
  f.group = group;
  if (!ignore.is_none()) f.ignore = handle_of(ignore.cast<std::uint64_t>());
  return f;
}

/// The world settings from the constructor's arguments (validated by the world's create).
inline WorldSettings settings_of(const std::string& broadphase, Real contact_distance, int max_contacts,
                                 bool sensors_sense_sensors, bool continuous, Real ccd_safety_factor,
                                 Real ccd_tolerance) {
  WorldSettings s;
  s.broadphase = broadphase;
  s.contact_distance = contact_distance;
  s.max_contacts = max_contacts;
  s.sensors_sense_sensors = sensors_sense_sensors;
  s.continuous = continuous;
  s.ccd_safety_factor = ccd_safety_factor;
  s.ccd_tolerance = ccd_tolerance;
  return s;
}

/// A world's snapshot (its save()) as bytes; proxima.Error when it fails.
template <class World>
py::bytes snapshot_bytes(const World& world) {
  std::ostringstream out(std::ios::binary);
  check(world.save(out));
  return py::bytes(out.str());
}

/// The world a snapshot's bytes hold (World::load); proxima.Error names what is wrong.
template <class World>
World world_from_bytes(const py::bytes& data) {
  std::istringstream in(std::string(data), std::ios::binary);
  return take(World::load(in));
}

/// A new one-dimensional structured array of `n` rows of T (a registered dtype).
template <class T>
py::array_t<T> rows_of(std::size_t n) {
  return py::array_t<T>(static_cast<py::ssize_t>(n));
}

/// Contact events as an array of CONTACT_EVENT_DTYPE.
inline py::array contact_events(const std::vector<ContactEvent>& events) {
  auto out = rows_of<ContactEventRow>(events.size());
  ContactEventRow* r = out.mutable_data();
  for (const ContactEvent& e : events)
    *r++ = {e.pair.a.to_integer(), e.pair.b.to_integer(), e.user_data_a, e.user_data_b};
  return out;
}

/// Sensor events as an array of SENSOR_EVENT_DTYPE.
inline py::array sensor_events(const std::vector<SensorEvent>& events) {
  auto out = rows_of<SensorEventRow>(events.size());
  SensorEventRow* r = out.mutable_data();
  for (const SensorEvent& e : events) {
    *r++ = {e.sensor.to_integer(), e.other.to_integer(), e.user_data_sensor, e.user_data_other};
  }
  return out;
}

/// A step's events as a dict of structured arrays: begin, persist, end, sensor_enter,
/// sensor_exit, and `impacts` (rows of the dimension's impact dtype).
template <class StepEvents>
py::dict events_dict(const StepEvents& e, py::array impacts) {
  py::dict d;
  d["begin"] = contact_events(e.begin);
  d["persist"] = contact_events(e.persist);
  d["end"] = contact_events(e.end);
  d["sensor_enter"] = sensor_events(e.sensor_enter);
  d["sensor_exit"] = sensor_events(e.sensor_exit);
  d["impacts"] = std::move(impacts);
  return d;
}

/// Defines on `c` (a py::class_ of a binding struct whose `world` points at a 3D or a 2D
/// world and whose `listener` is a ListenerForwarder) the calls both worlds bind alike: move,
/// teleport (their poses read by `read_pose(value, field)`), remove, set_filter,
/// set_pair_excluded, set_listener, len, in and state_hash.
template <class Class, class ReadPose>
void def_shared_world_calls(Class& c, ReadPose read_pose) {
  using Bound = typename Class::type;
  c.def(
       "move",
       [read_pose](Bound& w, std::uint64_t h, py::handle pose) {
         check(w.world->move(handle_of(h), read_pose(pose, "pose")));
       },
       py::arg("object"), py::arg("pose"),
       "Sets the object's pose for the next step (its motion for CCD starts at the old one).")
      .def(
          "teleport",
          [read_pose](Bound& w, std::uint64_t h, py::handle pose) {
            check(w.world->teleport(handle_of(h), read_pose(pose, "pose")));
          },
          py::arg("object"), py::arg("pose"), "Sets the pose with no motion (continuous detection sweeps nothing).")
      .def(
          "remove", [](Bound& w, std::uint64_t h) { check(w.world->remove(handle_of(h))); }, py::arg("object"),
          "Removes the object (its touching pairs end at the next step).")
      .def(
          "set_filter",
          [](Bound& w, std::uint64_t h, const CollisionFilter& f) { check(w.world->set_filter(handle_of(h), f)); },
          py::arg("object"), py::arg("filter"), "Replaces the object's filter.")
      .def(
          "set_pair_excluded",
          [](Bound& w, std::uint64_t a, std::uint64_t b, bool excluded) {
            check(w.world->set_pair_excluded(handle_of(a), handle_of(b), excluded));
          },
          py::arg("a"), py::arg("b"), py::arg("excluded") = true, "Never pair these two objects (or again allow it).")
      .def(
          "set_listener",
          [](Bound& w, py::object listener) {
            w.listener.target = listener;
            w.world->set_listener(listener.is_none() ? nullptr : &w.listener);
          },
          py::arg("listener"),
          "An object whose methods on_contact_begin, on_contact_persist, on_contact_end, on_sensor_enter, "
          "on_sensor_exit, on_impact (those it has) are called with each event during step(); None removes it.")
      .def("__len__", [](const Bound& w) { return w.world->size(); })
      .def("__contains__", [](const Bound& w, std::uint64_t h) { return w.world->contains(handle_of(h)); })
      .def(
          "state_hash", [](const Bound& w) { return w.world->state_hash(); },
          "A hash of the whole state: equal hashes mean equal worlds.");
}

/// Forwards a world's callbacks to a Python object's on_* methods (those it has).
class ListenerForwarder {
 public:
  py::object target = py::none();   ///< the Python listener, or None
  py::object pending = py::none();  ///< the first exception a callback raised during this step

  /// Calls target.<name>(event) under the GIL, unless a callback of this step already raised.
  template <class E>
  void call(const char* name, const E& event) {
    py::gil_scoped_acquire gil;
    if (target.is_none() || !pending.is_none() || !py::hasattr(target, name)) return;
    try {
      target.attr(name)(event);
    } catch (py::error_already_set& e) {
      pending = py::make_tuple(e.type(), e.value(), e.trace());
    }
  }
  /// Raises (and clears) the exception a callback kept, if any; called with the GIL held.
  void raise_pending() {
    if (pending.is_none()) return;
    const py::tuple e = pending;
    pending = py::none();
    PyErr_Restore(py::object(e[0]).release().ptr(), py::object(e[1]).release().ptr(), py::object(e[2]).release().ptr());
    throw py::error_already_set();
  }
};

}  // namespace proxima::python
