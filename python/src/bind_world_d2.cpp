// proxima.d2.CollisionWorld: the 2D collision world, bound like proxima.CollisionWorld
// (bind_world.cpp) with 2D shapes and poses (x, y, angle in radians).
//
// Steps of a call to step(): 1. release the GIL and run the library's step on the caller's
// thread or a pool; 2. the listener's callbacks re-take the GIL one by one (world_rows.hpp's
// ListenerForwarder: the first exception is kept and raised from step() afterwards); 3. the
// events and manifolds are then read as numpy structured arrays. Snapshots are bytes, and
// the world pickles through them.
#include <proxima/d2/collision_world.hpp>
#include <proxima/debug/capture_recorder_2d.hpp>

#include <pybind11/stl.h>

#include "batch_arrays.hpp"
#include "d2_conversions.hpp"
#include "module_parts.hpp"
#include "recording.hpp"
#include "world_rows.hpp"

namespace proxima::python {
namespace {

/// A 2D impact as a row of d2.IMPACT_EVENT_DTYPE.
struct ImpactRow2 {
  std::uint64_t a, b;
  double toi;
  double point[2];
  double normal[2];
  std::int32_t part_b;
  std::uint64_t user_data_a, user_data_b;
};
/// One point of a 2D manifold as a row of d2.MANIFOLD_POINT_DTYPE.
struct ManifoldPointRow2 {
  std::uint64_t a, b;
  std::int32_t part_a, part_b;
  double normal[2];
  double point_a[2];
  double point_b[2];
  double depth;
  std::uint32_t feature_id;
};

void put2(double (&out)[2], const d2::Vec2& v) { out[0] = double(v.x), out[1] = double(v.y); }

/// Forwards the 2D world's callbacks to a Python object's on_* methods (those it has).
class PyListener2 final : public d2::WorldListener, public ListenerForwarder {
 public:
  void on_contact_begin(const d2::CollisionWorld&, const ContactEvent& e) override { call("on_contact_begin", e); }
  void on_contact_persist(const d2::CollisionWorld&, const ContactEvent& e) override { call("on_contact_persist", e); }
  void on_contact_end(const d2::CollisionWorld&, const ContactEvent& e) override { call("on_contact_end", e); }
  void on_sensor_enter(const d2::CollisionWorld&, const SensorEvent& e) override { call("on_sensor_enter", e); }
  void on_sensor_exit(const d2::CollisionWorld&, const SensorEvent& e) override { call("on_sensor_exit", e); }
  void on_impact(const d2::CollisionWorld&, const d2::ImpactEvent& e) override { call("on_impact", e); }
};

/// The 2D world and its listener.
struct PyWorld2 {
  std::unique_ptr<d2::CollisionWorld> world;
  PyListener2 listener;
  std::unique_ptr<Recording<debug::CaptureRecorder2D>> recording;  ///< set while recording
};

std::unique_ptr<PyWorld2> wrap_world2(d2::CollisionWorld&& world) {
  auto w = std::make_unique<PyWorld2>();
  w->world = std::make_unique<d2::CollisionWorld>(std::move(world));
  return w;
}

py::array impact_events2(const std::vector<d2::ImpactEvent>& events) {
  auto out = rows_of<ImpactRow2>(events.size());
  ImpactRow2* r = out.mutable_data();
  for (const d2::ImpactEvent& e : events) {
    r->a = e.a.to_integer(), r->b = e.b.to_integer(), r->toi = double(e.toi);
    put2(r->point, e.point);
    put2(r->normal, e.normal);
    r->part_b = e.part_b, r->user_data_a = e.user_data_a, r->user_data_b = e.user_data_b;
    ++r;
  }
  return out;
}

py::array manifold_points(std::span<const d2::WorldManifold> manifolds) {
  std::size_t n = 0;
  for (const d2::WorldManifold& m : manifolds) n += static_cast<std::size_t>(m.manifold.count);
  auto out = rows_of<ManifoldPointRow2>(n);
  ManifoldPointRow2* r = out.mutable_data();
  for (const d2::WorldManifold& m : manifolds) {
    for (int i = 0; i < m.manifold.count; ++i) {
      const d2::ContactPoint& p = m.manifold.points[static_cast<std::size_t>(i)];
      r->a = m.pair.a.to_integer(), r->b = m.pair.b.to_integer();
      r->part_a = m.manifold.part_a, r->part_b = m.manifold.part_b;
      put2(r->normal, m.manifold.normal);
      put2(r->point_a, p.point_a);
      put2(r->point_b, p.point_b);
      r->depth = double(p.depth), r->feature_id = p.feature_id;
      ++r;
    }
  }
  return out;
}

py::bytes save_world2(const PyWorld2& w) { return snapshot_bytes(*w.world); }

std::unique_ptr<PyWorld2> load_world2(const py::bytes& data) {
  return wrap_world2(world_from_bytes<d2::CollisionWorld>(data));
}

void step2(PyWorld2& w, long threads) {
  const std::size_t count = resolve_threads(threads);
  std::optional<Error> error;
  {
    py::gil_scoped_release release;
    error = w.world->step(count <= 1 ? serial_executor() : thread_pool(count));
  }
  // A 2D step has no duration: its capture line's dt is 1 (one step).
  if (w.recording && !error) check(w.recording->recorder->record_step(*w.world, Real(1)));
  w.listener.raise_pending();
  check(error);
}

std::uint64_t add_object2(PyWorld2& w, py::handle shape, py::handle pose, ObjectKind kind,
                          const CollisionFilter& filter, bool sensor, CcdMode ccd, std::uint64_t user_data) {
  d2::ObjectDesc d;
  d.shape = to_shape2(shape, "shape");
  d.pose = to_pose2(pose, "pose");
  d.kind = kind;
  d.filter = filter;
  d.sensor = sensor;
  d.ccd = ccd;
  d.user_data = user_data;
  return take(w.world->add(d)).to_integer();
}

void bind_world2_types(py::module_& m, py::module_& d) {
  for (const char* shared : {"ObjectKind", "CcdMode", "CollisionFilter", "ContactEvent", "SensorEvent",
                             "CONTACT_EVENT_DTYPE", "SENSOR_EVENT_DTYPE"}) {
    d.attr(shared) = m.attr(shared);
  }
  py::class_<d2::ImpactEvent>(d, "ImpactEvent", "The first impact of a fast 2D object during a step (world frame).")
      .def_property_readonly("a", [](const d2::ImpactEvent& e) { return e.a.to_integer(); })
      .def_property_readonly("b", [](const d2::ImpactEvent& e) { return e.b.to_integer(); })
      .def_readonly("toi", &d2::ImpactEvent::toi, "Fraction of the step in [0, 1].")
      .def_property_readonly("point", [](const d2::ImpactEvent& e) { return to_numpy2(e.point); })
      .def_property_readonly("normal", [](const d2::ImpactEvent& e) { return to_numpy2(e.normal); })
      .def_readonly("part_b", &d2::ImpactEvent::part_b, "Chain segment of b (-1: convex).")
      .def_readonly("user_data_a", &d2::ImpactEvent::user_data_a)
      .def_readonly("user_data_b", &d2::ImpactEvent::user_data_b)
      .def("__repr__", [](const d2::ImpactEvent& e) {
        return "d2.ImpactEvent(a=" + std::to_string(e.a.to_integer()) + ", b=" + std::to_string(e.b.to_integer()) +
               ", toi=" + repr_real(e.toi) + ")";
      });
  py::class_<d2::WorldRayHit>(d, "WorldRayHit", "The object a ray hits first in a 2D world (world frame).")
      .def_property_readonly("object", [](const d2::WorldRayHit& h) { return h.object.to_integer(); })
      .def_property_readonly("t", [](const d2::WorldRayHit& h) { return h.hit.t; })
      .def_property_readonly("point", [](const d2::WorldRayHit& h) { return to_numpy2(h.hit.point); })
      .def_property_readonly("normal", [](const d2::WorldRayHit& h) { return to_numpy2(h.hit.normal); })
      .def_property_readonly("part", [](const d2::WorldRayHit& h) { return h.hit.part; })
      .def("__repr__", [](const d2::WorldRayHit& h) {
        return "d2.WorldRayHit(object=" + std::to_string(h.object.to_integer()) + ", t=" + repr_real(h.hit.t) + ")";
      });
  PYBIND11_NUMPY_DTYPE(ImpactRow2, a, b, toi, point, normal, part_b, user_data_a, user_data_b);
  PYBIND11_NUMPY_DTYPE(ManifoldPointRow2, a, b, part_a, part_b, normal, point_a, point_b, depth, feature_id);
  d.attr("IMPACT_EVENT_DTYPE") = py::dtype::of<ImpactRow2>();
  d.attr("MANIFOLD_POINT_DTYPE") = py::dtype::of<ManifoldPointRow2>();
}

using World2 = py::class_<PyWorld2, std::unique_ptr<PyWorld2>>;

void def_objects2(World2& c) {
  c.def("add", &add_object2, py::arg("shape"), py::arg("pose") = py::none(), py::kw_only(),
        py::arg("kind") = ObjectKind::Moving, py::arg("filter") = CollisionFilter{}, py::arg("sensor") = false,
        py::arg("ccd") = CcdMode::Auto, py::arg("user_data") = 0,
        "Adds an object at pose (x, y, angle); returns its handle (an int). A chain only as kind=ObjectKind.Static.")
      .def(
          "objects", [](const PyWorld2& w) { return handle_array(w.world->objects()); },
          "Handles of every object, as a uint64 array (slot order).")
      .def(
          "pose",
          [](const PyWorld2& w, std::uint64_t h) {
            const std::optional<d2::Pose> p = w.world->pose(handle_of(h));
            if (!p) raise_argument_error("object", "no such object");
            return py::make_tuple(double(p->position.x), double(p->position.y), double(p->rotation.angle()));
          },
          py::arg("object"), "The object's pose as (x, y, angle).");
}

void def_step2(World2& c) {
  c.def("step", &step2, py::kw_only(), py::arg("threads") = 1,
        "Runs the broad and narrow phases and continuous detection, then calls the listener. threads: 0 every "
        "hardware thread; the GIL is released.")
      .def_property_readonly(
          "events",
          [](const PyWorld2& w) { return events_dict(w.world->events(), impact_events2(w.world->events().impacts)); },
          "The last step's events: a dict of structured arrays (begin, persist, end: CONTACT_EVENT_DTYPE; "
          "sensor_enter, sensor_exit: SENSOR_EVENT_DTYPE; impacts: d2.IMPACT_EVENT_DTYPE).")
      .def(
          "manifolds", [](const PyWorld2& w) { return manifold_points(w.world->manifolds()); },
          "Every point of the touching pairs' manifolds, by pair then chain segment: an array of "
          "d2.MANIFOLD_POINT_DTYPE (a, b, part_a, part_b, normal, point_a, point_b, depth, feature_id).")
      .def(
          "record",
          [](PyWorld2& w, const std::string& path, py::handle camera) {
            w.recording = start_recording<debug::CaptureRecorder2D>(path, camera);
          },
          py::arg("path"), py::arg("camera") = py::none(),
          "Records every following step to a 2D capture file (docs/capture-format.md, dimension 2: the objects in "
          "the plane z = 0; a step's dt is 1); read it with proxima.capture, draw it with proxima.render or "
          "proxima view. camera: a dict of position, target, up, fov_degrees, ortho_height.")
      .def(
          "stop_recording", [](PyWorld2& w) { w.recording.reset(); }, "Closes the capture file.");
}

void def_queries2(World2& c) {
  c.def(
       "raycast",
       [](const PyWorld2& w, py::handle origin, py::handle direction, Real max_t, std::uint64_t mask,
          std::int32_t group, py::handle ignore) {
         const d2::Ray ray{to_vec2(origin, "origin"), to_vec2(direction, "direction")};
         if (ray.direction == d2::Vec2(Real(0))) raise_argument_error("direction", "must not be zero");
         if (!(max_t >= Real(0))) raise_argument_error("max_t", "must be >= 0");
         return w.world->raycast(ray, max_t, query_filter(mask, group, ignore));
       },
       py::arg("origin"), py::arg("direction"), py::arg("max_t") = Real(1), py::kw_only(), py::arg("mask") = ~0ull,
       py::arg("group") = 0, py::arg("ignore") = py::none(),
       "The first object hit within [0, max_t] (t in units of the direction's length): a d2.WorldRayHit or None.")
      .def(
          "overlap",
          [](const PyWorld2& w, py::handle shape, py::handle pose, std::uint64_t mask, std::int32_t group,
             py::handle ignore) {
            std::vector<ObjectHandle> found;
            w.world->overlap(to_shape2(shape, "shape"), to_pose2(pose, "pose"), query_filter(mask, group, ignore),
                             found);
            std::vector<std::uint64_t> handles;
            for (ObjectHandle h : found) handles.push_back(h.to_integer());
            return handles;
          },
          py::arg("shape"), py::arg("pose") = py::none(), py::kw_only(), py::arg("mask") = ~0ull, py::arg("group") = 0,
          py::arg("ignore") = py::none(), "Handles of the objects the placed shape touches or overlaps, ascending.");
}

void def_snapshots2(World2& c) {
  c.def("save", &save_world2, "The world as a versioned binary snapshot (bytes).")
      .def_static("load", &load_world2, py::arg("snapshot"),
                  "A world from save()'s bytes; proxima.Error names what is wrong (field 'snapshot...').")
      .def(py::pickle([](const PyWorld2& w) { return save_world2(w); },
                      [](const py::bytes& data) { return load_world2(data); }));
}

}  // namespace

void bind_world_d2(py::module_& m) {
  py::module_ d = py::reinterpret_borrow<py::module_>(m.attr("d2"));
  bind_world2_types(m, d);
  World2 c(d, "CollisionWorld",
           "The 2D collision world: objects by integer handle, a step that reports contacts, sensors and impacts, "
           "scene queries and snapshots. Lengths in the caller's units, poses (x, y, angle) local -> world.");
  c.def(py::init([](const std::string& broadphase, Real contact_distance, int max_contacts, bool sensors_sense_sensors,
                    bool continuous, Real ccd_safety_factor, Real ccd_tolerance) {
          return wrap_world2(take(
              d2::CollisionWorld::create(settings_of(broadphase, contact_distance, max_contacts, sensors_sense_sensors,
                                                     continuous, ccd_safety_factor, ccd_tolerance))));
        }),
        py::arg("broadphase") = "tree", py::arg("contact_distance") = Real(0), py::arg("max_contacts") = 2,
        py::arg("sensors_sense_sensors") = false, py::arg("continuous") = true,
        py::arg("ccd_safety_factor") = Real(0.25), py::arg("ccd_tolerance") = Real(0));
  def_shared_world_calls(c, &to_pose2);
  def_objects2(c);
  def_step2(c);
  def_queries2(c);
  def_snapshots2(c);
}

}  // namespace proxima::python
