// The object operations of the world protocol: add, remove, move, set_*, attach, exclude.
// Every handler reads and checks the whole request before it changes the world, and the
// world's own calls apply completely or not at all, so a rejected request changes nothing.
#include <proxima/world/object_desc.hpp>

#include <algorithm>
#include <vector>

#include "json_shapes.hpp"
#include "world_json.hpp"
#include "world_ops.hpp"
#include "world_session.hpp"

namespace proxima::tool {

Json op_world_add(WorldSession& session, const Json& request) {
  reject_unknown_fields(
      request, "",
      {"id", "op", "geometry", "pose", "kind", "filter", "sensor", "ccd", "parent", "local_pose", "user_data"});
  CollisionWorld& world = session.world();
  ObjectDesc desc;
  desc.geometry = read_geometry(require_member(request, "", "geometry"), "geometry");
  const Json* parent = find_member(request, "parent");
  if (parent != nullptr && parent->is_null()) parent = nullptr;
  if (const Json* pose = find_member(request, "pose")) {
    if (parent != nullptr) {
      throw FieldError("pose", "invalid_argument", "an attached object is placed by \"local_pose\", not \"pose\"");
    }
    desc.pose = read_pose(*pose, "pose");
  }
  if (const Json* kind = find_member(request, "kind")) desc.kind = read_kind(*kind, "kind");
  if (const Json* filter = find_member(request, "filter")) desc.filter = read_collision_filter(*filter, "filter");
  if (const Json* sensor = find_member(request, "sensor")) desc.sensor = read_bool(*sensor, "sensor");
  if (const Json* ccd = find_member(request, "ccd")) desc.ccd = read_ccd(*ccd, "ccd");
  if (parent != nullptr) desc.parent = read_live_handle(*parent, "parent", world);
  if (const Json* local = find_member(request, "local_pose")) {
    if (parent == nullptr) {
      throw FieldError("local_pose", "invalid_argument", "only an attached object (with a \"parent\") has one");
    }
    desc.local_pose = read_pose(*local, "local_pose");
  }
  if (const Json* user_data = find_member(request, "user_data")) desc.user_data = read_u64(*user_data, "user_data");
  const ObjectHandle handle = unwrap_world(world.add(desc));
  Json answer = Json::object();
  answer["object"] = handle_to_json(handle);
  return answer;
}

Json op_world_remove(WorldSession& session, const Json& request) {
  reject_unknown_fields(request, "", {"id", "op", "object"});
  CollisionWorld& world = session.world();
  const ObjectHandle object = member_live_handle(request, "object", world);
  const std::vector<ObjectHandle> before = world.objects();
  check_world(world.remove(object));
  Json removed = Json::array();
  for (ObjectHandle h : before) {
    if (!world.contains(h)) removed.push_back(handle_to_json(h));
  }
  Json answer = Json::object();
  answer["removed"] = std::move(removed);
  return answer;
}

Json op_world_move(WorldSession& session, const Json& request) {
  reject_unknown_fields(request, "", {"id", "op", "object", "pose", "objects", "teleport"});
  CollisionWorld& world = session.world();
  if (const Json* list = find_member(request, "objects")) {
    if (find_member(request, "object") != nullptr || find_member(request, "pose") != nullptr) {
      throw FieldError("objects", "invalid_argument", "give either \"objects\" or \"object\" and \"pose\", not both");
    }
    if (find_member(request, "teleport") != nullptr) {
      throw FieldError("teleport", "invalid_argument", "only with \"object\" and \"pose\" (one object)");
    }
    if (!list->is_array()) throw FieldError("objects", "wrong_type", "must be an array of {\"object\":…,\"pose\":…}");
    std::vector<ObjectMove> moves;
    moves.reserve(list->size());
    for (std::size_t i = 0; i < list->size(); ++i) {
      const std::string path = index_path("objects", i);
      const Json& entry = (*list)[i];
      require_object(entry, path);
      reject_unknown_fields(entry, path, {"object", "pose"});
      const ObjectHandle h = read_live_handle(require_member(entry, path, "object"), join_path(path, "object"), world);
      moves.push_back({h, read_pose(require_member(entry, path, "pose"), join_path(path, "pose"))});
    }
    check_world(world.move(moves));
    return ok_answer();
  }
  const ObjectHandle object = member_live_handle(request, "object", world);
  const Transform pose = read_pose(require_member(request, "", "pose"), "pose");
  const Json* teleport = find_member(request, "teleport");
  const bool warp = teleport != nullptr && read_bool(*teleport, "teleport");
  check_world(warp ? world.teleport(object, pose) : world.move(object, pose));
  return ok_answer();
}

namespace {

/// A set_* operation: {"object":H, member: value}; `read(json, path)` parses the value and
/// `set(world, object, value)` applies it.
template <class Read, class Set>
Json set_property(WorldSession& session, const Json& request, const char* member, Read read, Set set) {
  reject_unknown_fields(request, "", {"id", "op", "object", member});
  const ObjectHandle object = member_live_handle(request, "object", session.world());
  const auto value = read(require_member(request, "", member), member);
  check_world(set(session.world(), object, value));
  return ok_answer();
}

}  // namespace

Json op_world_set_geometry(WorldSession& session, const Json& request) {
  return set_property(
      session, request, "geometry", [](const Json& j, const char* p) { return read_geometry(j, p); },
      [](CollisionWorld& w, ObjectHandle o, const Shape& g) { return w.set_geometry(o, g); });
}

Json op_world_set_filter(WorldSession& session, const Json& request) {
  return set_property(
      session, request, "filter", [](const Json& j, const char* p) { return read_collision_filter(j, p); },
      [](CollisionWorld& w, ObjectHandle o, const CollisionFilter& f) { return w.set_filter(o, f); });
}

Json op_world_set_kind(WorldSession& session, const Json& request) {
  return set_property(
      session, request, "kind", [](const Json& j, const char* p) { return read_kind(j, p); },
      [](CollisionWorld& w, ObjectHandle o, ObjectKind k) { return w.set_kind(o, k); });
}

Json op_world_set_ccd(WorldSession& session, const Json& request) {
  return set_property(
      session, request, "ccd", [](const Json& j, const char* p) { return read_ccd(j, p); },
      [](CollisionWorld& w, ObjectHandle o, CcdMode m) { return w.set_ccd(o, m); });
}

Json op_world_set_user_data(WorldSession& session, const Json& request) {
  return set_property(
      session, request, "user_data", [](const Json& j, const char* p) { return read_u64(j, p); },
      [](CollisionWorld& w, ObjectHandle o, std::uint64_t u) { return w.set_user_data(o, u); });
}

Json op_world_attach(WorldSession& session, const Json& request) {
  reject_unknown_fields(request, "", {"id", "op", "object", "parent", "local_pose"});
  CollisionWorld& world = session.world();
  const ObjectHandle object = member_live_handle(request, "object", world);
  const Json& parent_json = require_member(request, "", "parent");
  ObjectHandle parent{};  // null: detach
  Transform local_pose = Transform::identity();
  if (!parent_json.is_null()) {
    parent = read_live_handle(parent_json, "parent", world);
    if (const Json* local = find_member(request, "local_pose")) local_pose = read_pose(*local, "local_pose");
  } else if (find_member(request, "local_pose") != nullptr) {
    throw FieldError("local_pose", "invalid_argument", "a detached object keeps its world pose: no \"local_pose\"");
  }
  check_world(world.attach(object, parent, local_pose));
  return ok_answer();
}

Json op_world_exclude(WorldSession& session, const Json& request) {
  reject_unknown_fields(request, "", {"id", "op", "a", "b", "excluded"});
  const ObjectHandle a = member_live_handle(request, "a", session.world());
  const ObjectHandle b = member_live_handle(request, "b", session.world());
  bool excluded = true;
  if (const Json* e = find_member(request, "excluded")) excluded = read_bool(*e, "excluded");
  check_world(session.world().set_pair_excluded(a, b, excluded));
  return ok_answer();
}

}  // namespace proxima::tool
