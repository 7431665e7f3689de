#pragma once
/// @file shape_ref.hpp
/// ShapeRef: a non-owning, type-tagged reference to any shape. It converts implicitly from
/// every concrete shape and from the Shape variant, so run-time dispatch (the narrow phase's
/// table) costs one table lookup and no copy, no allocation and no virtual call.

#include <proxima/core/assert.hpp>
#include <proxima/shapes/shape.hpp>
#include <proxima/shapes/shape_type.hpp>

#include <type_traits>

namespace proxima {

/// The ShapeType of a concrete shape type, at compile time (Point -> ShapeType::Point, ...).
template <class S>
inline constexpr ShapeType kShapeTypeOf = ShapeType::Count;  // not a shape (specialised below)

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
#undef PROXIMA_SHAPE_TYPE_OF

/// The concrete shape type for a ShapeType (ShapeTypeAt<ShapeType::Box> is Box).
template <ShapeType T>
using ShapeTypeAt = std::variant_alternative_t<static_cast<std::size_t>(T), Shape>;

/// A borrowed shape with its type tag. The referenced shape must outlive the ShapeRef.
class ShapeRef {
 public:
  /// From any concrete shape (implicit, so `distance(sphere, ta, box, tb)` just works).
  template <class S>
  requires(kShapeTypeOf<std::remove_cvref_t<S>> != ShapeType::Count) ShapeRef(const S& shape)
  noexcept  // NOLINT(google-explicit-constructor)
      : data_(&shape), type_(kShapeTypeOf<S>) {}

  /// From the Shape variant (implicit): refers to the held alternative.
  ShapeRef(const Shape& shape) noexcept  // NOLINT(google-explicit-constructor)
      : data_(std::visit([](const auto& s) -> const void* { return &s; }, shape)), type_(shape_type(shape)) {}

  /// The referenced shape's type.
  ShapeType type() const noexcept { return type_; }
  /// The referenced object, to be cast to ShapeTypeAt<type()>.
  const void* data() const noexcept { return data_; }

  /// The referenced shape as S; S must be the type named by type().
  template <class S>
  const S& as() const noexcept {
    PROXIMA_ASSERT(kShapeTypeOf<S> == type_);
    return *static_cast<const S*>(data_);
  }

 private:
  const void* data_;
  ShapeType type_;
};

}  // namespace proxima
