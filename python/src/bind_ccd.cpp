// Continuous detection: proxima.Motion, toi (certified time of impact), cast (shape cast
// along a translation) and safe_step (the largest step before two moving bodies can touch).
#include <proxima/ccd/motion.hpp>
#include <proxima/ccd/safe_step.hpp>
#include <proxima/ccd/shape_cast.hpp>
#include <proxima/ccd/time_of_impact.hpp>

#include <sstream>

#include "module_parts.hpp"
#include "shape_object.hpp"

namespace proxima::python {
namespace {

/// A motion from a proxima.Motion, a pose (stationary) or a (start, end) pair of poses.
Motion to_motion(py::handle value, const char* field) {
  if (py::isinstance<Motion>(value)) return value.cast<Motion>();
  if (value.is_none() || py::isinstance<Transform>(value)) return Motion::stationary(to_transform(value, field));
  if (py::isinstance<py::sequence>(value) && py::len(value) == 2) {
    const py::sequence pair = value.cast<py::sequence>();
    return {to_transform(pair[0], (std::string(field) + ".start").c_str()),
            to_transform(pair[1], (std::string(field) + ".end").c_str())};
  }
  return Motion::stationary(to_transform(value, field));
}

void bind_results(py::module_& m) {
  py::class_<Motion>(m, "Motion",
                     "A rigid motion over the unit time interval: start at t = 0, end at t = 1 "
                     "(screw interpolation: constant linear and angular velocity).")
      .def(py::init([](py::handle start, py::handle end) {
             const Motion motion{to_transform(start, "start"), to_transform(end, "end")};
             check(validate_motion(motion, "motion"));
             return motion;
           }),
           py::arg("start"), py::arg("end"))
      .def_static(
          "from_velocity",
          [](py::handle pose, py::handle linear, py::handle angular, Real dt) {
            if (!(dt > Real(0))) raise_error(make_error(ErrorCode::NonPositive, "dt", "must be > 0"));
            return Motion::from_velocity(to_transform(pose, "pose"), to_vec3(linear, "linear"),
                                         to_vec3(angular, "angular"), dt);
          },
          py::arg("pose"), py::arg("linear"), py::arg("angular"), py::arg("dt"),
          "The motion over dt seconds at linear (length/s) and angular (rad/s, world frame) velocity.")
      .def_readonly("start", &Motion::start)
      .def_readonly("end", &Motion::end)
      .def("at", &Motion::at, py::arg("t"), "The placement at t in [0, 1].")
      .def("__repr__", [](const Motion& mo) {
        return "Motion(start=" + repr_vec3(mo.start.position) + ", end=" + repr_vec3(mo.end.position) + ")";
      });
  py::class_<ToiResult>(m, "ToiResult", "The first time two moving shapes come within the target distance.")
      .def_readonly("status", &ToiResult::status)
      .def_readonly("toi", &ToiResult::toi, "Time of impact in [0, 1] (1: none).")
      .def_readonly("t_lower", &ToiResult::t_lower, "Certified apart on [0, t_lower].")
      .def_readonly("t_upper", &ToiResult::t_upper, "Within target distance + tolerance at t_upper.")
      .def_readonly("distance", &ToiResult::distance)
      .def_readonly("depth", &ToiResult::depth, "InitiallyOverlapping: penetration at t = 0.")
      .def_property_readonly("point", [](const ToiResult& r) { return to_numpy(r.point); })
      .def_property_readonly("point_a", [](const ToiResult& r) { return to_numpy(r.point_a); })
      .def_property_readonly("point_b", [](const ToiResult& r) { return to_numpy(r.point_b); })
      .def_property_readonly(
          "normal", [](const ToiResult& r) { return to_numpy(r.normal); }, "Unit, from A to B.")
      .def_readonly("iterations", &ToiResult::iterations)
      .def_property_readonly("part_a", [](const ToiResult& r) { return part_index(r.sub_a); })
      .def_property_readonly("part_b", [](const ToiResult& r) { return part_index(r.sub_b); })
      .def_property_readonly(
          "hit",
          [](const ToiResult& r) { return r.status == CcdStatus::Hit || r.status == CcdStatus::InitiallyOverlapping; })
      .def("__repr__", [](const ToiResult& r) {
        return std::string("ToiResult(status=") + to_string(r.status) + ", toi=" + repr_real(r.toi) + ")";
      });
  py::class_<CastResult>(m, "CastResult", "Where a shape moved along a translation first meets another.")
      .def_readonly("status", &CastResult::status)
      .def_readonly("t", &CastResult::t, "Fraction of the translation at the hit (1: no hit).")
      .def_readonly("distance", &CastResult::distance)
      .def_readonly("depth", &CastResult::depth)
      .def_property_readonly("point", [](const CastResult& r) { return to_numpy(r.point); })
      .def_property_readonly("point_a", [](const CastResult& r) { return to_numpy(r.point_a); })
      .def_property_readonly("point_b", [](const CastResult& r) { return to_numpy(r.point_b); })
      .def_property_readonly(
          "normal", [](const CastResult& r) { return to_numpy(r.normal); }, "Unit, from A to B.")
      .def_readonly("iterations", &CastResult::iterations)
      .def_property_readonly("part_a", [](const CastResult& r) { return part_index(r.sub_a); })
      .def_property_readonly("part_b", [](const CastResult& r) { return part_index(r.sub_b); })
      .def_property_readonly(
          "hit",
          [](const CastResult& r) { return r.status == CcdStatus::Hit || r.status == CcdStatus::InitiallyOverlapping; })
      .def("__repr__", [](const CastResult& r) {
        return std::string("CastResult(status=") + to_string(r.status) + ", t=" + repr_real(r.t) + ")";
      });
}

}  // namespace

void bind_ccd(py::module_& m) {
  bind_results(m);
  m.def(
      "toi",
      [](py::handle a, py::handle motion_a, py::handle b, py::handle motion_b, Real target_distance, Real tolerance,
         int max_iterations) {
        const PyShape& sa = to_shape(a, "a");
        const PyShape& sb = to_shape(b, "b");
        const Motion ma = to_motion(motion_a, "motion_a"), mb = to_motion(motion_b, "motion_b");
        ToiOptions options;
        options.target_distance = target_distance;
        options.tolerance = tolerance;
        options.max_iterations = max_iterations;
        std::optional<Result<ToiResult>> r;
        {
          py::gil_scoped_release release;
          r.emplace(time_of_impact(sa.ref(), ma, sb.ref(), mb, options));
        }
        return take(std::move(*r));
      },
      py::arg("a"), py::arg("motion_a"), py::arg("b"), py::arg("motion_b"), py::arg("target_distance") = Real(0),
      py::arg("tolerance") = Real(1e-4), py::arg("max_iterations") = 1024,
      "Certified time of impact of a moving along motion_a and b along motion_b (each a Motion, a pose for a "
      "stationary shape, or a (start, end) pair of poses).");
  m.def(
      "cast",
      [](py::handle a, py::handle pose_a, py::handle translation, py::handle b, py::handle pose_b, Real target_distance,
         Real tolerance, int max_iterations) {
        const PyShape& sa = to_shape(a, "a");
        const PyShape& sb = to_shape(b, "b");
        const Transform pa = to_transform(pose_a, "pose_a"), pb = to_transform(pose_b, "pose_b");
        const Vec3 d = to_vec3(translation, "translation");
        CastOptions options;
        options.target_distance = target_distance;
        options.tolerance = tolerance;
        options.max_iterations = max_iterations;
        std::optional<Result<CastResult>> r;
        {
          py::gil_scoped_release release;
          r.emplace(shape_cast(sa.ref(), pa, d, sb.ref(), pb, options));
        }
        return take(std::move(*r));
      },
      py::arg("a"), py::arg("pose_a"), py::arg("translation"), py::arg("b"), py::arg("pose_b"),
      py::arg("target_distance") = Real(0), py::arg("tolerance") = Real(1e-4), py::arg("max_iterations") = 64,
      "Cast a (convex, or a compound of convex parts) from pose_a along translation against b at pose_b.");
  m.def(
      "safe_step",
      [](py::handle a, py::handle pose_a, py::handle linear_a, py::handle angular_a, py::handle b, py::handle pose_b,
         py::handle linear_b, py::handle angular_b, Real target_distance) {
        const MovingBody ba{to_shape(a, "a").ref(), to_transform(pose_a, "pose_a"), to_vec3(linear_a, "linear_a"),
                            to_vec3(angular_a, "angular_a")};
        const MovingBody bb{to_shape(b, "b").ref(), to_transform(pose_b, "pose_b"), to_vec3(linear_b, "linear_b"),
                            to_vec3(angular_b, "angular_b")};
        return take(safe_time_step(ba, bb, target_distance));
      },
      py::arg("a"), py::arg("pose_a"), py::arg("linear_a"), py::arg("angular_a"), py::arg("b"), py::arg("pose_b"),
      py::arg("linear_b") = py::make_tuple(0.0, 0.0, 0.0), py::arg("angular_b") = py::make_tuple(0.0, 0.0, 0.0),
      py::arg("target_distance") = Real(0),
      "Seconds both bodies may move at their velocities (length/s, rad/s) before they can come within "
      "target_distance (conservative; infinity when never).");
}

}  // namespace proxima::python
