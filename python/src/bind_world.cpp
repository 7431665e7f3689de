// proxima.CollisionWorld: objects by integer handle, filters, the step, its events as numpy
// structured arrays, callbacks into Python, scene queries (single and batched on numpy
// arrays) and snapshots (bytes; the world pickles through them).
//
// Callbacks: the step runs with the GIL released; the listener re-takes it for each call.
// An exception raised by a Python callback stops further callbacks of that step and is
// raised again from step() once the library's step has finished (never thrown through it):
// world_rows.hpp's ListenerForwarder, shared with the 2D world (bind_world_d2.cpp).
#include <proxima/core/validate.hpp>
#include <proxima/debug/capture_recorder.hpp>
#include <proxima/world/collision_world.hpp>

#include <fstream>
#include <limits>
#include <pybind11/stl.h>

#include "batch_arrays.hpp"
#include "module_parts.hpp"
#include "recording.hpp"
#include "shape_object.hpp"
#include "world_rows.hpp"

namespace proxima::python {
namespace {

struct ImpactEventRow {
  std::uint64_t a, b;
  double toi;
  double point[3];
  double normal[3];
  std::uint64_t user_data_a, user_data_b;
};
struct ContactPointRow {
  std::uint64_t a, b;
  double normal[3];
  double point_a[3];
  double point_b[3];
  double depth;
  std::uint32_t id;
  bool persisted;
};
struct WorldHitRow {
  bool hit;
  std::uint64_t object;
  std::uint64_t user_data;
  double t;
  double point[3];
  double normal[3];
};
struct WorldClosestRow {
  bool found;
  std::uint64_t object;
  std::uint64_t user_data;
  double signed_distance;
  double point_object[3];
  double normal[3];
};

void put(double (&out)[3], const Vec3& v) { out[0] = double(v.x), out[1] = double(v.y), out[2] = double(v.z); }

/// Forwards the world's callbacks to a Python object's on_* methods (those it has).
class PyListener final : public WorldListener, public ListenerForwarder {
 public:
  void on_contact_begin(CollisionWorld&, const ContactEvent& e) override { call("on_contact_begin", e); }
  void on_contact_persist(CollisionWorld&, const ContactEvent& e) override { call("on_contact_persist", e); }
  void on_contact_end(CollisionWorld&, const ContactEvent& e) override { call("on_contact_end", e); }
  void on_sensor_enter(CollisionWorld&, const SensorEvent& e) override { call("on_sensor_enter", e); }
  void on_sensor_exit(CollisionWorld&, const SensorEvent& e) override { call("on_sensor_exit", e); }
  void on_impact(CollisionWorld&, const ImpactEvent& e) override { call("on_impact", e); }
};

/// The world and what the bindings keep beside it.
struct PyWorld {
  std::unique_ptr<CollisionWorld> world;
  PyListener listener;
  std::unique_ptr<Recording<debug::CaptureRecorder>> recording;  ///< set while recording
};

QueryMode query_mode(const std::string& mode) {
  if (mode == "closest") return QueryMode::Closest;
  if (mode == "any") return QueryMode::Any;
  if (mode == "all") return QueryMode::All;
  raise_argument_error("mode", "expected 'closest', 'any' or 'all'");
}

py::array impact_events(const std::vector<ImpactEvent>& events) {
  auto out = rows_of<ImpactEventRow>(events.size());
  ImpactEventRow* r = out.mutable_data();
  for (const ImpactEvent& e : events) {
    r->a = e.a.to_integer(), r->b = e.b.to_integer(), r->toi = double(e.toi);
    put(r->point, e.point);
    put(r->normal, e.normal);
    r->user_data_a = e.user_data_a, r->user_data_b = e.user_data_b;
    ++r;
  }
  return out;
}

py::array contact_points(std::span<const WorldManifold> manifolds) {
  std::size_t n = 0;
  for (const WorldManifold& m : manifolds) n += static_cast<std::size_t>(m.count);
  auto out = rows_of<ContactPointRow>(n);
  ContactPointRow* r = out.mutable_data();
  for (const WorldManifold& m : manifolds) {
    for (int i = 0; i < m.count; ++i) {
      const WorldContactPoint& p = m.points[static_cast<std::size_t>(i)];
      r->a = m.pair.a.to_integer(), r->b = m.pair.b.to_integer();
      put(r->normal, m.normal);
      put(r->point_a, p.contact.point_a);
      put(r->point_b, p.contact.point_b);
      r->depth = double(p.contact.depth), r->id = p.id, r->persisted = p.persisted;
      ++r;
    }
  }
  return out;
}

std::unique_ptr<PyWorld> wrap_world(CollisionWorld&& world) {
  auto w = std::make_unique<PyWorld>();
  w->world = std::make_unique<CollisionWorld>(std::move(world));
  return w;
}

py::bytes save_world(const PyWorld& w) { return snapshot_bytes(*w.world); }

std::unique_ptr<PyWorld> load_world(const py::bytes& data) {
  return wrap_world(world_from_bytes<CollisionWorld>(data));
}

}  // namespace
}  // namespace proxima::python

