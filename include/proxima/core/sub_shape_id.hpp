#pragma once
/// @file sub_shape_id.hpp
/// SubShapeId: which part of a shape a result comes from. Every query result that can come
/// from a part of a shape (a ray hit, a distance witness, a contact point) carries one per
/// side, so that a mesh triangle or a compound child is known without a second result type.
#include <cstdint>

namespace proxima {

/// Marks "no triangle / no neighbour / no child".
inline constexpr std::uint32_t kNoIndex = 0xffffffffu;

/// The part of a shape a result comes from: for a compound, the index of its top-level
/// child; for a triangle mesh (directly, as a compound child, or deeper), the index of the
/// triangle. kNoIndex where it does not apply (a convex shape: both fields).
struct SubShapeId {
  std::uint32_t child = kNoIndex;     ///< top-level compound child
  std::uint32_t triangle = kNoIndex;  ///< triangle of a mesh

  friend bool operator==(const SubShapeId&, const SubShapeId&) = default;
};

}  // namespace proxima
