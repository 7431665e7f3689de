#pragma once
// JSON values of the world protocol (docs/world-protocol.md): object handles, 64-bit layers
// and masks, collision and query filters, kinds, continuous-detection modes, query modes, and
// the library's world errors mapped onto the request's field paths.
#include <proxima/core/result.hpp>
#include <proxima/world/collision_filter.hpp>
#include <proxima/world/collision_world.hpp>
#include <proxima/world/object_desc.hpp>
#include <proxima/world/object_handle.hpp>
#include <proxima/world/scene_query.hpp>

#include <cstdint>
#include <optional>
#include <string>

#include "json_values.hpp"

namespace proxima::tool {

/// A handle as the protocol writes it: the JSON integer ObjectHandle::to_integer().
Json handle_to_json(ObjectHandle handle);
/// A non-negative JSON integer below 2^64 (error "wrong_type" otherwise).
std::uint64_t read_u64(const Json& value, const std::string& path);
/// A handle written as handle_to_json does (any value; liveness is not checked here).
ObjectHandle read_handle(const Json& value, const std::string& path);
/// A handle of a live object of `world` (error "unknown_object" when it names none: stale,
/// never issued, or of another world).
ObjectHandle read_live_handle(const Json& value, const std::string& path, const CollisionWorld& world);
/// The member `key` of `request` as a live handle (error "missing" when absent).
ObjectHandle member_live_handle(const Json& request, std::string_view key, const CollisionWorld& world);

/// {"layer":L,"mask":M,"group":g}, each optional with CollisionFilter's defaults.
CollisionFilter read_collision_filter(const Json& value, const std::string& path);
/// {"mask":M,"group":g,"ignore":H}, each optional with QueryFilter's defaults (the ignored
/// handle need not be live).
QueryFilter read_query_filter(const Json& value, const std::string& path);
/// "static" or "moving" (error "unknown_kind").
ObjectKind read_kind(const Json& value, const std::string& path);
/// "off", "auto" or "bullet" (error "unknown_ccd").
CcdMode read_ccd(const Json& value, const std::string& path);
/// "closest", "any" or "all" (error "unknown_mode").
QueryMode read_query_mode(const Json& value, const std::string& path);
/// A JSON boolean.
bool read_bool(const Json& value, const std::string& path);

/// The request's field path of a world Error's field: "desc.pose" -> "pose" (add takes the
/// description's fields at the top level), "moves[2].pose" -> "objects[2].pose",
/// "ray.origin" -> "origin"; others unchanged.
std::string request_field(const std::string& library_field);
/// Throws the world's Error as a FieldError on request_field(error.field), prefixed by `path`.
[[noreturn]] void throw_world_error(const Error& error, const std::string& path = "");
/// Throws the Error held by `error`, if any.
void check_world(const std::optional<Error>& error, const std::string& path = "");
/// Unwraps a world Result, throwing its Error as throw_world_error does.
template <class T>
T unwrap_world(Result<T> result, const std::string& path = "") {
  if (!result.ok()) throw_world_error(result.error(), path);
  return std::move(result).value();
}

}  // namespace proxima::tool
