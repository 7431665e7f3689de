#include "json_shapes.hpp"

#include <proxima/shapes/shape_type.hpp>

#include <string_view>

namespace proxima::tool {

namespace {

// Segment and triangle name their vertices a, b, c; the protocol names them vertices[i].
Error rename_vertices(Error error) {
  static const char* const kNames[] = {"a", "b", "c"};
  for (int i = 0; i < 3; ++i) {
    const std::string name = kNames[i];
    if (error.field == name || error.field.rfind(name + ".", 0) == 0) {
      error.field = "vertices[" + std::to_string(i) + "]" + error.field.substr(name.size());
      break;
    }
  }
  return error;
}

template <class T>
T unwrap_vertices(Result<T> result, const std::string& path) {
  if (!result.ok()) throw_library_error(path, rename_vertices(result.error()));
  return std::move(result).value();
}

Real member_real(const Json& value, const std::string& path, std::string_view key) {
  return read_real(require_member(value, path, key), join_path(path, key));
}

Vec3 member_vec3(const Json& value, const std::string& path, std::string_view key) {
  return read_vec3(require_member(value, path, key), join_path(path, key));
}

}  // namespace

std::string shape_type_names() {
  std::string names;
  for (int i = 0; i < kShapeTypeCount; ++i) {
    if (i > 0) names += ", ";
    names += to_string(static_cast<ShapeType>(i));
  }
  return names;
}

Shape read_shape(const Json& value, const std::string& path) {
  require_object(value, path);
  const std::string type_path = join_path(path, "type");
  const std::string type = read_string(require_member(value, path, "type"), type_path);

  if (type == "point") {
    reject_unknown_fields(value, path, {"type"});
    return unwrap(Point::create(), path);
  }
  if (type == "segment") {
    reject_unknown_fields(value, path, {"type", "vertices"});
    const auto v = read_points(require_member(value, path, "vertices"), join_path(path, "vertices"), 2);
    return unwrap_vertices(Segment::create(v[0], v[1]), path);
  }
  if (type == "triangle") {
    reject_unknown_fields(value, path, {"type", "vertices"});
    const auto v = read_points(require_member(value, path, "vertices"), join_path(path, "vertices"), 3);
    return unwrap_vertices(Triangle::create(v[0], v[1], v[2]), path);
  }
  if (type == "sphere") {
    reject_unknown_fields(value, path, {"type", "radius"});
    return unwrap(Sphere::create(member_real(value, path, "radius")), path);
  }
  if (type == "capsule" || type == "cylinder" || type == "cone") {
    reject_unknown_fields(value, path, {"type", "radius", "half_length"});
    const Real radius = member_real(value, path, "radius");
    const Real half_length = member_real(value, path, "half_length");
    if (type == "capsule") return unwrap(Capsule::create(radius, half_length), path);
    if (type == "cylinder") return unwrap(Cylinder::create(radius, half_length), path);
    return unwrap(Cone::create(radius, half_length), path);
  }
  if (type == "box") {
    reject_unknown_fields(value, path, {"type", "half_extents"});
    return unwrap(Box::create(member_vec3(value, path, "half_extents")), path);
  }
  if (type == "ellipsoid") {
    reject_unknown_fields(value, path, {"type", "radii"});
    return unwrap(Ellipsoid::create(member_vec3(value, path, "radii")), path);
  }
  if (type == "convex") {
    reject_unknown_fields(value, path, {"type", "points"});
    const auto points = read_points(require_member(value, path, "points"), join_path(path, "points"));
    return unwrap(ConvexHull::create(points), path);
  }
  if (type == "halfspace") {
    reject_unknown_fields(value, path, {"type", "normal", "offset"});
    const Vec3 normal = member_vec3(value, path, "normal");
    const Real offset = member_real(value, path, "offset");
    return unwrap(HalfSpace::create(normal, offset), path);
  }
  throw FieldError(type_path, "unknown_shape",
                   "unknown shape type \"" + type + "\" (expected one of " + shape_type_names() + ")");
}

Transform read_pose(const Json& value, const std::string& path) {
  require_object(value, path);
  reject_unknown_fields(value, path, {"position", "rotation"});
  Vec3 position(Real(0));
  Quat rotation = kIdentityQuat;
  if (const Json* p = find_member(value, "position")) position = read_vec3(*p, join_path(path, "position"));
  if (const Json* r = find_member(value, "rotation")) rotation = read_quat_xyzw(*r, join_path(path, "rotation"));
  return unwrap(Transform::create(position, rotation), path);
}

PlacedShape read_placed_shape(const Json& value, const std::string& path) {
  require_object(value, path);
  if (find_member(value, "type") != nullptr) return PlacedShape{read_shape(value, path), Transform::identity()};
  reject_unknown_fields(value, path, {"shape", "pose"});
  PlacedShape placed{read_shape(require_member(value, path, "shape"), join_path(path, "shape")), Transform::identity()};
  if (const Json* pose = find_member(value, "pose")) placed.pose = read_pose(*pose, join_path(path, "pose"));
  return placed;
}

}  // namespace proxima::tool
