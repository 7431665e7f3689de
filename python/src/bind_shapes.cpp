// proxima.Shape and its subclasses, one per geometry kind: validated constructors (errors as
// proxima.Error naming the field), read-only dimensions, point and ray queries, bounds, mass
// properties, pickling by constructor arguments.
#include <proxima/shapes/placed.hpp>
#include <proxima/shapes/shape_queries.hpp>

#include <limits>
#include <pybind11/stl.h>
#include <sstream>

#include "module_parts.hpp"
#include "shape_object.hpp"

namespace proxima::python {
namespace {

template <class S>
py::object make(Result<S>&& result) {
  return wrap_shape(Shape(take(std::move(result))));
}

/// vertices as an (N, 3) float64 array.
py::array_t<double> points_array(std::span<const Vec3> points) {
  py::array_t<double> out({static_cast<py::ssize_t>(points.size()), py::ssize_t(3)});
  auto a = out.mutable_unchecked<2>();
  for (std::size_t i = 0; i < points.size(); ++i) {
    for (int k = 0; k < 3; ++k) a(static_cast<py::ssize_t>(i), k) = double(points[i][k]);
  }
  return out;
}

std::vector<TriangleIndices> to_triangles(py::handle value, const char* field) {
  py::array_t<std::int64_t, py::array::c_style | py::array::forcecast> a;
  try {
    a = py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>::ensure(value);
  } catch (const py::error_already_set&) {
  }
  if (!a || a.ndim() != 2 || a.shape(1) != 3) raise_argument_error(field, "expected an (M, 3) array of indices");
  std::vector<TriangleIndices> triangles(static_cast<std::size_t>(a.shape(0)));
  const std::int64_t* d = a.data();
  for (std::size_t i = 0; i < 3 * triangles.size(); ++i) {
    if (d[i] < 0 || d[i] > std::int64_t(std::numeric_limits<std::uint32_t>::max())) {
      raise_argument_error(std::string(field) + "[" + std::to_string(i / 3) + "]", "index out of range");
    }
    triangles[i / 3][i % 3] = static_cast<std::uint32_t>(d[i]);
  }
  return triangles;
}

template <class R, class F>
R point_query(const PyShape& s, const char* what, F&& f) {
  return visit_shape(s.ref(), [&](const auto& shape) -> R {
    using S = std::decay_t<decltype(shape)>;
    if constexpr (PointQueryable<S>) {
      return f(shape);
    } else {
      raise_error(make_error(ErrorCode::InvalidArgument, "shape",
                             std::string("a ") + to_string(kShapeTypeOf<S>) + " has no " + what));
    }
  });
}

void bind_base(py::module_& m) {
  py::class_<SurfacePoint>(m, "SurfacePoint", "The nearest surface point to a query point (world frame).")
      .def_property_readonly("point", [](const SurfacePoint& p) { return to_numpy(p.point); })
      .def_property_readonly(
          "normal", [](const SurfacePoint& p) { return to_numpy(p.normal); }, "Unit outward normal at point.")
      .def_readonly("signed_distance", &SurfacePoint::signed_distance, "> 0 outside, < 0 inside (length units).")
      .def("__repr__", [](const SurfacePoint& p) {
        return "SurfacePoint(point=" + repr_vec3(p.point) + ", normal=" + repr_vec3(p.normal) +
               ", signed_distance=" + repr_real(p.signed_distance) + ")";
      });
  py::class_<MassProperties>(m, "MassProperties", "Volume, mass, centroid and inertia of a solid (local frame).")
      .def_readonly("volume", &MassProperties::volume, "Length units cubed.")
      .def_readonly("mass", &MassProperties::mass, "density * volume.")
      .def_property_readonly("centroid", [](const MassProperties& p) { return to_numpy(p.centroid); })
      .def_property_readonly(
          "inertia",
          [](const MassProperties& p) {
            py::array_t<double> out({3, 3});
            auto a = out.mutable_unchecked<2>();
            for (int r = 0; r < 3; ++r)
              for (int c = 0; c < 3; ++c) a(r, c) = double(p.inertia[c][r]);
            return out;
          },
          "Inertia tensor about the centroid, local axes, (3, 3).")
      .def("__repr__", [](const MassProperties& p) {
        return "MassProperties(volume=" + repr_real(p.volume) + ", mass=" + repr_real(p.mass) +
               ", centroid=" + repr_vec3(p.centroid) + ")";
      });
  py::class_<RayHit>(m, "RayHit", "Where a ray meets a shape (world frame).")
      .def_readonly("t", &RayHit::t, "Ray parameter, in units of the direction's length.")
      .def_property_readonly("point", [](const RayHit& h) { return to_numpy(h.point); })
      .def_property_readonly("normal", [](const RayHit& h) { return to_numpy(h.normal); })
      .def_property_readonly(
          "part", [](const RayHit& h) { return part_index(h.sub); },
          "Mesh triangle or compound child hit, None for a convex shape.")
      .def("__repr__", [](const RayHit& h) {
        return "RayHit(t=" + repr_real(h.t) + ", point=" + repr_vec3(h.point) + ", normal=" + repr_vec3(h.normal) + ")";
      });

  py::class_<PyShape>(m, "Shape", "Any geometry (immutable). Construct one of the subclasses.")
      .def_property_readonly(
          "type", [](const PyShape& s) { return to_string(s.ref().type()); },
          "The kind, as in the query protocol ('sphere', 'box', 'mesh', ...).")
      .def(
          "aabb", [](const PyShape& s, py::handle pose) { return world_aabb(s.ref(), to_transform(pose, "pose")); },
          py::arg("pose") = py::none(), "Bounding box of the shape placed at pose (world frame).")
      .def(
          "raycast",
          [](const PyShape& s, py::handle origin, py::handle direction, Real max_t, py::handle pose) {
            const Ray ray{to_vec3(origin, "origin"), to_vec3(direction, "direction")};
            if (ray.direction == Vec3(Real(0))) raise_argument_error("direction", "must not be zero");
            if (!(max_t >= Real(0))) raise_argument_error("max_t", "must be >= 0");
            return raycast(s.ref(), to_transform(pose, "pose"), ray, max_t);
          },
          py::arg("origin"), py::arg("direction"), py::arg("max_t") = std::numeric_limits<Real>::max(),
          py::arg("pose") = py::none(), "The first hit with t in [0, max_t], or None.")
      .def(
          "contains",
          [](const PyShape& s, py::handle point, py::handle pose) {
            const Vec3 p = to_vec3(point, "point");
            const Transform t = to_transform(pose, "pose");
            return point_query<bool>(s, "point containment", [&](const auto& shape) { return contains(shape, t, p); });
          },
          py::arg("point"), py::arg("pose") = py::none(), "True when the world point is inside or on the shape.")
      .def(
          "closest_point",
          [](const PyShape& s, py::handle point, py::handle pose) {
            const Vec3 p = to_vec3(point, "point");
            const Transform t = to_transform(pose, "pose");
            return point_query<SurfacePoint>(s, "closest point",
                                             [&](const auto& shape) { return closest_point(shape, t, p); });
          },
          py::arg("point"), py::arg("pose") = py::none(), "The nearest surface point (signed: negative inside).")
      .def(
          "mass_properties",
          [](const PyShape& s, Real density) {
            if (!(density > Real(0))) raise_error(make_error(ErrorCode::NonPositive, "density", "must be > 0"));
            return visit_shape(s.ref(), [&](const auto& shape) -> MassProperties {
              using S = std::decay_t<decltype(shape)>;
              if constexpr (std::is_same_v<S, TriangleMesh>) {
                if (!shape.is_closed()) raise_argument_error("shape", "the mesh is not closed: it encloses no volume");
                return shape.mass_properties(density);
              } else if constexpr (requires { shape.mass_properties(density); }) {
                return shape.mass_properties(density);
              } else {
                raise_argument_error("shape", std::string("a ") + to_string(kShapeTypeOf<S>) + " has infinite volume");
              }
            });
          },
          py::arg("density") = Real(1), "Mass properties at uniform density (mass per length unit cubed).")
      .def("__repr__", [](const PyShape& s) { return shape_repr(*s.shape); });
}

}  // namespace
}  // namespace proxima::python

