// Bounding-volume fitting on numpy point clouds: fit_aabb, fit_sphere (exact minimal ball by
// default), fit_obb (minimum-volume box by default), fit_capsule, fit_hull; and the fitted
// volumes' classes with their fields (frame of the points).
#include <proxima/bounds/fit_aabb.hpp>
#include <proxima/bounds/fit_capsule.hpp>
#include <proxima/bounds/fit_obb.hpp>
#include <proxima/bounds/fit_sphere.hpp>

#include <string>

#include "module_parts.hpp"
#include "shape_object.hpp"

namespace proxima::python {
namespace {

SphereFit sphere_method(const std::string& name) {
  if (name == "minimal") return SphereFit::Minimal;
  if (name == "ritter") return SphereFit::Ritter;
  if (name == "centroid") return SphereFit::Centroid;
  if (name == "aabb_center") return SphereFit::AabbCenter;
  raise_argument_error("method", "expected 'minimal', 'ritter', 'centroid' or 'aabb_center'");
}

ObbFit obb_method(const std::string& name) {
  if (name == "min_volume") return ObbFit::MinVolume;
  if (name == "pca") return ObbFit::Pca;
  if (name == "dito14") return ObbFit::Dito14;
  if (name == "dito26") return ObbFit::Dito26;
  raise_argument_error("method", "expected 'min_volume', 'pca', 'dito14' or 'dito26'");
}

}  // namespace

void bind_bounds(py::module_& m) {
  py::class_<BoundingSphere>(m, "BoundingSphere", "A closed ball (frame of the fitted points).")
      .def_property_readonly("center", [](const BoundingSphere& s) { return to_numpy(s.center); })
      .def_readonly("radius", &BoundingSphere::radius)
      .def("__repr__", [](const BoundingSphere& s) {
        return "BoundingSphere(center=" + repr_vec3(s.center) + ", radius=" + std::to_string(s.radius) + ")";
      });
  py::class_<Obb>(m, "Obb", "An oriented box: center, axes (rows: unit box axes), half extents.")
      .def_property_readonly("center", [](const Obb& b) { return to_numpy(b.center); })
      .def_property_readonly("axes",
                             [](const Obb& b) {
                               py::array_t<double> out({3, 3});
                               auto a = out.mutable_unchecked<2>();
                               for (int i = 0; i < 3; ++i)
                                 for (int k = 0; k < 3; ++k) a(i, k) = double(b.axes[i][k]);
                               return out;
                             })
      .def_property_readonly("half_extents", [](const Obb& b) { return to_numpy(b.half_extents); })
      .def("__repr__", [](const Obb& b) {
        return "Obb(center=" + repr_vec3(b.center) + ", half_extents=" + repr_vec3(b.half_extents) + ")";
      });
  py::class_<BoundingCapsule>(m, "BoundingCapsule", "Points within radius of the segment p0-p1.")
      .def_property_readonly("p0", [](const BoundingCapsule& c) { return to_numpy(c.p0); })
      .def_property_readonly("p1", [](const BoundingCapsule& c) { return to_numpy(c.p1); })
      .def_readonly("radius", &BoundingCapsule::radius);
  m.def(
      "fit_aabb", [](py::handle points) { return take(fit_aabb(to_points(points, "points"))); }, py::arg("points"),
      "The smallest axis-aligned box of an (N, 3) point array.");
  m.def(
      "fit_sphere",
      [](py::handle points, const std::string& method) {
        return take(fit_sphere(to_points(points, "points"), sphere_method(method)));
      },
      py::arg("points"), py::arg("method") = "minimal",
      "A ball enclosing the points: 'minimal' (exact smallest), 'ritter', 'centroid' or 'aabb_center'.");
  m.def(
      "fit_obb",
      [](py::handle points, const std::string& method) {
        return take(fit_obb(to_points(points, "points"), obb_method(method)));
      },
      py::arg("points"), py::arg("method") = "min_volume",
      "An oriented box enclosing the points: 'min_volume', 'pca', 'dito14' or 'dito26'.");
  m.def(
      "fit_capsule", [](py::handle points) { return take(fit_capsule(to_points(points, "points"))); },
      py::arg("points"), "A capsule enclosing the points.");
  m.def(
      "fit_hull",
      [](py::handle points) { return wrap_shape(Shape(take(ConvexHull::create(to_points(points, "points"))))); },
      py::arg("points"), "The convex hull of the points (a proxima.ConvexHull).");
}

}  // namespace proxima::python