namespace proxima::python {
namespace {

void bind_world_types(py::module_& m) {
  py::enum_<ObjectKind>(m, "ObjectKind", "How an object takes part in the step.")
      .value("Static", ObjectKind::Static)
      .value("Moving", ObjectKind::Moving);
  py::enum_<CcdMode>(m, "CcdMode", "Continuous detection of a world object.")
      .value("Off", CcdMode::Off)
      .value("Auto", CcdMode::Auto)
      .value("Bullet", CcdMode::Bullet);
  py::class_<CollisionFilter>(m, "CollisionFilter",
                              "Which objects pair: (a.layer & b.mask) and (b.layer & a.mask) non-zero, and not the "
                              "same non-zero group.")
      .def(py::init([](std::uint64_t layer, std::uint64_t mask, std::int32_t group) {
             return CollisionFilter{layer, mask, group};
           }),
           py::arg("layer") = 1, py::arg("mask") = ~0ull, py::arg("group") = 0)
      .def_readonly("layer", &CollisionFilter::layer)
      .def_readonly("mask", &CollisionFilter::mask)
      .def_readonly("group", &CollisionFilter::group)
      .def("__eq__", [](const CollisionFilter& a, const CollisionFilter& b) { return a == b; })
      .def("__repr__", [](const CollisionFilter& f) {
        return "CollisionFilter(layer=" + std::to_string(f.layer) + ", mask=" + std::to_string(f.mask) +
               ", group=" + std::to_string(f.group) + ")";
      });
  py::class_<ContactEvent>(m, "ContactEvent", "A pair that began, kept or stopped touching (a < b).")
      .def_property_readonly("a", [](const ContactEvent& e) { return e.pair.a.to_integer(); })
      .def_property_readonly("b", [](const ContactEvent& e) { return e.pair.b.to_integer(); })
      .def_readonly("user_data_a", &ContactEvent::user_data_a)
      .def_readonly("user_data_b", &ContactEvent::user_data_b)
      .def("__repr__", [](const ContactEvent& e) {
        return "ContactEvent(a=" + std::to_string(e.pair.a.to_integer()) +
               ", b=" + std::to_string(e.pair.b.to_integer()) + ")";
      });
  py::class_<SensorEvent>(m, "SensorEvent", "An object that entered or left a sensor.")
      .def_property_readonly("sensor", [](const SensorEvent& e) { return e.sensor.to_integer(); })
      .def_property_readonly("other", [](const SensorEvent& e) { return e.other.to_integer(); })
      .def_readonly("user_data_sensor", &SensorEvent::user_data_sensor)
      .def_readonly("user_data_other", &SensorEvent::user_data_other);
  py::class_<ImpactEvent>(m, "ImpactEvent", "The first impact of a fast object during a step.")
      .def_property_readonly("a", [](const ImpactEvent& e) { return e.a.to_integer(); })
      .def_property_readonly("b", [](const ImpactEvent& e) { return e.b.to_integer(); })
      .def_readonly("toi", &ImpactEvent::toi, "Fraction of the step in [0, 1].")
      .def_property_readonly("point", [](const ImpactEvent& e) { return to_numpy(e.point); })
      .def_property_readonly("normal", [](const ImpactEvent& e) { return to_numpy(e.normal); })
      .def_readonly("user_data_a", &ImpactEvent::user_data_a)
      .def_readonly("user_data_b", &ImpactEvent::user_data_b);
  py::class_<WorldHit>(m, "WorldHit", "An object hit by a ray or a sweep (world frame).")
      .def_property_readonly("object", [](const WorldHit& h) { return h.object.to_integer(); })
      .def_readonly("user_data", &WorldHit::user_data)
      .def_readonly("t", &WorldHit::t, "Ray: parameter; sweep: fraction of the translation.")
      .def_property_readonly("point", [](const WorldHit& h) { return to_numpy(h.point); })
      .def_property_readonly("normal", [](const WorldHit& h) { return to_numpy(h.normal); })
      .def_property_readonly("part", [](const WorldHit& h) { return part_index(h.sub); })
      .def("__repr__", [](const WorldHit& h) {
        return "WorldHit(object=" + std::to_string(h.object.to_integer()) + ", t=" + std::to_string(h.t) + ")";
      });
  py::class_<WorldClosest>(m, "WorldClosest", "The object nearest a point or a shape (world frame).")
      .def_property_readonly("object", [](const WorldClosest& c) { return c.object.to_integer(); })
      .def_readonly("user_data", &WorldClosest::user_data)
      .def_readonly("signed_distance", &WorldClosest::signed_distance)
      .def_property_readonly("point_query", [](const WorldClosest& c) { return to_numpy(c.point_query); })
      .def_property_readonly("point_object", [](const WorldClosest& c) { return to_numpy(c.point_object); })
      .def_property_readonly("normal", [](const WorldClosest& c) { return to_numpy(c.normal); });
  py::class_<ObjectDesc>(m, "ObjectInfo", "What the world holds of one object.")
      .def_property_readonly("geometry", [](const ObjectDesc& d) { return wrap_shape(d.geometry); })
      .def_readonly("pose", &ObjectDesc::pose)
      .def_readonly("kind", &ObjectDesc::kind)
      .def_readonly("filter", &ObjectDesc::filter)
      .def_readonly("sensor", &ObjectDesc::sensor)
      .def_readonly("ccd", &ObjectDesc::ccd)
      .def_readonly("user_data", &ObjectDesc::user_data)
      .def_property_readonly("parent", [](const ObjectDesc& d) -> py::object {
        return d.parent.is_set() ? py::object(py::int_(d.parent.to_integer())) : py::object(py::none());
      });
  PYBIND11_NUMPY_DTYPE(ContactEventRow, a, b, user_data_a, user_data_b);
  PYBIND11_NUMPY_DTYPE(SensorEventRow, sensor, other, user_data_sensor, user_data_other);
  PYBIND11_NUMPY_DTYPE(ImpactEventRow, a, b, toi, point, normal, user_data_a, user_data_b);
  PYBIND11_NUMPY_DTYPE(ContactPointRow, a, b, normal, point_a, point_b, depth, id, persisted);
  PYBIND11_NUMPY_DTYPE(WorldHitRow, hit, object, user_data, t, point, normal);
  PYBIND11_NUMPY_DTYPE(WorldClosestRow, found, object, user_data, signed_distance, point_object, normal);
  m.attr("CONTACT_EVENT_DTYPE") = py::dtype::of<ContactEventRow>();
  m.attr("SENSOR_EVENT_DTYPE") = py::dtype::of<SensorEventRow>();
  m.attr("IMPACT_EVENT_DTYPE") = py::dtype::of<ImpactEventRow>();
  m.attr("CONTACT_POINT_DTYPE") = py::dtype::of<ContactPointRow>();
  m.attr("WORLD_HIT_DTYPE") = py::dtype::of<WorldHitRow>();
  m.attr("WORLD_CLOSEST_DTYPE") = py::dtype::of<WorldClosestRow>();
}

std::uint64_t add_object(PyWorld& w, py::handle geometry, py::handle pose, ObjectKind kind,
                         const CollisionFilter& filter, bool sensor, CcdMode ccd, std::uint64_t user_data,
                         py::handle parent, py::handle local_pose) {
  ObjectDesc d;
  d.geometry = *to_shape(geometry, "geometry").shape;
  d.pose = to_transform(pose, "pose");
  d.kind = kind;
  d.filter = filter;
  d.sensor = sensor;
  d.ccd = ccd;
  d.user_data = user_data;
  if (!parent.is_none()) d.parent = handle_of(parent.cast<std::uint64_t>());
  d.local_pose = to_transform(local_pose, "local_pose");
  return take(w.world->add(d)).to_integer();
}

void move_batch(PyWorld& w, py::handle handles, py::handle poses) {
  const py::array_t<std::uint64_t, py::array::forcecast> h =
      py::array_t<std::uint64_t, py::array::forcecast>::ensure(handles);
  if (!h || h.ndim() != 1) raise_argument_error("objects", "expected a 1-D array of handles");
  const RowReader rows(poses, 7, "poses", false);
  if (rows.rows() != h.shape(0)) raise_argument_error("poses", "needs one row per object");
  const std::vector<Transform> list = read_poses(rows, rows.rows(), "poses");
  std::vector<ObjectMove> moves(list.size());
  for (std::size_t i = 0; i < list.size(); ++i) moves[i] = {handle_of(h.at(static_cast<py::ssize_t>(i))), list[i]};
  check(w.world->move(moves));
}

void step(PyWorld& w, Real dt, long threads) {
  const std::size_t count = resolve_threads(threads);
  std::optional<Error> error;
  {
    py::gil_scoped_release release;
    error = count <= 1 ? w.world->step(dt) : w.world->step(dt, thread_pool(count));
  }
  if (w.recording && !error) check(w.recording->recorder->record_step(*w.world, dt));
  w.listener.raise_pending();
  check(error);
}

}  // namespace
}  // namespace proxima::python

