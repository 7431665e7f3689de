#pragma once
/// @file shape.hpp
/// Shape: the one owning type of every 2D geometry (a value: copyable, no shared state),
/// with its kind, its core and its bounds. The 2D queries (narrowphase.hpp) take Shapes.

#include <proxima/d2/chain.hpp>
#include <proxima/d2/convex_shapes.hpp>

#include <cstdint>
#include <variant>

namespace proxima::d2 {

/// The kinds of 2D geometry, in the order of Shape's alternatives.
enum class ShapeType : std::uint8_t { Point, Circle, Segment, Capsule, Polygon, Chain };

/// Short name of a kind ("point", "circle", "segment", "capsule", "polygon", "chain").
const char* to_string(ShapeType type);

/// Any 2D geometry. Build the alternatives with their validated `create` functions.
class Shape {
 public:
  /// The alternatives, in ShapeType order.
  using Variant = std::variant<Point, Circle, Segment, Capsule, Polygon, Chain>;

  /// A shape holding `value` (any alternative).
  template <class T>
  requires std::is_constructible_v<Variant, T> Shape(T value)
      : value_(std::move(value)) {}  // NOLINT(google-explicit-constructor)

  /// Which kind this is.
  ShapeType type() const { return static_cast<ShapeType>(value_.index()); }
  /// True for every kind but Chain.
  bool is_convex() const { return type() != ShapeType::Chain; }
  /// The alternative (std::get / std::visit on it).
  const Variant& variant() const { return value_; }
  /// The core of a convex shape (stored in it). Precondition: is_convex() (a chain, which has
  /// no single core, fails PROXIMA_ASSERT and gives an empty core).
  const ConvexCore& core() const;
  /// The chain. Precondition: type() == ShapeType::Chain.
  const Chain& chain() const { return std::get<Chain>(value_); }
  /// Tight rectangle under `pose` (O(points) for a chain).
  Aabb world_aabb(const Pose& pose) const;

 private:
  Variant value_;
};

}  // namespace proxima::d2
