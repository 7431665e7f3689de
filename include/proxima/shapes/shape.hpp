#pragma once
/// @file shape.hpp
/// Shape: a type-erased convex shape (std::variant over every shape type), for code that
/// receives shapes at run time (the CLI, scene files, later the world). Hot paths use the
/// concrete types; this wrapper dispatches once per call with std::visit.

#include <proxima/shapes/box.hpp>
#include <proxima/shapes/capsule.hpp>
#include <proxima/shapes/cone.hpp>
#include <proxima/shapes/convex_hull.hpp>
#include <proxima/shapes/cylinder.hpp>
#include <proxima/shapes/ellipsoid.hpp>
#include <proxima/shapes/halfspace.hpp>
#include <proxima/shapes/point.hpp>
#include <proxima/shapes/segment.hpp>
#include <proxima/shapes/sphere.hpp>
#include <proxima/shapes/triangle.hpp>

#include <variant>

namespace proxima {

/// Any shape, alternatives in ShapeType order (index() == static_cast<int>(type())).
using Shape =
    std::variant<Point, Segment, Triangle, Sphere, Capsule, Box, Cylinder, Cone, Ellipsoid, ConvexHull, HalfSpace>;

/// The dispatch tag of the held shape.
inline ShapeType shape_type(const Shape& shape) { return static_cast<ShapeType>(shape.index()); }

}  // namespace proxima
