#pragma once
/// @file shape.hpp
/// Shape: the one owning type for every shape the library has (the eleven convex shapes,
/// the half-space, the triangle mesh and the compound), as a std::variant in ShapeType
/// order. Every alternative is a small value or shares immutable data (hulls, meshes and
/// compounds hold a shared_ptr to const data), so a Shape is cheap to copy and safe to share
/// between threads. Queries take the non-owning ShapeRef (shape_ref.hpp), which converts
/// implicitly from a Shape and from every concrete shape.
#include <proxima/core/transform.hpp>
#include <proxima/shapes/box.hpp>
#include <proxima/shapes/capsule.hpp>
#include <proxima/shapes/compound.hpp>
#include <proxima/shapes/cone.hpp>
#include <proxima/shapes/convex_hull.hpp>
#include <proxima/shapes/cylinder.hpp>
#include <proxima/shapes/ellipsoid.hpp>
#include <proxima/shapes/halfspace.hpp>
#include <proxima/shapes/point.hpp>
#include <proxima/shapes/segment.hpp>
#include <proxima/shapes/shape_type.hpp>
#include <proxima/shapes/sphere.hpp>
#include <proxima/shapes/triangle.hpp>
#include <proxima/shapes/triangle_mesh.hpp>

#include <variant>

namespace proxima {

/// Any shape, owning; alternatives in ShapeType order (index() == static_cast<int>(type)).
using Shape = std::variant<Point, Segment, Triangle, Sphere, Capsule, Box, Cylinder, Cone, Ellipsoid, ConvexHull,
                           HalfSpace, TriangleMesh, Compound>;
static_assert(std::variant_size_v<Shape> == static_cast<std::size_t>(kShapeTypeCount));

/// The kind of the held shape.
inline ShapeType shape_type(const Shape& shape) noexcept { return static_cast<ShapeType>(shape.index()); }

/// One child of a compound: its shape (any kind but a half-space) and its pose in the
/// compound's frame.
struct CompoundChild {
  Shape shape;     ///< the child shape
  Transform pose;  ///< child frame -> compound frame
};

/// The data behind a Compound.
struct Compound::Data {
  std::vector<CompoundChild> children;  ///< children in the order given
  Bvh bvh;                              ///< over the children's boxes, compound frame
};

inline std::span<const CompoundChild> Compound::children() const { return data_->children; }
inline const Bvh& Compound::bvh() const { return data_->bvh; }

}  // namespace proxima
