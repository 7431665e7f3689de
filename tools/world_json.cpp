#include "world_json.hpp"

#include <limits>

namespace proxima::tool {

Json handle_to_json(ObjectHandle handle) { return Json(handle.to_integer()); }

std::uint64_t read_u64(const Json& value, const std::string& path) {
  if (value.is_number_unsigned()) return value.get<std::uint64_t>();
  if (value.is_number_integer() && value.get<std::int64_t>() >= 0) return std::uint64_t(value.get<std::int64_t>());
  throw FieldError(path, "wrong_type", "must be a non-negative integer below 2^64");
}

ObjectHandle read_handle(const Json& value, const std::string& path) {
  if (!value.is_number_integer() || (!value.is_number_unsigned() && value.get<std::int64_t>() < 0)) {
    throw FieldError(path, "wrong_type", "must be an object handle (the non-negative integer \"add\" answered)");
  }
  return ObjectHandle::from_integer(read_u64(value, path));
}

ObjectHandle read_live_handle(const Json& value, const std::string& path, const CollisionWorld& world) {
  const ObjectHandle handle = read_handle(value, path);
  if (!world.contains(handle)) {
    throw FieldError(path, "unknown_object",
                     "is not a live object of this world (removed, or never answered by \"add\")");
  }
  return handle;
}

ObjectHandle member_live_handle(const Json& request, std::string_view key, const CollisionWorld& world) {
  return read_live_handle(require_member(request, "", key), std::string(key), world);
}

CollisionFilter read_collision_filter(const Json& value, const std::string& path) {
  require_object(value, path);
  reject_unknown_fields(value, path, {"layer", "mask", "group"});
  CollisionFilter filter;
  if (const Json* layer = find_member(value, "layer")) filter.layer = read_u64(*layer, join_path(path, "layer"));
  if (const Json* mask = find_member(value, "mask")) filter.mask = read_u64(*mask, join_path(path, "mask"));
  if (const Json* group = find_member(value, "group")) {
    const std::string group_path = join_path(path, "group");
    if (!group->is_number_integer()) throw FieldError(group_path, "wrong_type", "must be an integer");
    const bool fits = group->is_number_unsigned()
                          ? group->get<std::uint64_t>() <= std::uint64_t(std::numeric_limits<std::int32_t>::max())
                          : group->get<std::int64_t>() >= std::numeric_limits<std::int32_t>::min();
    if (!fits) throw FieldError(group_path, "out_of_range", "must be a 32-bit signed integer");
    filter.group = static_cast<std::int32_t>(group->get<std::int64_t>());
  }
  return filter;
}

QueryFilter read_query_filter(const Json& value, const std::string& path) {
  require_object(value, path);
  reject_unknown_fields(value, path, {"mask", "group", "ignore"});
  // The mask and group read as a collision filter's do.
  Json as_collision = Json::object();
  if (const Json* mask = find_member(value, "mask")) as_collision["mask"] = *mask;
  if (const Json* group = find_member(value, "group")) as_collision["group"] = *group;
  const CollisionFilter read = read_collision_filter(as_collision, path);
  QueryFilter filter;
  filter.mask = read.mask;
  filter.group = read.group;
  if (const Json* ignore = find_member(value, "ignore"))
    filter.ignore = read_handle(*ignore, join_path(path, "ignore"));
  return filter;
}

namespace {

template <class E, std::size_t N>
E read_name(const Json& value, const std::string& path, const std::pair<const char*, E> (&names)[N], const char* code) {
  const std::string name = read_string(value, path);
  std::string list;
  for (const auto& [text, e] : names) {
    if (name == text) return e;
    list += list.empty() ? "" : ", ";
    list += text;
  }
  throw FieldError(path, code, "unknown value \"" + name + "\" (expected one of " + list + ")");
}

}  // namespace

ObjectKind read_kind(const Json& value, const std::string& path) {
  static const std::pair<const char*, ObjectKind> kNames[] = {{"static", ObjectKind::Static},
                                                              {"moving", ObjectKind::Moving}};
  return read_name(value, path, kNames, "unknown_kind");
}

CcdMode read_ccd(const Json& value, const std::string& path) {
  static const std::pair<const char*, CcdMode> kNames[] = {
      {"off", CcdMode::Off}, {"auto", CcdMode::Auto}, {"bullet", CcdMode::Bullet}};
  return read_name(value, path, kNames, "unknown_ccd");
}

QueryMode read_query_mode(const Json& value, const std::string& path) {
  static const std::pair<const char*, QueryMode> kNames[] = {
      {"closest", QueryMode::Closest}, {"any", QueryMode::Any}, {"all", QueryMode::All}};
  return read_name(value, path, kNames, "unknown_mode");
}

bool read_bool(const Json& value, const std::string& path) {
  if (!value.is_boolean()) throw FieldError(path, "wrong_type", "must be true or false");
  return value.get<bool>();
}

std::string request_field(const std::string& library_field) {
  const auto replace_prefix = [&](std::string_view from, std::string_view to) -> std::optional<std::string> {
    if (library_field.rfind(from, 0) != 0) return std::nullopt;
    return std::string(to) + library_field.substr(from.size());
  };
  if (auto f = replace_prefix("desc.", "")) return *f;
  if (auto f = replace_prefix("moves[", "objects[")) return *f;
  if (auto f = replace_prefix("ray.", "")) return *f;
  return library_field;
}

void throw_world_error(const Error& error, const std::string& path) {
  Error renamed = error;
  renamed.field = request_field(error.field);
  throw_library_error(path, renamed);
}

void check_world(const std::optional<Error>& error, const std::string& path) {
  if (error) throw_world_error(*error, path);
}

}  // namespace proxima::tool
