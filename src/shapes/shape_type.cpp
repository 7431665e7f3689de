#include <proxima/shapes/shape_type.hpp>

namespace proxima {

const char* to_string(ShapeType type) {
  switch (type) {
    case ShapeType::Point: return "point";
    case ShapeType::Segment: return "segment";
    case ShapeType::Triangle: return "triangle";
    case ShapeType::Sphere: return "sphere";
    case ShapeType::Capsule: return "capsule";
    case ShapeType::Box: return "box";
    case ShapeType::Cylinder: return "cylinder";
    case ShapeType::Cone: return "cone";
    case ShapeType::Ellipsoid: return "ellipsoid";
    case ShapeType::ConvexHull: return "convex";
    case ShapeType::HalfSpace: return "halfspace";
    case ShapeType::TriangleMesh: return "mesh";
    case ShapeType::Compound: return "compound";
    case ShapeType::Count: break;
  }
  return "unknown";
}

}  // namespace proxima
