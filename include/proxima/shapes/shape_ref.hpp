#pragma once
/// @file shape_ref.hpp
/// ShapeRef: a non-owning, type-tagged view of any shape. It converts implicitly from every
/// concrete shape (convex, half-space, mesh, compound) and from the owning Shape, so run-time
/// dispatch (the narrow phase's table) costs one table lookup and no copy, no allocation and
/// no virtual call.
#include <proxima/core/assert.hpp>
#include <proxima/shapes/shape.hpp>
#include <proxima/shapes/shape_type.hpp>

#include <cstddef>
#include <type_traits>
#include <variant>

namespace proxima {

/// The ShapeType of a concrete shape type, at compile time (Point -> ShapeType::Point, ...);
/// ShapeType::Count for a type that is not a shape.
template <class S>
inline constexpr ShapeType kShapeTypeOf = ShapeType::Count;

#define PROXIMA_SHAPE_TYPE_OF(S) \
  template <>                    \
  inline constexpr ShapeType kShapeTypeOf<S> = ShapeType::S;
PROXIMA_SHAPE_TYPE_OF(Point)
PROXIMA_SHAPE_TYPE_OF(Segment)
PROXIMA_SHAPE_TYPE_OF(Triangle)
PROXIMA_SHAPE_TYPE_OF(Sphere)
PROXIMA_SHAPE_TYPE_OF(Capsule)
PROXIMA_SHAPE_TYPE_OF(Box)
PROXIMA_SHAPE_TYPE_OF(Cylinder)
PROXIMA_SHAPE_TYPE_OF(Cone)
PROXIMA_SHAPE_TYPE_OF(Ellipsoid)
PROXIMA_SHAPE_TYPE_OF(ConvexHull)
PROXIMA_SHAPE_TYPE_OF(HalfSpace)
PROXIMA_SHAPE_TYPE_OF(TriangleMesh)
PROXIMA_SHAPE_TYPE_OF(Compound)
#undef PROXIMA_SHAPE_TYPE_OF

/// The concrete shape type for a ShapeType (ShapeTypeAt<ShapeType::Box> is Box).
template <ShapeType T>
using ShapeTypeAt = std::variant_alternative_t<static_cast<std::size_t>(T), Shape>;

/// True for the concrete shape types (those a ShapeRef can view).
template <class S>
concept ConcreteShape = (kShapeTypeOf<std::remove_cvref_t<S>> != ShapeType::Count);

/// A borrowed shape with its type tag. The viewed shape must outlive the ShapeRef.
class ShapeRef {
 public:
  /// From any concrete shape (implicit, so `distance(sphere, ta, mesh, tb)` just works).
  template <ConcreteShape S>
  ShapeRef(const S& shape) noexcept  // NOLINT(google-explicit-constructor)
      : data_(&shape), type_(kShapeTypeOf<S>) {}
  /// From the owning Shape (implicit): views the held alternative.
  ShapeRef(const Shape& shape) noexcept  // NOLINT(google-explicit-constructor)
      : data_(std::visit([](const auto& s) -> const void* { return &s; }, shape)), type_(shape_type(shape)) {}

  /// The viewed shape's type.
  ShapeType type() const noexcept { return type_; }
  /// The viewed object, to be cast to ShapeTypeAt<type()>.
  const void* data() const noexcept { return data_; }
  /// The viewed shape as S; S must be the type named by type().
  template <class S>
  const S& as() const noexcept {
    PROXIMA_ASSERT(kShapeTypeOf<S> == type_);
    return *static_cast<const S*>(data_);
  }

 private:
  const void* data_;
  ShapeType type_;
};

/// Calls `f(concrete_shape)` with the shape `s` views (one switch, no allocation); `f` must
/// accept every concrete shape type and return the same type for each.
template <class F>
decltype(auto) visit_shape(ShapeRef s, F&& f) {
  switch (s.type()) {
    case ShapeType::Point: return f(s.as<Point>());
    case ShapeType::Segment: return f(s.as<Segment>());
    case ShapeType::Triangle: return f(s.as<Triangle>());
    case ShapeType::Sphere: return f(s.as<Sphere>());
    case ShapeType::Capsule: return f(s.as<Capsule>());
    case ShapeType::Box: return f(s.as<Box>());
    case ShapeType::Cylinder: return f(s.as<Cylinder>());
    case ShapeType::Cone: return f(s.as<Cone>());
    case ShapeType::Ellipsoid: return f(s.as<Ellipsoid>());
    case ShapeType::ConvexHull: return f(s.as<ConvexHull>());
    case ShapeType::HalfSpace: return f(s.as<HalfSpace>());
    case ShapeType::TriangleMesh: return f(s.as<TriangleMesh>());
    default: return f(s.as<Compound>());
  }
}

}  // namespace proxima
