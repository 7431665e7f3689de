#pragma once
// Reading and writing the JSON values of the query protocol (numbers, vectors, quaternions,
// point lists) with errors that name the offending field by its path in the request.
#include <proxima/core/math.hpp>
#include <proxima/core/result.hpp>

#include <nlohmann/json.hpp>

#include <initializer_list>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace proxima::tool {

/// The JSON value type of the protocol: objects keep their members in insertion order, so
/// answers print "id" first.
using Json = nlohmann::ordered_json;

/// A rejected request field: `field` is its path in the request ("target.shape.radius",
/// "points[3].x"), `code` a short machine-readable reason ("missing", "wrong_type",
/// "non_positive", ...), what() is "field: message".
class FieldError : public std::runtime_error {
 public:
  /// An error on `field` with the reason `code` and a sentence `message`.
  FieldError(std::string field, std::string code, const std::string& message);
  /// Path of the offending field in the request (empty for the whole line).
  const std::string& field() const { return field_; }
  /// Short reason ("missing", "wrong_type", "unknown_field", or a library ErrorCode name).
  const std::string& code() const { return code_; }

 private:
  std::string field_;
  std::string code_;
};

/// Joins a path and a member name: ("target", "shape") -> "target.shape", ("", "id") -> "id".
std::string join_path(const std::string& path, std::string_view key);
/// Joins a path and an array index: ("points", 3) -> "points[3]".
std::string index_path(const std::string& path, std::size_t index);

/// Rethrows a library validation Error found under `path` (its field is appended to the
/// path: "target.shape" + "radius" -> "target.shape.radius").
[[noreturn]] void throw_library_error(const std::string& path, const Error& error);

/// Unwraps a library Result, throwing its Error as a FieldError under `path`.
template <class T>
T unwrap(Result<T> result, const std::string& path) {
  if (!result.ok()) throw_library_error(path, result.error());
  return std::move(result).value();
}

/// Requires `value` to be a JSON object (error "wrong_type" on `path`).
void require_object(const Json& value, const std::string& path);
/// Rejects any member of the object `value` whose name is not in `allowed`
/// (error "unknown_field" naming the member).
void reject_unknown_fields(const Json& value, const std::string& path, std::initializer_list<std::string_view> allowed);
/// The member `key` of the object `object` (error "missing" on path.key when absent).
const Json& require_member(const Json& object, const std::string& path, std::string_view key);
/// The member `key` of `object`, or nullptr when absent.
const Json* find_member(const Json& object, std::string_view key);
/// The answer {"ok": true} of a request that changes state and reports nothing else.
Json ok_answer();

/// A JSON number as double: finite (JSON cannot hold NaN or infinity; numbers beyond the
/// double range are rejected by the parser) and at most kMaxCoordinate in magnitude.
double read_double(const Json& value, const std::string& path);
/// A JSON number as Real (same checks as read_double, so it never overflows Real).
Real read_real(const Json& value, const std::string& path);
/// The member `key` of `object` read as read_real does (error "missing" when absent).
Real member_real(const Json& object, const std::string& path, std::string_view key);
/// A JSON string.
std::string read_string(const Json& value, const std::string& path);
/// A JSON array [x, y, z] of numbers; a bad component is named path.x / path.y / path.z.
Vec3 read_vec3(const Json& value, const std::string& path);
/// A JSON array [x, y, z, w] of numbers (glTF order) as a quaternion; not normalised here.
Quat read_quat_xyzw(const Json& value, const std::string& path);
/// A JSON array of `count` points (count 0: any number); element i is named path[i].
std::vector<Vec3> read_points(const Json& value, const std::string& path, std::size_t count = 0);

/// A Real as a JSON number. In the float build it is written with the shortest decimal
/// that reads back as the same float (0.1f -> 0.1, not 0.10000000149011612).
Json to_json(Real x);
/// A vector as [x, y, z].
Json to_json(const Vec3& v);
/// A 3x3 matrix as rows [[m00, m01, m02], [m10, ...], ...] (m[row][column]).
Json matrix_to_json(const Mat3& m);

}  // namespace proxima::tool
