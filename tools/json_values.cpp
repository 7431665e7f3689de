#include "json_values.hpp"

#include <proxima/core/tolerance.hpp>

#include <charconv>
#include <cmath>
#include <cstdlib>

namespace proxima::tool {

FieldError::FieldError(std::string field, std::string code, const std::string& message)
    : std::runtime_error(field.empty() ? message : field + ": " + message),
      field_(std::move(field)),
      code_(std::move(code)) {}

std::string join_path(const std::string& path, std::string_view key) {
  if (path.empty()) return std::string(key);
  if (key.empty()) return path;
  if (key.front() == '[') return path + std::string(key);
  return path + "." + std::string(key);
}

std::string index_path(const std::string& path, std::size_t index) { return path + "[" + std::to_string(index) + "]"; }

void throw_library_error(const std::string& path, const Error& error) {
  throw FieldError(join_path(path, error.field), to_string(error.code), error.message);
}

void require_object(const Json& value, const std::string& path) {
  if (!value.is_object()) throw FieldError(path, "wrong_type", "must be a JSON object");
}

void reject_unknown_fields(const Json& value, const std::string& path,
                           std::initializer_list<std::string_view> allowed) {
  for (auto it = value.begin(); it != value.end(); ++it) {
    bool known = false;
    for (std::string_view name : allowed) known = known || it.key() == name;
    if (!known) throw FieldError(join_path(path, it.key()), "unknown_field", "unknown field");
  }
}

const Json& require_member(const Json& object, const std::string& path, std::string_view key) {
  const Json* member = find_member(object, key);
  if (member == nullptr) throw FieldError(join_path(path, key), "missing", "required field is missing");
  return *member;
}

const Json* find_member(const Json& object, std::string_view key) {
  const auto it = object.find(key);
  return it == object.end() ? nullptr : &*it;
}

double read_double(const Json& value, const std::string& path) {
  if (!value.is_number()) throw FieldError(path, "wrong_type", "must be a number");
  const double x = value.get<double>();
  if (!std::isfinite(x)) throw FieldError(path, "not_finite", "must be a finite number");
  if (std::abs(x) > static_cast<double>(kMaxCoordinate)) {
    throw FieldError(path, "out_of_range", "magnitude exceeds the supported range");
  }
  return x;
}

Real read_real(const Json& value, const std::string& path) { return static_cast<Real>(read_double(value, path)); }

Real member_real(const Json& object, const std::string& path, std::string_view key) {
  return read_real(require_member(object, path, key), join_path(path, key));
}

Json ok_answer() { return Json{{"ok", true}}; }

std::string read_string(const Json& value, const std::string& path) {
  if (!value.is_string()) throw FieldError(path, "wrong_type", "must be a string");
  return value.get<std::string>();
}

namespace {

void require_array(const Json& value, const std::string& path, std::size_t size, const char* what) {
  if (!value.is_array() || (size != 0 && value.size() != size)) {
    throw FieldError(path, "wrong_type", std::string("must be ") + what);
  }
}

}  // namespace

Vec3 read_vec3(const Json& value, const std::string& path) {
  require_array(value, path, 3, "an array of 3 numbers [x, y, z]");
  static const char* const kAxis[] = {"x", "y", "z"};
  Vec3 v;
  for (int i = 0; i < 3; ++i) v[i] = read_real(value[static_cast<std::size_t>(i)], join_path(path, kAxis[i]));
  return v;
}

Quat read_quat_xyzw(const Json& value, const std::string& path) {
  require_array(value, path, 4, "an array of 4 numbers [x, y, z, w]");
  static const char* const kAxis[] = {"x", "y", "z", "w"};
  Real c[4];
  for (int i = 0; i < 4; ++i) c[i] = read_real(value[static_cast<std::size_t>(i)], join_path(path, kAxis[i]));
  return Quat(c[3], c[0], c[1], c[2]);
}

std::vector<Vec3> read_points(const Json& value, const std::string& path, std::size_t count) {
  if (count == 0) {
    require_array(value, path, 0, "an array of points [[x, y, z], ...]");
  } else {
    require_array(value, path, count, ("an array of " + std::to_string(count) + " points [[x, y, z], ...]").c_str());
  }
  std::vector<Vec3> points;
  points.reserve(value.size());
  for (std::size_t i = 0; i < value.size(); ++i) points.push_back(read_vec3(value[i], index_path(path, i)));
  return points;
}

Json to_json(Real x) {
#if PROXIMA_DOUBLE
  return Json(x);
#else
  // Shortest decimal that reads back as this float, then that decimal as a double.
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), x);
  *result.ptr = '\0';
  return Json(std::strtod(buffer, nullptr));
#endif
}

Json to_json(const Vec3& v) { return Json::array({to_json(v.x), to_json(v.y), to_json(v.z)}); }

Json matrix_to_json(const Mat3& m) {
  Json rows = Json::array();
  for (int r = 0; r < 3; ++r) rows.push_back(Json::array({to_json(m[0][r]), to_json(m[1][r]), to_json(m[2][r])}));
  return rows;
}

}  // namespace proxima::tool
