#include "json_shapes.hpp"

#include <proxima/shapes/shape_type.hpp>

#include <filesystem>
#include <limits>
#include <map>
#include <string_view>
#include <utility>

#include "mesh_io.hpp"

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

Vec3 member_vec3(const Json& value, const std::string& path, std::string_view key) {
  return read_vec3(require_member(value, path, key), join_path(path, key));
}

Shape read_convex_shape(const Json& value, const std::string& path, bool geometry_allowed);

/// Triangles [[i, j, k], ...]: non-negative integers below 2^32 (range against the vertex
/// count is checked by the library, which names "triangles[t][k]" too).
std::vector<TriangleIndices> read_triangles(const Json& value, const std::string& path) {
  if (!value.is_array()) throw FieldError(path, "wrong_type", "must be an array of triangles [[i, j, k], ...]");
  std::vector<TriangleIndices> triangles;
  triangles.reserve(value.size());
  for (std::size_t t = 0; t < value.size(); ++t) {
    const std::string tp = index_path(path, t);
    const Json& tri = value[t];
    if (!tri.is_array() || tri.size() != 3) {
      throw FieldError(tp, "wrong_type", "must be an array of three vertex indices [i, j, k]");
    }
    TriangleIndices indices{};
    for (std::size_t k = 0; k < 3; ++k) {
      const Json& index = tri[k];
      if (!index.is_number_integer() || index.get<long long>() < 0 ||
          index.get<long long>() > static_cast<long long>(std::numeric_limits<std::uint32_t>::max())) {
        throw FieldError(index_path(tp, k), "wrong_type", "must be a non-negative integer vertex index");
      }
      indices[k] = static_cast<std::uint32_t>(index.get<long long>());
    }
    triangles.push_back(indices);
  }
  return triangles;
}

/// Meshes read from files, by path and repair flag, reloaded when the file changes.
struct CachedMesh {
  std::filesystem::file_time_type time;
  TriangleMesh mesh;
};

TriangleMesh mesh_from_file(const std::string& file, bool repair, const std::string& path) {
  static std::map<std::pair<std::string, bool>, CachedMesh> cache;
  std::error_code ec;
  const auto time = std::filesystem::last_write_time(file, ec);
  std::error_code ignored;
  const auto key = std::make_pair(std::filesystem::absolute(file, ignored).string(), repair);
  if (!ec) {
    if (auto it = cache.find(key); it != cache.end() && it->second.time == time) return it->second.mesh;
  }
  Result<IndexedMesh> loaded = load_mesh(file);
  if (!loaded.ok()) throw_library_error(path, loaded.error());
  MeshCreateOptions options;
  options.repair = repair;
  // The library's errors name "vertices[i].x" / "triangles[t][k]" of the file's mesh.
  Result<TriangleMesh> mesh = TriangleMesh::create(std::move(loaded).value(), options);
  if (!mesh.ok()) {
    Error e = mesh.error();
    e.message = "in \"" + file + "\" (" + e.field + "): " + e.message;
    e.field = "file";
    throw_library_error(path, e);
  }
  if (!ec) {
    if (cache.size() >= 64) cache.clear();
    cache.insert_or_assign(key, CachedMesh{time, mesh.value()});
  }
  return std::move(mesh).value();
}

TriangleMesh read_mesh(const Json& value, const std::string& path) {
  reject_unknown_fields(value, path, {"type", "file", "vertices", "triangles", "repair"});
  bool repair = true;
  if (const Json* r = find_member(value, "repair")) {
    if (!r->is_boolean()) throw FieldError(join_path(path, "repair"), "wrong_type", "must be true or false");
    repair = r->get<bool>();
  }
  if (const Json* file = find_member(value, "file")) {
    if (find_member(value, "vertices") != nullptr || find_member(value, "triangles") != nullptr) {
      throw FieldError(join_path(path, "file"), "invalid_argument",
                       "give either \"file\" or \"vertices\" and \"triangles\", not both");
    }
    return mesh_from_file(read_string(*file, join_path(path, "file")), repair, path);
  }
  IndexedMesh mesh;
  mesh.vertices = read_points(require_member(value, path, "vertices"), join_path(path, "vertices"));
  mesh.triangles = read_triangles(require_member(value, path, "triangles"), join_path(path, "triangles"));
  MeshCreateOptions options;
  options.repair = repair;
  return unwrap(TriangleMesh::create(std::move(mesh), options), path);
}

Compound read_compound(const Json& value, const std::string& path) {
  reject_unknown_fields(value, path, {"type", "children"});
  const std::string children_path = join_path(path, "children");
  const Json& list = require_member(value, path, "children");
  if (!list.is_array()) throw FieldError(children_path, "wrong_type", "must be an array of {\"shape\":…,\"pose\":…}");
  std::vector<CompoundChild> children;
  children.reserve(list.size());
  for (std::size_t i = 0; i < list.size(); ++i) {
    PlacedShape child = read_placed_geometry(list[i], index_path(children_path, i));
    children.push_back(CompoundChild{std::move(child.shape), child.pose});
  }
  return unwrap(Compound::create(std::move(children)), path);
}

}  // namespace

std::string geometry_type_names() { return shape_type_names() + ", mesh, compound"; }

Shape read_geometry(const Json& value, const std::string& path) {
  require_object(value, path);
  const std::string type = read_string(require_member(value, path, "type"), join_path(path, "type"));
  if (type == "mesh") return read_mesh(value, path);
  if (type == "compound") return read_compound(value, path);
  return read_convex_shape(value, path, true);
}

PlacedShape read_placed_geometry(const Json& value, const std::string& path) {
  require_object(value, path);
  if (find_member(value, "type") != nullptr) return PlacedShape{read_geometry(value, path), Transform::identity()};
  reject_unknown_fields(value, path, {"shape", "pose"});
  PlacedShape placed{read_geometry(require_member(value, path, "shape"), join_path(path, "shape")),
                     Transform::identity()};
  if (const Json* pose = find_member(value, "pose")) placed.pose = read_pose(*pose, join_path(path, "pose"));
  return placed;
}

std::string shape_type_names() {
  std::string names;
  for (int i = 0; i < kConvexShapeTypeCount; ++i) {
    if (i > 0) names += ", ";
    names += to_string(static_cast<ShapeType>(i));
  }
  return names;
}

Shape read_shape(const Json& value, const std::string& path) { return read_convex_shape(value, path, false); }

namespace {

Shape read_convex_shape(const Json& value, const std::string& path, bool geometry_allowed) {
  require_object(value, path);
  const std::string type_path = join_path(path, "type");
  const std::string type = read_string(require_member(value, path, "type"), type_path);
  if (type == "mesh" || type == "compound") {
    throw FieldError(
        type_path, "unsupported_geometry",
        "a " + type + " is not accepted by this operation (it takes convex shapes: " + shape_type_names() + ")");
  }

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
                   "unknown shape type \"" + type + "\" (expected one of " +
                       (geometry_allowed ? geometry_type_names() : shape_type_names()) + ")");
}

}  // namespace

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
