#include "json_shapes_2d.hpp"

#include <array>
#include <string_view>
#include <vector>

namespace proxima::tool {

namespace {

constexpr std::array<std::string_view, 7> kTypes = {"circle",  "point2d", "segment2d", "capsule2d",
                                                    "polygon", "box2d",   "chain"};

Real optional_real(const Json& value, std::string_view key, const std::string& path, Real fallback) {
  const Json* m = find_member(value, key);
  return m == nullptr ? fallback : read_real(*m, join_path(path, key));
}

Vec2 optional_vec2(const Json& value, std::string_view key, const std::string& path) {
  const Json* m = find_member(value, key);
  return m == nullptr ? Vec2(Real(0)) : read_vec2(*m, join_path(path, key));
}

std::vector<Vec2> read_points_2d(const Json& value, const std::string& path, std::size_t count) {
  if (!value.is_array() || (count != 0 && value.size() != count)) {
    throw FieldError(path, "wrong_type",
                     count == 0 ? "must be an array of points [[x, y], ...]"
                                : "must be an array of " + std::to_string(count) + " points [[x, y], ...]");
  }
  std::vector<Vec2> points;
  points.reserve(value.size());
  for (std::size_t i = 0; i < value.size(); ++i) points.push_back(read_vec2(value[i], index_path(path, i)));
  return points;
}

d2::Shape read_chain(const Json& value, const std::string& path) {
  reject_unknown_fields(value, path, {"type", "points", "loop"});
  const std::vector<Vec2> points = read_points_2d(require_member(value, path, "points"), join_path(path, "points"), 0);
  bool loop = false;
  if (const Json* l = find_member(value, "loop")) {
    if (!l->is_boolean()) throw FieldError(join_path(path, "loop"), "wrong_type", "must be true or false");
    loop = l->get<bool>();
  }
  return unwrap(d2::Chain::create(points, loop), path);
}

d2::Shape read_two_point(const Json& value, const std::string& path, bool rounded) {
  if (rounded) {
    reject_unknown_fields(value, path, {"type", "vertices", "radius"});
  } else {
    reject_unknown_fields(value, path, {"type", "vertices"});
  }
  const std::vector<Vec2> v = read_points_2d(require_member(value, path, "vertices"), join_path(path, "vertices"), 2);
  if (!rounded) return unwrap(d2::Segment::create(v[0], v[1]), path);
  return unwrap(d2::Capsule::create(v[0], v[1], member_real(value, path, "radius")), path);
}

}  // namespace

bool is_2d_type_name(std::string_view name) {
  for (std::string_view t : kTypes) {
    if (t == name) return true;
  }
  return false;
}

std::string shape_2d_type_names() {
  std::string names;
  for (std::string_view t : kTypes) names += (names.empty() ? "" : ", ") + std::string(t);
  return names;
}

Vec2 read_vec2(const Json& value, const std::string& path) {
  if (!value.is_array() || value.size() != 2)
    throw FieldError(path, "wrong_type", "must be an array of 2 numbers [x, y]");
  return {read_real(value[0], join_path(path, "x")), read_real(value[1], join_path(path, "y"))};
}

Json to_json(const Vec2& v) { return Json::array({to_json(v.x), to_json(v.y)}); }

d2::Shape read_shape_2d(const Json& value, const std::string& path) {
  require_object(value, path);
  const std::string type = read_string(require_member(value, path, "type"), join_path(path, "type"));
  if (type == "circle") {
    reject_unknown_fields(value, path, {"type", "radius", "center"});
    return unwrap(d2::Circle::create(member_real(value, path, "radius"), optional_vec2(value, "center", path)), path);
  }
  if (type == "point2d") {
    reject_unknown_fields(value, path, {"type", "position"});
    return unwrap(d2::Point::create(optional_vec2(value, "position", path)), path);
  }
  if (type == "segment2d") return read_two_point(value, path, false);
  if (type == "capsule2d") return read_two_point(value, path, true);
  if (type == "polygon") {
    reject_unknown_fields(value, path, {"type", "points", "radius"});
    const std::vector<Vec2> points =
        read_points_2d(require_member(value, path, "points"), join_path(path, "points"), 0);
    return unwrap(d2::Polygon::create(points, optional_real(value, "radius", path, Real(0))), path);
  }
  if (type == "box2d") {
    reject_unknown_fields(value, path, {"type", "half_extents", "center", "angle", "radius"});
    const Vec2 h = read_vec2(require_member(value, path, "half_extents"), join_path(path, "half_extents"));
    return unwrap(
        d2::Polygon::box(h.x, h.y, optional_vec2(value, "center", path), optional_real(value, "angle", path, Real(0)),
                         optional_real(value, "radius", path, Real(0))),
        path);
  }
  if (type == "chain") return read_chain(value, path);
  throw FieldError(join_path(path, "type"), "unknown_shape", "must be one of: " + shape_2d_type_names());
}

d2::Pose read_pose_2d(const Json& value, const std::string& path) {
  require_object(value, path);
  reject_unknown_fields(value, path, {"position", "angle"});
  const Vec2 position = optional_vec2(value, "position", path);
  const Real angle = optional_real(value, "angle", path, Real(0));
  return unwrap(d2::Pose::create(position, angle), path);
}

PlacedShape2d read_placed_shape_2d(const Json& value, const std::string& path) {
  require_object(value, path);
  if (find_member(value, "type") != nullptr) return {read_shape_2d(value, path)};
  reject_unknown_fields(value, path, {"shape", "pose"});
  PlacedShape2d placed{read_shape_2d(require_member(value, path, "shape"), join_path(path, "shape"))};
  if (const Json* pose = find_member(value, "pose")) placed.pose = read_pose_2d(*pose, join_path(path, "pose"));
  return placed;
}

}  // namespace proxima::tool
