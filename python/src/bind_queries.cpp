// Pair queries on two placed shapes: intersect, distance, collide (contact manifolds) and the
// module-level raycast; their result classes with named fields.
#include <proxima/narrowphase/narrowphase.hpp>

#include <limits>
#include <sstream>

#include "module_parts.hpp"
#include "shape_object.hpp"

namespace proxima::python {
namespace {

const char* status_name(PairStatus s) {
  switch (s) {
    case PairStatus::Separated: return "Separated";
    case PairStatus::Touching: return "Touching";
    case PairStatus::Penetrating: return "Penetrating";
    case PairStatus::MaxIterations: return "MaxIterations";
    case PairStatus::Degenerate: return "Degenerate";
    case PairStatus::InvalidInput: return "InvalidInput";
  }
  return "?";
}

/// The pair request of the keyword arguments, validated.
PairRequest make_request(int max_contacts, Real contact_distance, Real tolerance, int max_iterations) {
  if (max_contacts < 1 || max_contacts > kMaxContactPoints)
    raise_error(make_error(ErrorCode::OutOfRange, "max_contacts", "must be in [1, 4]"));
  if (!(contact_distance >= Real(0)) || !std::isfinite(contact_distance))
    raise_error(make_error(ErrorCode::Negative, "contact_distance", "must be finite and >= 0"));
  if (!(tolerance >= Real(0)) || !std::isfinite(tolerance))
    raise_error(make_error(ErrorCode::Negative, "tolerance", "must be finite and >= 0"));
  if (max_iterations < 1) raise_error(make_error(ErrorCode::NonPositive, "max_iterations", "must be >= 1"));
  PairRequest r;
  r.max_contacts = max_contacts;
  r.contact_distance = contact_distance;
  r.tolerance = tolerance;
  r.max_iterations = max_iterations;
  return r;
}

struct Pair {
  const PyShape& a;
  Transform pose_a;
  const PyShape& b;
  Transform pose_b;
};

Pair read_pair(py::handle a, py::handle pose_a, py::handle b, py::handle pose_b) {
  return {to_shape(a, "a"), to_transform(pose_a, "pose_a"), to_shape(b, "b"), to_transform(pose_b, "pose_b")};
}

void bind_results(py::module_& m) {
  py::class_<DistanceResult>(m, "DistanceResult", "Separation or penetration of two placed shapes (world frame).")
      .def_readonly("signed_distance", &DistanceResult::signed_distance, "> 0 gap, < 0 penetration (length units).")
      .def_property_readonly(
          "point_a", [](const DistanceResult& r) { return to_numpy(r.point_a); }, "Witness on A's surface.")
      .def_property_readonly(
          "point_b", [](const DistanceResult& r) { return to_numpy(r.point_b); }, "Witness on B's surface.")
      .def_property_readonly(
          "normal", [](const DistanceResult& r) { return to_numpy(r.normal); }, "Unit, from A to B.")
      .def_readonly("status", &DistanceResult::status)
      .def_readonly("method", &DistanceResult::method)
      .def_readonly("iterations", &DistanceResult::iterations)
      .def_property_readonly("part_a", [](const DistanceResult& r) { return part_index(r.sub_a); })
      .def_property_readonly("part_b", [](const DistanceResult& r) { return part_index(r.sub_b); })
      .def("__repr__", [](const DistanceResult& r) {
        return "DistanceResult(signed_distance=" + repr_real(r.signed_distance) + ", status=" + status_name(r.status) +
               ", normal=" + repr_vec3(r.normal) + ")";
      });
  py::class_<ContactPoint>(m, "ContactPoint", "One point of a contact manifold (world frame).")
      .def_property_readonly("point_a", [](const ContactPoint& c) { return to_numpy(c.point_a); })
      .def_property_readonly("point_b", [](const ContactPoint& c) { return to_numpy(c.point_b); })
      .def_property_readonly("normal", [](const ContactPoint& c) { return to_numpy(c.normal); })
      .def_readonly("depth", &ContactPoint::depth, "Penetration (> 0) or speculative gap (< 0), length units.")
      .def_readonly("feature_id", &ContactPoint::feature_id, "Stable id of the features in contact.")
      .def_property_readonly("part_a", [](const ContactPoint& c) { return part_index(c.sub_a); })
      .def_property_readonly("part_b", [](const ContactPoint& c) { return part_index(c.sub_b); })
      .def("__repr__", [](const ContactPoint& c) {
        return "ContactPoint(point_a=" + repr_vec3(c.point_a) + ", depth=" + repr_real(c.depth) + ")";
      });
  py::class_<ContactManifold>(m, "ContactManifold", "Up to 4 contact points sharing one normal (world frame).")
      .def_property_readonly("points",
                             [](const ContactManifold& mf) {
                               py::list l;
                               for (int i = 0; i < mf.count; ++i) l.append(mf.points[static_cast<std::size_t>(i)]);
                               return l;
                             })
      .def_property_readonly(
          "normal", [](const ContactManifold& mf) { return to_numpy(mf.normal); }, "Unit, from A to B.")
      .def_readonly("status", &ContactManifold::status)
      .def_readonly("method", &ContactManifold::method)
      .def("__len__", [](const ContactManifold& mf) { return mf.count; })
      .def("__repr__", [](const ContactManifold& mf) {
        return "ContactManifold(points=" + std::to_string(mf.count) + ", normal=" + repr_vec3(mf.normal) +
               ", status=" + status_name(mf.status) + ")";
      });
}

}  // namespace

void bind_queries(py::module_& m) {
  bind_results(m);
  m.def(
      "intersect",
      [](py::handle a, py::handle pose_a, py::handle b, py::handle pose_b) {
        const Pair p = read_pair(a, pose_a, b, pose_b);
        return intersect(p.a.ref(), p.pose_a, p.b.ref(), p.pose_b);
      },
      py::arg("a"), py::arg("pose_a"), py::arg("b"), py::arg("pose_b"),
      "True when shape a at pose_a and shape b at pose_b touch or overlap.");
  m.def(
      "distance",
      [](py::handle a, py::handle pose_a, py::handle b, py::handle pose_b, Real tolerance, int max_iterations) {
        const Pair p = read_pair(a, pose_a, b, pose_b);
        return distance(p.a.ref(), p.pose_a, p.b.ref(), p.pose_b, make_request(4, Real(0), tolerance, max_iterations));
      },
      py::arg("a"), py::arg("pose_a"), py::arg("b"), py::arg("pose_b"), py::arg("tolerance") = Real(0),
      py::arg("max_iterations") = 128,
      "Signed distance with witness points and normal (penetration depth when overlapping).");
  m.def(
      "collide",
      [](py::handle a, py::handle pose_a, py::handle b, py::handle pose_b, int max_contacts, Real contact_distance) {
        const Pair p = read_pair(a, pose_a, b, pose_b);
        return collide(p.a.ref(), p.pose_a, p.b.ref(), p.pose_b,
                       make_request(max_contacts, contact_distance, Real(0), 128));
      },
      py::arg("a"), py::arg("pose_a"), py::arg("b"), py::arg("pose_b"), py::arg("max_contacts") = 4,
      py::arg("contact_distance") = Real(0),
      "The contact manifold: points where the shapes touch, overlap, or are within contact_distance.");
  m.def(
      "raycast",
      [](py::handle shape, py::handle pose, py::handle origin, py::handle direction, Real max_t) {
        return py::cast(&to_shape(shape, "shape")).attr("raycast")(origin, direction, max_t, pose);
      },
      py::arg("shape"), py::arg("pose"), py::arg("origin"), py::arg("direction"),
      py::arg("max_t") = std::numeric_limits<Real>::max(), "Shape.raycast as a function: the first hit or None.");
}

}  // namespace proxima::python
