#pragma once
/// @file shape_object.hpp
/// How a Python shape holds its geometry: proxima.Shape (PyShape) shares one immutable
/// proxima::Shape; each kind is a Python subclass (proxima.Sphere, proxima.TriangleMesh, ...)
/// over PyShapeOf<S>, so isinstance works and the library sees one ShapeRef.
#include <proxima/shapes/shape.hpp>
#include <proxima/shapes/shape_ref.hpp>

#include <memory>

#include "conversions.hpp"

namespace proxima::python {

/// The base of every Python shape: one shared, immutable geometry (local frame).
struct PyShape {
  virtual ~PyShape() = default;
  std::shared_ptr<const Shape> shape;  ///< never null
  ShapeRef ref() const { return *shape; }
};

/// A shape of one kind; S is a member of proxima::Shape.
template <class S>
struct PyShapeOf : PyShape {
  const S& get() const { return std::get<S>(*shape); }
};

/// A Python object of the right subclass holding `shape`.
py::object wrap_shape(Shape shape);
/// The geometry of a proxima.Shape argument, else proxima.Error naming `field`.
const PyShape& to_shape(py::handle value, const char* field);

}  // namespace proxima::python

namespace proxima::python {
/// The part of a shape that a query answer lies on: None (convex), the triangle of a mesh,
/// the child of a compound, or (child, triangle).
py::object part_index(const SubShapeId& sub);
/// "Sphere(0.5,)": the class name and its constructor arguments.
std::string shape_repr(const Shape& shape);
}  // namespace proxima::python