namespace proxima::python {
namespace {

template <class S>
std::unique_ptr<PyShapeOf<S>> hold(Result<S>&& result) {
  auto p = std::make_unique<PyShapeOf<S>>();
  p->shape = std::make_shared<const Shape>(take(std::move(result)));
  return p;
}

/// The class of kind S with pickling by `args` (the constructor's arguments of a shape).
template <class S, class Args>
py::class_<PyShapeOf<S>, PyShape> shape_class(py::module_& m, const char* name, const char* doc, Args args) {
  py::class_<PyShapeOf<S>, PyShape> c(m, name, doc);
  c.def("__reduce__", [args](py::object self) {
    return py::make_tuple(py::type::of(self), args(self.cast<const PyShapeOf<S>&>().get()));
  });
  return c;
}

void bind_convex_kinds(py::module_& m) {
  shape_class<Point>(m, "Point", "A point at the origin of its frame.", [](const Point&) {
    return py::tuple();
  }).def(py::init([] { return hold(Point::create()); }));
  shape_class<Segment>(m, "Segment", "The segment from a to b (local frame).",
                       [](const Segment& s) { return py::make_tuple(to_numpy(s.a()), to_numpy(s.b())); })
      .def(py::init([](py::handle a, py::handle b) { return hold(Segment::create(to_vec3(a, "a"), to_vec3(b, "b"))); }),
           py::arg("a"), py::arg("b"))
      .def_property_readonly("a", [](const PyShapeOf<Segment>& s) { return to_numpy(s.get().a()); })
      .def_property_readonly("b", [](const PyShapeOf<Segment>& s) { return to_numpy(s.get().b()); });
  shape_class<Triangle>(
      m, "Triangle", "A two-sided triangle a, b, c (local frame).",
      [](const Triangle& t) { return py::make_tuple(to_numpy(t.a()), to_numpy(t.b()), to_numpy(t.c())); })
      .def(py::init([](py::handle a, py::handle b, py::handle c) {
             return hold(Triangle::create(to_vec3(a, "a"), to_vec3(b, "b"), to_vec3(c, "c")));
           }),
           py::arg("a"), py::arg("b"), py::arg("c"))
      .def_property_readonly("vertices", [](const PyShapeOf<Triangle>& s) {
        const Triangle& t = s.get();
        const Vec3 v[3] = {t.a(), t.b(), t.c()};
        return points_array(v);
      });
  shape_class<Sphere>(m, "Sphere", "A ball of `radius` centred on the origin.",
                      [](const Sphere& s) { return py::make_tuple(s.radius()); })
      .def(py::init([](Real r) { return hold(Sphere::create(r)); }), py::arg("radius"))
      .def_property_readonly("radius", [](const PyShapeOf<Sphere>& s) { return s.get().radius(); });
  shape_class<Capsule>(m, "Capsule", "Points within `radius` of the segment z in [-half_length, half_length].",
                       [](const Capsule& s) { return py::make_tuple(s.radius(), s.half_length()); })
      .def(py::init([](Real r, Real h) { return hold(Capsule::create(r, h)); }), py::arg("radius"),
           py::arg("half_length"))
      .def_property_readonly("radius", [](const PyShapeOf<Capsule>& s) { return s.get().radius(); })
      .def_property_readonly("half_length", [](const PyShapeOf<Capsule>& s) { return s.get().half_length(); });
  shape_class<Box>(m, "Box", "A box of the given half extents centred on the origin.",
                   [](const Box& s) { return py::make_tuple(to_numpy(s.half_extents())); })
      .def(py::init([](py::handle h) { return hold(Box::create(to_vec3(h, "half_extents"))); }),
           py::arg("half_extents"))
      .def_property_readonly("half_extents", [](const PyShapeOf<Box>& s) { return to_numpy(s.get().half_extents()); });
  shape_class<Cylinder>(m, "Cylinder", "A cylinder along z: radius, z in [-half_length, half_length].",
                        [](const Cylinder& s) { return py::make_tuple(s.radius(), s.half_length()); })
      .def(py::init([](Real r, Real h) { return hold(Cylinder::create(r, h)); }), py::arg("radius"),
           py::arg("half_length"))
      .def_property_readonly("radius", [](const PyShapeOf<Cylinder>& s) { return s.get().radius(); })
      .def_property_readonly("half_length", [](const PyShapeOf<Cylinder>& s) { return s.get().half_length(); });
  shape_class<Cone>(m, "Cone", "A cone along z: base of `radius` at z = -half_length, apex at +half_length.",
                    [](const Cone& s) { return py::make_tuple(s.radius(), s.half_length()); })
      .def(py::init([](Real r, Real h) { return hold(Cone::create(r, h)); }), py::arg("radius"), py::arg("half_length"))
      .def_property_readonly("radius", [](const PyShapeOf<Cone>& s) { return s.get().radius(); })
      .def_property_readonly("half_length", [](const PyShapeOf<Cone>& s) { return s.get().half_length(); });
  shape_class<Ellipsoid>(m, "Ellipsoid", "An ellipsoid of semi-axes `radii` along x, y, z.",
                         [](const Ellipsoid& s) { return py::make_tuple(to_numpy(s.radii())); })
      .def(py::init([](py::handle r) { return hold(Ellipsoid::create(to_vec3(r, "radii"))); }), py::arg("radii"))
      .def_property_readonly("radii", [](const PyShapeOf<Ellipsoid>& s) { return to_numpy(s.get().radii()); });
  shape_class<ConvexHull>(m, "ConvexHull", "The convex hull of a point cloud (qhull), at least 4 non-coplanar points.",
                          [](const ConvexHull& s) { return py::make_tuple(points_array(s.vertices())); })
      .def(py::init([](py::handle points) {
             const std::vector<Vec3> p = to_points(points, "points");
             return hold(ConvexHull::create(p));
           }),
           py::arg("points"))
      .def_property_readonly(
          "vertices", [](const PyShapeOf<ConvexHull>& s) { return points_array(s.get().vertices()); },
          "Hull vertices, (N, 3), each one an input point.");
  shape_class<HalfSpace>(m, "HalfSpace", "Points x with dot(normal, x) <= offset (normal is normalised).",
                         [](const HalfSpace& s) { return py::make_tuple(to_numpy(s.normal()), s.offset()); })
      .def(py::init([](py::handle n, Real offset) { return hold(HalfSpace::create(to_vec3(n, "normal"), offset)); }),
           py::arg("normal"), py::arg("offset") = Real(0))
      .def_property_readonly("normal", [](const PyShapeOf<HalfSpace>& s) { return to_numpy(s.get().normal()); })
      .def_property_readonly("offset", [](const PyShapeOf<HalfSpace>& s) { return s.get().offset(); });
}

py::array_t<std::uint32_t> triangles_array(std::span<const TriangleIndices> triangles) {
  py::array_t<std::uint32_t> out({static_cast<py::ssize_t>(triangles.size()), py::ssize_t(3)});
  std::uint32_t* d = out.mutable_data();
  for (std::size_t i = 0; i < triangles.size(); ++i)
    for (int k = 0; k < 3; ++k) d[3 * i + k] = triangles[i][k];
  return out;
}

void bind_mesh(py::module_& m) {
  shape_class<TriangleMesh>(m, "TriangleMesh",
                            "A triangle surface with its BVH. Built from an (N, 3) vertex array and an (M, 3) index "
                            "array; repair welds, drops degenerate and duplicate triangles and orients consistently.",
                            [](const TriangleMesh& s) {
                              return py::make_tuple(points_array(s.vertices()), triangles_array(s.triangles()), false);
                            })
      .def(py::init([](py::handle vertices, py::handle triangles, bool repair) {
             IndexedMesh mesh{to_points(vertices, "vertices"), to_triangles(triangles, "triangles")};
             MeshCreateOptions options;
             options.repair = repair;
             std::optional<Result<TriangleMesh>> made;
             {
               py::gil_scoped_release release;  // the BVH build of a large mesh takes a while
               made.emplace(TriangleMesh::create(std::move(mesh), options));
             }
             return hold(std::move(*made));
           }),
           py::arg("vertices"), py::arg("triangles"), py::arg("repair") = true)
      .def_property_readonly("vertices",
                             [](const PyShapeOf<TriangleMesh>& s) { return points_array(s.get().vertices()); })
      .def_property_readonly("triangles",
                             [](const PyShapeOf<TriangleMesh>& s) { return triangles_array(s.get().triangles()); })
      .def_property_readonly(
          "is_closed", [](const PyShapeOf<TriangleMesh>& s) { return s.get().is_closed(); },
          "True for a closed, outward-oriented mesh (then it bounds a solid).");
}

void bind_compound(py::module_& m) {
  shape_class<Compound>(m, "Compound", "Child shapes at poses in the compound's frame, with a BVH over them.",
                        [](const Compound& s) {
                          py::list children;
                          for (const CompoundChild& c : s.children()) {
                            children.append(py::make_tuple(wrap_shape(c.shape), c.pose));
                          }
                          return py::make_tuple(children);
                        })
      .def(py::init([](const py::sequence& children) {
             std::vector<CompoundChild> list;
             for (std::size_t i = 0; i < children.size(); ++i) {
               const std::string field = "children[" + std::to_string(i) + "]";
               py::handle item = children[i];
               if (py::isinstance<PyShape>(item)) {
                 list.push_back({*item.cast<const PyShape&>().shape, Transform::identity()});
                 continue;
               }
               if (!py::isinstance<py::sequence>(item) || py::len(item) != 2) {
                 raise_argument_error(field, "expected a shape or a (shape, pose) pair");
               }
               const py::sequence pair = item.cast<py::sequence>();
               list.push_back({*to_shape(pair[0], (field + ".shape").c_str()).shape,
                               to_transform(pair[1], (field + ".pose").c_str())});
             }
             return hold(Compound::create(std::move(list)));
           }),
           py::arg("children"))
      .def_property_readonly(
          "children",
          [](const PyShapeOf<Compound>& s) {
            py::list children;
            for (const CompoundChild& c : s.get().children())
              children.append(py::make_tuple(wrap_shape(c.shape), c.pose));
            return children;
          },
          "[(shape, pose), ...] in the order given.");
}

template <class S>
std::unique_ptr<PyShape> hold_shape(Shape&& shape) {
  auto p = std::make_unique<PyShapeOf<S>>();
  p->shape = std::make_shared<const Shape>(std::move(shape));
  return p;
}

}  // namespace

py::object part_index(const SubShapeId& sub) {
  const bool child = sub.child != kNoIndex, triangle = sub.triangle != kNoIndex;
  if (child && triangle) return py::make_tuple(sub.child, sub.triangle);
  if (child) return py::int_(sub.child);
  if (triangle) return py::int_(sub.triangle);
  return py::none();
}

py::object wrap_shape(Shape shape) {
  std::unique_ptr<PyShape> p = std::visit(
      [&](auto& s) {
        using S = std::decay_t<decltype(s)>;
        return hold_shape<S>(std::move(shape));
      },
      shape);
  return py::cast(std::move(p));
}

const PyShape& to_shape(py::handle value, const char* field) {
  if (!py::isinstance<PyShape>(value)) raise_argument_error(field, "expected a proxima.Shape");
  return value.cast<const PyShape&>();
}

std::string shape_repr(const Shape& shape) {
  const py::object self = wrap_shape(shape);
  std::string text = py::str(py::type::of(self).attr("__name__"));
  if (const auto* mesh = std::get_if<TriangleMesh>(&shape)) {
    return text + "(vertices=" + std::to_string(mesh->vertices().size()) +
           ", triangles=" + std::to_string(mesh->triangles().size()) + ")";
  }
  if (const auto* hull = std::get_if<ConvexHull>(&shape)) {
    return text + "(vertices=" + std::to_string(hull->vertices().size()) + ")";
  }
  if (const auto* compound = std::get_if<Compound>(&shape)) {
    return text + "(children=" + std::to_string(compound->children().size()) + ")";
  }
  const py::tuple args = self.attr("__reduce__")()[py::int_(1)];
  std::string inner;
  for (std::size_t i = 0; i < args.size(); ++i) {
    py::object a = args[i];
    if (py::isinstance<py::array>(a)) a = a.attr("tolist")();
    inner += (i ? ", " : "") + std::string(py::repr(a));
  }
  return text + "(" + inner + ")";
}

void bind_shapes(py::module_& m) {
  bind_base(m);
  bind_convex_kinds(m);
  bind_mesh(m);
  bind_compound(m);
}

}  // namespace proxima::python