namespace proxima::python {
namespace {

py::array world_raycast_batch(const PyWorld& w, py::handle rays, py::handle max_t, std::uint64_t mask,
                              std::int32_t group, py::handle ignore, long threads) {
  const RowReader r(rays, 6, "rays", false);
  const std::vector<double> limits = read_limits(max_t, r.rows());
  std::vector<WorldRay> list(static_cast<std::size_t>(r.rows()));
  r.find_rejected(0, r.rows(), [&](py::ssize_t i, const auto& number) {
    WorldRay& ray = list[static_cast<std::size_t>(i)];
    ray.origin = {number(0), number(1), number(2)};
    ray.direction = {number(3), number(4), number(5)};
    const double m = limits.size() == 1 ? limits[0] : limits[static_cast<std::size_t>(i)];
    ray.max_t = m > double(kRealMax) ? kRealMax : Real(m);  // the world names a bad ray
    return true;
  });
  std::vector<WorldHit> hits(list.size());
  const QueryFilter filter = query_filter(mask, group, ignore);
  const std::size_t count = resolve_threads(threads);
  Result<std::size_t> done = std::size_t(0);
  {
    py::gil_scoped_release release;
    done = count <= 1 ? w.world->raycast_batch(list, hits, filter)
                      : w.world->raycast_batch(list, hits, filter, thread_pool(count));
  }
  take(std::move(done));
  auto out = rows_of<WorldHitRow>(hits.size());
  WorldHitRow* row = out.mutable_data();
  for (const WorldHit& h : hits) {
    row->hit = h.object.is_set();
    row->object = h.object.to_integer();
    row->user_data = h.user_data;
    row->t = double(h.t);
    put(row->point, h.point);
    put(row->normal, h.normal);
    ++row;
  }
  return out;
}

py::array world_closest_point_batch(const PyWorld& w, py::handle points, Real max_distance, std::uint64_t mask,
                                    std::int32_t group, py::handle ignore, long threads) {
  const std::vector<Vec3> list = read_points(points);
  std::vector<WorldClosest> nearest(list.size());
  const QueryFilter filter = query_filter(mask, group, ignore);
  const std::size_t count = resolve_threads(threads);
  Result<std::size_t> done = std::size_t(0);
  {
    py::gil_scoped_release release;
    done = count <= 1 ? w.world->closest_point_batch(list, max_distance, nearest, filter)
                      : w.world->closest_point_batch(list, max_distance, nearest, filter, thread_pool(count));
  }
  take(std::move(done));
  auto out = rows_of<WorldClosestRow>(nearest.size());
  WorldClosestRow* row = out.mutable_data();
  for (const WorldClosest& c : nearest) {
    row->found = c.object.is_set();
    row->object = c.object.to_integer();
    row->user_data = c.user_data;
    row->signed_distance = double(c.signed_distance);
    put(row->point_object, c.point_object);
    put(row->normal, c.normal);
    ++row;
  }
  return out;
}

template <class C>
C& def_queries(C& c) {
  c.def(
       "raycast",
       [](PyWorld& w, py::handle origin, py::handle direction, Real max_t, std::uint64_t mask, std::int32_t group,
          py::handle ignore, const std::string& mode) {
         const Ray ray{to_vec3(origin, "origin"), to_vec3(direction, "direction")};
         std::vector<WorldHit> hits =
             take(w.world->raycast(ray, max_t, query_filter(mask, group, ignore), query_mode(mode)));
         if (w.recording) w.recording->recorder->record_ray(ray, max_t, hits);
         return hits;
       },
       py::arg("origin"), py::arg("direction"), py::arg("max_t") = Real(1), py::kw_only(), py::arg("mask") = ~0ull,
       py::arg("group") = 0, py::arg("ignore") = py::none(), py::arg("mode") = "closest",
       "Objects hit by the ray within [0, max_t] (t in units of the direction's length): a list of WorldHit, "
       "sorted by t (mode 'closest': at most one; 'any': the first found; 'all': every one).")
      .def(
          "line_of_sight",
          [](const PyWorld& w, py::handle from, py::handle to, std::uint64_t mask, std::int32_t group,
             py::handle ignore) {
            return take(
                w.world->line_of_sight(to_vec3(from, "from"), to_vec3(to, "to"), query_filter(mask, group, ignore)));
          },
          py::arg("from_"), py::arg("to"), py::kw_only(), py::arg("mask") = ~0ull, py::arg("group") = 0,
          py::arg("ignore") = py::none(), "True when nothing the filter sees touches the segment.")
      .def(
          "overlap",
          [](const PyWorld& w, py::handle geometry, py::handle pose, std::uint64_t mask, std::int32_t group,
             py::handle ignore) {
            const auto found = take(w.world->overlap(to_shape(geometry, "geometry").ref(), to_transform(pose, "pose"),
                                                     query_filter(mask, group, ignore)));
            std::vector<std::uint64_t> handles;
            for (const WorldOverlap& o : found) handles.push_back(o.object.to_integer());
            return handles;
          },
          py::arg("geometry"), py::arg("pose") = py::none(), py::kw_only(), py::arg("mask") = ~0ull,
          py::arg("group") = 0, py::arg("ignore") = py::none(),
          "Handles of the objects the placed geometry touches or overlaps, ascending.")
      .def(
          "overlap_box",
          [](const PyWorld& w, const Aabb& box, std::uint64_t mask, std::int32_t group, py::handle ignore) {
            const auto found = take(w.world->overlap_box(box, query_filter(mask, group, ignore)));
            std::vector<std::uint64_t> handles;
            for (const WorldOverlap& o : found) handles.push_back(o.object.to_integer());
            return handles;
          },
          py::arg("box"), py::kw_only(), py::arg("mask") = ~0ull, py::arg("group") = 0, py::arg("ignore") = py::none(),
          "Handles of the objects whose geometry meets the world-frame box.")
      .def(
          "overlap_point",
          [](const PyWorld& w, py::handle point, std::uint64_t mask, std::int32_t group, py::handle ignore) {
            const auto found = take(w.world->overlap_point(to_vec3(point, "point"), query_filter(mask, group, ignore)));
            std::vector<std::uint64_t> handles;
            for (const WorldOverlap& o : found) handles.push_back(o.object.to_integer());
            return handles;
          },
          py::arg("point"), py::kw_only(), py::arg("mask") = ~0ull, py::arg("group") = 0,
          py::arg("ignore") = py::none(), "Handles of the objects containing or touching the point.")
      .def(
          "sweep",
          [](const PyWorld& w, py::handle geometry, py::handle pose, py::handle translation, std::uint64_t mask,
             std::int32_t group, py::handle ignore, const std::string& mode) {
            return take(w.world->sweep(to_shape(geometry, "geometry").ref(), to_transform(pose, "pose"),
                                       to_vec3(translation, "translation"), query_filter(mask, group, ignore),
                                       query_mode(mode)));
          },
          py::arg("geometry"), py::arg("pose"), py::arg("translation"), py::kw_only(), py::arg("mask") = ~0ull,
          py::arg("group") = 0, py::arg("ignore") = py::none(), py::arg("mode") = "closest",
          "Objects hit by the convex geometry moved along translation (t: fraction of it).")
      .def(
          "closest_point",
          [](const PyWorld& w, py::handle point, Real max_distance, std::uint64_t mask, std::int32_t group,
             py::handle ignore) {
            return take(
                w.world->closest_point(to_vec3(point, "point"), max_distance, query_filter(mask, group, ignore)));
          },
          py::arg("point"), py::arg("max_distance"), py::kw_only(), py::arg("mask") = ~0ull, py::arg("group") = 0,
          py::arg("ignore") = py::none(), "The object nearest the point within max_distance, or None.")
      .def(
          "closest",
          [](const PyWorld& w, py::handle geometry, py::handle pose, Real max_distance, std::uint64_t mask,
             std::int32_t group, py::handle ignore) {
            return take(w.world->closest(to_shape(geometry, "geometry").ref(), to_transform(pose, "pose"), max_distance,
                                         query_filter(mask, group, ignore)));
          },
          py::arg("geometry"), py::arg("pose"), py::arg("max_distance"), py::kw_only(), py::arg("mask") = ~0ull,
          py::arg("group") = 0, py::arg("ignore") = py::none(),
          "The object nearest the placed geometry within max_distance, or None.")
      .def("raycast_batch", &world_raycast_batch, py::arg("rays"), py::arg("max_t") = Real(1), py::kw_only(),
           py::arg("mask") = ~0ull, py::arg("group") = 0, py::arg("ignore") = py::none(), py::arg("threads") = 0,
           "The closest hit of each ray of an (N, 6) array (origin, direction): an array of WORLD_HIT_DTYPE "
           "(hit, object, user_data, t, point, normal). The GIL is released; threads as in distance_batch.")
      .def("closest_point_batch", &world_closest_point_batch, py::arg("points"), py::arg("max_distance"), py::kw_only(),
           py::arg("mask") = ~0ull, py::arg("group") = 0, py::arg("ignore") = py::none(), py::arg("threads") = 0,
           "closest_point of each point of an (N, 3) array: an array of WORLD_CLOSEST_DTYPE (found, object, "
           "user_data, signed_distance, point_object, normal).");
  return c;
}

}  // namespace
}  // namespace proxima::python

