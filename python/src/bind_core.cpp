// proxima.Transform, proxima.Aabb and the enumerations shared by the query results.
#include <proxima/ccd/time_of_impact.hpp>
#include <proxima/geometry/aabb.hpp>
#include <proxima/narrowphase/contact.hpp>
#include <proxima/shapes/shape_type.hpp>

#include <pybind11/operators.h>
#include <sstream>

#include "conversions.hpp"
#include "module_parts.hpp"

namespace proxima::python {
namespace {

std::string repr(const Vec3& v) {
  std::ostringstream s;
  s.precision(9);
  s << "(" << v.x << ", " << v.y << ", " << v.z << ")";
  return s.str();
}

void bind_transform(py::module_& m) {
  py::class_<Transform>(m, "Transform",
                        "A rigid placement: local frame -> parent frame. position (length units) and rotation, "
                        "a unit quaternion (x, y, z, w).")
      .def(py::init([](py::handle position, py::handle rotation) {
             return take(Transform::create(to_vec3(position, "position"), to_quat(rotation, "rotation")));
           }),
           py::arg("position") = py::make_tuple(0.0, 0.0, 0.0),
           py::arg("rotation") = py::make_tuple(0.0, 0.0, 0.0, 1.0),
           "A placement; the rotation must be a unit quaternion (x, y, z, w) within 1e-4 and is renormalised.")
      .def_static("identity", &Transform::identity, "The identity placement.")
      .def_property_readonly(
          "position", [](const Transform& t) { return to_numpy(t.position); },
          "Origin of the local frame in the parent frame, shape (3,).")
      .def_property_readonly(
          "rotation", [](const Transform& t) { return to_numpy(t.rotation); },
          "Unit quaternion (x, y, z, w), local -> parent.")
      .def(
          "apply", [](const Transform& t, py::handle p) { return to_numpy(t.apply(to_vec3(p, "point"))); },
          py::arg("point"), "A local point in parent coordinates.")
      .def(
          "apply_vector",
          [](const Transform& t, py::handle v) { return to_numpy(t.apply_vector(to_vec3(v, "vector"))); },
          py::arg("vector"), "A local direction in parent coordinates (rotation only).")
      .def("inverse", &Transform::inverse, "The placement parent -> local.")
      .def(py::self * py::self, "Composition: (a * b).apply(p) == a.apply(b.apply(p)).")
      .def(
          "to_array",
          [](const Transform& t) {
            py::array_t<double> out(7);
            double* d = out.mutable_data();
            for (int i = 0; i < 3; ++i) d[i] = double(t.position[i]);
            d[3] = double(t.rotation.x), d[4] = double(t.rotation.y), d[5] = double(t.rotation.z);
            d[6] = double(t.rotation.w);
            return out;
          },
          "(px, py, pz, qx, qy, qz, qw), the row layout of the batched calls' pose arrays.")
      .def("__repr__",
           [](const Transform& t) {
             const Quat& q = t.rotation;
             std::ostringstream s;
             s.precision(9);
             s << "Transform(position=" << repr(t.position) << ", rotation=(" << q.x << ", " << q.y << ", " << q.z
               << ", " << q.w << "))";
             return s.str();
           })
      .def(py::pickle(
          [](const Transform& t) {
            return py::make_tuple(py::make_tuple(t.position.x, t.position.y, t.position.z),
                                  py::make_tuple(t.rotation.x, t.rotation.y, t.rotation.z, t.rotation.w));
          },
          [](const py::tuple& state) {
            return take(Transform::create(to_vec3(state[0], "position"), to_quat(state[1], "rotation")));
          }));
}

void bind_aabb(py::module_& m) {
  py::class_<Aabb>(m, "Aabb", "An axis-aligned box: min and max corners (length units, the frame of the query).")
      .def(py::init([](py::handle lo, py::handle hi) {
             const Vec3 a = to_vec3(lo, "min"), b = to_vec3(hi, "max");
             if (!(a.x <= b.x && a.y <= b.y && a.z <= b.z)) raise_argument_error("max", "must be >= min componentwise");
             return Aabb{a, b};
           }),
           py::arg("min"), py::arg("max"))
      .def_property_readonly(
          "min", [](const Aabb& b) { return to_numpy(b.min); }, "Smallest corner, shape (3,).")
      .def_property_readonly(
          "max", [](const Aabb& b) { return to_numpy(b.max); }, "Largest corner, shape (3,).")
      .def_property_readonly("center", [](const Aabb& b) { return to_numpy(b.center()); })
      .def_property_readonly("half_extents", [](const Aabb& b) { return to_numpy(b.half_extents()); })
      .def("overlaps", &Aabb::overlaps, py::arg("other"), "True when the closed boxes share a point.")
      .def("__repr__", [](const Aabb& b) { return "Aabb(min=" + repr(b.min) + ", max=" + repr(b.max) + ")"; });
}

void bind_enums(py::module_& m) {
  py::enum_<PairStatus>(m, "PairStatus", "How a pair query ended.")
      .value("Separated", PairStatus::Separated)
      .value("Touching", PairStatus::Touching)
      .value("Penetrating", PairStatus::Penetrating)
      .value("MaxIterations", PairStatus::MaxIterations)
      .value("Degenerate", PairStatus::Degenerate)
      .value("InvalidInput", PairStatus::InvalidInput);
  py::enum_<PairMethod>(m, "PairMethod", "Which algorithm answered a pair query.")
      .value("Analytic", PairMethod::Analytic)
      .value("Gjk", PairMethod::Gjk)
      .value("Epa", PairMethod::Epa)
      .value("Sat", PairMethod::Sat)
      .value("Support", PairMethod::Support)
      .value("ClosestPoint", PairMethod::ClosestPoint);
  py::enum_<CcdStatus>(m, "CcdStatus", "How a time-of-impact or cast query ended.")
      .value("Hit", CcdStatus::Hit)
      .value("Separated", CcdStatus::Separated)
      .value("InitiallyOverlapping", CcdStatus::InitiallyOverlapping)
      .value("MaxIterations", CcdStatus::MaxIterations)
      .value("Failed", CcdStatus::Failed);
}

}  // namespace

std::string repr_vec3(const Vec3& v) { return repr(v); }

std::string repr_real(Real x) {
  std::ostringstream s;
  s.precision(9);
  s << x;
  return s.str();
}

void bind_core(py::module_& m) {
  bind_transform(m);
  bind_aabb(m);
  bind_enums(m);
}

}  // namespace proxima::python
