// proxima.d2, the 2D module: shapes (point, circle, segment, capsule, convex polygon and box
// with an optional rounding radius, one-sided chains) made by factory functions, poses as
// (x, y, angle in radians), and the pair queries, ray casts, point queries, time of impact
// and shape casts. Vectors come back as float64 arrays of shape (2,).
#include <proxima/d2/narrowphase.hpp>
#include <proxima/d2/time_of_impact.hpp>

#include <limits>
#include <pybind11/stl.h>
#include <sstream>

#include "d2_conversions.hpp"
#include "module_parts.hpp"

namespace proxima::python {

d2::Vec2 to_vec2(py::handle v, const char* field) {
  const std::vector<double> n = to_numbers(v, 2, field);
  return {Real(n[0]), Real(n[1])};
}

py::array_t<double> to_numpy2(const d2::Vec2& v) {
  py::array_t<double> out(2);
  out.mutable_data()[0] = double(v.x), out.mutable_data()[1] = double(v.y);
  return out;
}

d2::Pose to_pose2(py::handle v, const char* field) {
  if (v.is_none()) return d2::Pose::identity();
  const std::vector<double> n = to_numbers(v, 3, field);
  Result<d2::Pose> p = d2::Pose::create({Real(n[0]), Real(n[1])}, Real(n[2]));
  if (!p.ok()) {
    Error e = p.error();
    e.field = std::string(field) + "." + e.field;
    raise_error(e);
  }
  return *p;
}

std::vector<d2::Vec2> to_points2(py::handle v, const char* field) {
  const auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(v);
  if (!a || a.ndim() != 2 || a.shape(1) != 2) raise_argument_error(field, "expected an (N, 2) array of numbers");
  std::vector<d2::Vec2> points(static_cast<std::size_t>(a.shape(0)));
  for (std::size_t i = 0; i < points.size(); ++i) points[i] = {Real(a.data()[2 * i]), Real(a.data()[2 * i + 1])};
  return points;
}

const d2::Shape& to_shape2(py::handle v, const char* field) {
  if (!py::isinstance<d2::Shape>(v)) raise_argument_error(field, "expected a proxima.d2.Shape");
  return v.cast<const d2::Shape&>();
}

namespace {

using D2Shape = d2::Shape;

template <class S>
D2Shape make(Result<S>&& r) {
  return D2Shape(take(std::move(r)));
}

void bind_d2_types(py::module_& d) {
  py::class_<D2Shape>(d, "Shape", "A 2D geometry (immutable); made by proxima.d2.Circle, Polygon, Box, ...")
      .def_property_readonly("type", [](const D2Shape& s) { return d2::to_string(s.type()); })
      .def_property_readonly("is_convex", &D2Shape::is_convex)
      .def(
          "aabb",
          [](const D2Shape& s, py::handle pose) {
            const d2::Aabb b = s.world_aabb(to_pose2(pose, "pose"));
            return py::make_tuple(to_numpy2(b.min), to_numpy2(b.max));
          },
          py::arg("pose") = py::none(), "(min, max) corners of the placed shape's box.")
      .def("__repr__", [](const D2Shape& s) { return std::string("d2.Shape(") + d2::to_string(s.type()) + ")"; });
  py::class_<d2::DistanceResult>(d, "DistanceResult", "2D separation or penetration (world frame).")
      .def_readonly("signed_distance", &d2::DistanceResult::signed_distance)
      .def_property_readonly("point_a", [](const d2::DistanceResult& r) { return to_numpy2(r.point_a); })
      .def_property_readonly("point_b", [](const d2::DistanceResult& r) { return to_numpy2(r.point_b); })
      .def_property_readonly("normal", [](const d2::DistanceResult& r) { return to_numpy2(r.normal); })
      .def_readonly("status", &d2::DistanceResult::status)
      .def_readonly("part_a", &d2::DistanceResult::part_a, "Chain segment of A (-1: convex).")
      .def_readonly("part_b", &d2::DistanceResult::part_b)
      .def("__repr__", [](const d2::DistanceResult& r) {
        return "d2.DistanceResult(signed_distance=" + repr_real(r.signed_distance) + ")";
      });
  py::class_<d2::Manifold>(d, "Manifold", "Up to 2 contact points sharing one normal (world frame).")
      .def_property_readonly("normal", [](const d2::Manifold& m) { return to_numpy2(m.normal); })
      .def_property_readonly(
          "points",
          [](const d2::Manifold& m) {
            py::list l;
            for (int i = 0; i < m.count; ++i) {
              const d2::ContactPoint& p = m.points[static_cast<std::size_t>(i)];
              l.append(py::dict(py::arg("point_a") = to_numpy2(p.point_a), py::arg("point_b") = to_numpy2(p.point_b),
                                py::arg("depth") = p.depth, py::arg("feature_id") = p.feature_id));
            }
            return l;
          })
      .def("__len__", [](const d2::Manifold& m) { return m.count; })
      .def("__repr__", [](const d2::Manifold& m) { return "d2.Manifold(points=" + std::to_string(m.count) + ")"; });
  py::class_<d2::RayHit>(d, "RayHit", "Where a 2D ray meets a shape.")
      .def_readonly("t", &d2::RayHit::t)
      .def_property_readonly("point", [](const d2::RayHit& h) { return to_numpy2(h.point); })
      .def_property_readonly("normal", [](const d2::RayHit& h) { return to_numpy2(h.normal); })
      .def_readonly("part", &d2::RayHit::part)
      .def("__repr__", [](const d2::RayHit& h) { return "d2.RayHit(t=" + repr_real(h.t) + ")"; });
  py::class_<d2::ToiResult>(d, "ToiResult", "2D time of impact (world frame at toi).")
      .def_readonly("status", &d2::ToiResult::status)
      .def_readonly("toi", &d2::ToiResult::toi)
      .def_readonly("t_lower", &d2::ToiResult::t_lower)
      .def_readonly("t_upper", &d2::ToiResult::t_upper)
      .def_property_readonly("point", [](const d2::ToiResult& r) { return to_numpy2(r.point); })
      .def_property_readonly("normal", [](const d2::ToiResult& r) { return to_numpy2(r.normal); })
      .def("__repr__", [](const d2::ToiResult& r) {
        return std::string("d2.ToiResult(status=") + to_string(r.status) + ", toi=" + repr_real(r.toi) + ")";
      });
}

void bind_d2_shapes(py::module_& d) {
  d.def(
      "Point", [](py::handle p) { return make(d2::Point::create(to_vec2(p, "position"))); },
      py::arg("position") = py::make_tuple(0.0, 0.0), "A point at position (local frame).");
  d.def(
      "Circle", [](Real r, py::handle c) { return make(d2::Circle::create(r, to_vec2(c, "center"))); },
      py::arg("radius"), py::arg("center") = py::make_tuple(0.0, 0.0), "A disc of radius about center (local frame).");
  d.def(
      "Segment", [](py::handle a, py::handle b) { return make(d2::Segment::create(to_vec2(a, "a"), to_vec2(b, "b"))); },
      py::arg("a"), py::arg("b"), "The segment from a to b (local frame); a != b.");
  d.def(
      "Capsule",
      [](py::handle a, py::handle b, Real r) { return make(d2::Capsule::create(to_vec2(a, "a"), to_vec2(b, "b"), r)); },
      py::arg("a"), py::arg("b"), py::arg("radius"), "Points within radius of the segment a-b (local frame).");
  d.def(
      "Polygon",
      [](py::handle points, Real radius) {
        const std::vector<d2::Vec2> p = to_points2(points, "points");
        return make(d2::Polygon::create(p, radius));
      },
      py::arg("points"), py::arg("radius") = Real(0), "The convex hull of 3 to 16 points, optionally rounded.");
  d.def(
      "Box", [](Real hx, Real hy, Real radius) { return make(d2::Polygon::box(hx, hy, radius)); }, py::arg("hx"),
      py::arg("hy"), py::arg("radius") = Real(0), "A box of half extents hx, hy centred on the origin.");
  d.def(
      "Chain",
      [](py::handle points, bool loop) {
        const std::vector<d2::Vec2> p = to_points2(points, "points");
        return make(d2::Chain::create(p, loop));
      },
      py::arg("points"), py::arg("loop") = false,
      "One-sided segments through the points (the right side collides: the outside of a counter-clockwise loop).");
}

void bind_d2_queries(py::module_& d) {
  d.def(
      "distance",
      [](py::handle a, py::handle pa, py::handle b, py::handle pb) {
        return d2::distance(to_shape2(a, "a"), to_pose2(pa, "pose_a"), to_shape2(b, "b"), to_pose2(pb, "pose_b"));
      },
      py::arg("a"), py::arg("pose_a"), py::arg("b"), py::arg("pose_b"),
      "Signed distance with witness points and the unit normal from A to B (world frame).");
  d.def(
      "intersect",
      [](py::handle a, py::handle pa, py::handle b, py::handle pb) {
        return d2::intersect(to_shape2(a, "a"), to_pose2(pa, "pose_a"), to_shape2(b, "b"), to_pose2(pb, "pose_b"));
      },
      py::arg("a"), py::arg("pose_a"), py::arg("b"), py::arg("pose_b"),
      "True when the placed shapes touch or overlap.");
  d.def(
      "collide",
      [](py::handle a, py::handle pa, py::handle b, py::handle pb, Real contact_distance) {
        if (!(contact_distance >= Real(0))) raise_argument_error("contact_distance", "must be >= 0");
        return d2::collide(to_shape2(a, "a"), to_pose2(pa, "pose_a"), to_shape2(b, "b"), to_pose2(pb, "pose_b"),
                           contact_distance);
      },
      py::arg("a"), py::arg("pose_a"), py::arg("b"), py::arg("pose_b"), py::arg("contact_distance") = Real(0),
      "The contact manifold (up to 2 points) of shapes touching, overlapping or within contact_distance.");
  d.def(
      "raycast",
      [](py::handle s, py::handle pose, py::handle origin, py::handle direction, Real max_t) {
        const d2::Ray ray{to_vec2(origin, "origin"), to_vec2(direction, "direction")};
        if (ray.direction == d2::Vec2(Real(0))) raise_argument_error("direction", "must not be zero");
        return d2::raycast(to_shape2(s, "shape"), to_pose2(pose, "pose"), ray, max_t);
      },
      py::arg("shape"), py::arg("pose"), py::arg("origin"), py::arg("direction"),
      py::arg("max_t") = std::numeric_limits<Real>::max(), "The first hit with t in [0, max_t], or None.");
  d.def(
      "contains",
      [](py::handle s, py::handle pose, py::handle p) {
        return d2::contains(to_shape2(s, "shape"), to_pose2(pose, "pose"), to_vec2(p, "point"));
      },
      py::arg("shape"), py::arg("pose"), py::arg("point"), "True when the placed shape contains the point.");
  d.def(
      "toi",
      [](py::handle a, py::handle start_a, py::handle translation_a, Real rotation_a, py::handle b, py::handle start_b,
         py::handle translation_b, Real rotation_b, Real target_distance, Real tolerance) {
        const d2::Motion ma{to_pose2(start_a, "start_a"), to_vec2(translation_a, "translation_a"), rotation_a};
        const d2::Motion mb{to_pose2(start_b, "start_b"), to_vec2(translation_b, "translation_b"), rotation_b};
        d2::ToiOptions o;
        o.target_distance = target_distance;
        o.tolerance = tolerance;
        return take(d2::time_of_impact(to_shape2(a, "a"), ma, to_shape2(b, "b"), mb, o));
      },
      py::arg("a"), py::arg("start_a"), py::arg("translation_a"), py::arg("rotation_a"), py::arg("b"),
      py::arg("start_b"), py::arg("translation_b") = py::make_tuple(0.0, 0.0), py::arg("rotation_b") = Real(0),
      py::arg("target_distance") = Real(0), py::arg("tolerance") = Real(1e-4),
      "Certified time of impact in [0, 1]: each shape moves from its start pose (x, y, angle) by a translation "
      "and a counter-clockwise turn (radians).");
  d.def(
      "cast",
      [](py::handle a, py::handle pa, py::handle translation, py::handle b, py::handle pb) {
        return take(d2::shape_cast(to_shape2(a, "a"), to_pose2(pa, "pose_a"), to_vec2(translation, "translation"),
                                   to_shape2(b, "b"), to_pose2(pb, "pose_b")));
      },
      py::arg("a"), py::arg("pose_a"), py::arg("translation"), py::arg("b"), py::arg("pose_b"),
      "Where a, moved from pose_a along translation (t in [0, 1]), first meets b at rest.");
}

}  // namespace

void bind_d2(py::module_& m) {
  py::module_ d = m.def_submodule("d2", "The 2D module: poses are (x, y, angle in radians).");
  bind_d2_types(d);
  bind_d2_shapes(d);
  bind_d2_queries(d);
}

}  // namespace proxima::python