namespace proxima::python {

void bind_world(py::module_& m) {
  bind_world_types(m);
  using World = py::class_<PyWorld, std::unique_ptr<PyWorld>>;
  World c(m, "CollisionWorld",
          "The collision world: objects by integer handle, a step that reports contacts, sensors and impacts, "
          "scene queries and snapshots. Lengths in the caller's units, poses local -> world.");
  c.def(py::init([](const std::string& broadphase, Real contact_distance, int max_contacts, bool sensors_sense_sensors,
                    bool continuous, Real ccd_safety_factor, Real ccd_tolerance) {
          return wrap_world(
              take(CollisionWorld::create(settings_of(broadphase, contact_distance, max_contacts, sensors_sense_sensors,
                                                      continuous, ccd_safety_factor, ccd_tolerance))));
        }),
        py::arg("broadphase") = "tree", py::arg("contact_distance") = Real(0), py::arg("max_contacts") = 4,
        py::arg("sensors_sense_sensors") = false, py::arg("continuous") = true,
        py::arg("ccd_safety_factor") = Real(0.25), py::arg("ccd_tolerance") = Real(0))
      .def("add", &add_object, py::arg("geometry"), py::arg("pose") = py::none(), py::kw_only(),
           py::arg("kind") = ObjectKind::Moving, py::arg("filter") = CollisionFilter{}, py::arg("sensor") = false,
           py::arg("ccd") = CcdMode::Auto, py::arg("user_data") = 0, py::arg("parent") = py::none(),
           py::arg("local_pose") = py::none(),
           "Adds an object; returns its handle (an int). A half-space or a mesh only as kind=ObjectKind.Static.")
      .def("move_batch", &move_batch, py::arg("objects"), py::arg("poses"),
           "Moves objects[i] to poses[i] ((N, 7) array); all validated first, nothing moved on an error.")
      .def(
          "set_geometry",
          [](PyWorld& w, std::uint64_t h, py::handle g) {
            check(w.world->set_geometry(handle_of(h), *to_shape(g, "geometry").shape));
          },
          py::arg("object"), py::arg("geometry"))
      .def(
          "set_kind", [](PyWorld& w, std::uint64_t h, ObjectKind k) { check(w.world->set_kind(handle_of(h), k)); },
          py::arg("object"), py::arg("kind"))
      .def(
          "set_ccd", [](PyWorld& w, std::uint64_t h, CcdMode k) { check(w.world->set_ccd(handle_of(h), k)); },
          py::arg("object"), py::arg("mode"))
      .def(
          "set_user_data",
          [](PyWorld& w, std::uint64_t h, std::uint64_t d) { check(w.world->set_user_data(handle_of(h), d)); },
          py::arg("object"), py::arg("user_data"))
      .def(
          "attach",
          [](PyWorld& w, std::uint64_t h, std::uint64_t parent, py::handle local) {
            check(w.world->attach(handle_of(h), handle_of(parent), to_transform(local, "local_pose")));
          },
          py::arg("object"), py::arg("parent"), py::arg("local_pose") = py::none(),
          "Attaches the object to parent at local_pose (parent frame); it then moves with it.")
      .def(
          "objects", [](const PyWorld& w) { return handle_array(w.world->objects()); },
          "Handles of every object, as a uint64 array.")
      .def(
          "object",
          [](const PyWorld& w, std::uint64_t h) {
            std::optional<ObjectDesc> d = w.world->object(handle_of(h));
            if (!d) raise_argument_error("object", "no such object");
            return *d;
          },
          py::arg("object"), "What the world holds of the object (ObjectInfo).")
      .def(
          "pose",
          [](const PyWorld& w, std::uint64_t h) {
            if (!w.world->contains(handle_of(h))) raise_argument_error("object", "no such object");
            return w.world->pose(handle_of(h));
          },
          py::arg("object"))
      .def(
          "bounds",
          [](const PyWorld& w, std::uint64_t h) {
            if (!w.world->contains(handle_of(h))) raise_argument_error("object", "no such object");
            return w.world->bounds(handle_of(h));
          },
          py::arg("object"), "The object's world box as the broad phase holds it.")
      .def("step", &step, py::arg("dt"), py::kw_only(), py::arg("threads") = 1,
           "Runs the broad and narrow phases and continuous detection over dt seconds, then calls the listener. "
           "threads: 0 every hardware thread; the GIL is released.")
      .def_property_readonly(
          "events",
          [](const PyWorld& w) { return events_dict(w.world->events(), impact_events(w.world->events().impacts)); },
          "The last step's events: a dict of structured arrays (begin, persist, end: CONTACT_EVENT_DTYPE; "
          "sensor_enter, sensor_exit: SENSOR_EVENT_DTYPE; impacts: IMPACT_EVENT_DTYPE).")
      .def(
          "contacts", [](const PyWorld& w) { return contact_points(w.world->contacts()); },
          "Every contact point of the touching pairs: an array of CONTACT_POINT_DTYPE.")
      .def_property_readonly("step_count", [](const PyWorld& w) { return w.world->step_count(); })
      .def(
          "record",
          [](PyWorld& w, const std::string& path, py::handle camera) {
            w.recording = start_recording<debug::CaptureRecorder>(path, camera);
          },
          py::arg("path"), py::arg("camera") = py::none(),
          "Records every following step to a capture file (docs/capture-format.md; read it with proxima.capture, "
          "draw it with proxima.render or proxima view). camera: a dict of position, target, up, fov_degrees, "
          "ortho_height.")
      .def(
          "stop_recording", [](PyWorld& w) { w.recording.reset(); }, "Closes the capture file.")
      .def("save", &save_world, "The world as a versioned binary snapshot (bytes).")
      .def_static("load", &load_world, py::arg("snapshot"), "A world from save()'s bytes.")
      .def(py::pickle([](const PyWorld& w) { return save_world(w); },
                      [](const py::bytes& data) { return load_world(data); }));
  def_shared_world_calls(c, &to_transform);
  def_queries(c);
}

}  // namespace proxima::python
