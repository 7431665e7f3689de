/// @file geometry_ref.cpp
/// GeometryRef from an owning Geometry.

#include <proxima/shapes/geometry.hpp>

namespace proxima {

GeometryRef::GeometryRef(const Geometry& geometry) noexcept : kind_(GeometryKind::Convex) {
  switch (geometry.index()) {
    case 0: convex_ = ShapeRef(std::get<Shape>(geometry)); break;
    case 1:
      other_ = &std::get<TriangleMesh>(geometry);
      kind_ = GeometryKind::Mesh;
      break;
    default:
      other_ = &std::get<Compound>(geometry);
      kind_ = GeometryKind::Compound;
      break;
  }
}

}  // namespace proxima
