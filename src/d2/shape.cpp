/// @file shape.cpp
/// The 2D owning shape type: kind names, cores and bounds.

#include <proxima/core/assert.hpp>
#include <proxima/d2/shape.hpp>

namespace proxima::d2 {

const char* to_string(ShapeType type) {
  switch (type) {
    case ShapeType::Point: return "point";
    case ShapeType::Circle: return "circle";
    case ShapeType::Segment: return "segment";
    case ShapeType::Capsule: return "capsule";
    case ShapeType::Polygon: return "polygon";
    case ShapeType::Chain: return "chain";
  }
  return "unknown";
}

const ConvexCore& Shape::core() const {
  return std::visit(
      [](const auto& s) -> const ConvexCore& {
        if constexpr (std::is_same_v<std::decay_t<decltype(s)>, Chain>) {
          PROXIMA_ASSERT(false && "Shape::core() of a chain");
          static const ConvexCore kNoCore{};
          return kNoCore;
        } else {
          return s.core();
        }
      },
      value_);
}

Aabb Shape::world_aabb(const Pose& pose) const {
  if (type() == ShapeType::Chain) return chain().world_aabb(pose);
  return core().world_aabb(pose);
}

}  // namespace proxima::d2
