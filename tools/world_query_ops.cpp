// The scene queries of the world protocol: raycast, line_of_sight, overlap, sweep, closest.
// Field names follow `proxima query` (origin, direction, max_t, translation, point); every
// query takes an optional "filter" {"mask","group","ignore"}, and those that collect several
// answers a "mode" (closest, any, all).
#include <proxima/core/math.hpp>
#include <proxima/geometry/aabb.hpp>
#include <proxima/geometry/ray.hpp>

#include "json_shapes.hpp"
#include "world_json.hpp"
#include "world_ops.hpp"
#include "world_session.hpp"

namespace proxima::tool {

namespace {

QueryFilter member_filter(const Json& request) {
  const Json* filter = find_member(request, "filter");
  return filter == nullptr ? QueryFilter{} : read_query_filter(*filter, "filter");
}

QueryMode member_mode(const Json& request, QueryMode fallback) {
  const Json* mode = find_member(request, "mode");
  return mode == nullptr ? fallback : read_query_mode(*mode, "mode");
}

Vec3 member_point(const Json& request, std::string_view key) {
  return read_vec3(require_member(request, "", key), std::string(key));
}

Transform member_pose(const Json& request) {
  const Json* pose = find_member(request, "pose");
  return pose == nullptr ? Transform::identity() : read_pose(*pose, "pose");
}

// "child" and "triangle" of a sub-shape, where they apply (as `proxima query` writes them).
void put_sub(Json& answer, const SubShapeId& sub) {
  if (sub.child != kNoIndex) answer["child"] = sub.child;
  if (sub.triangle != kNoIndex) answer["triangle"] = sub.triangle;
}

Json hits_to_json(const std::vector<WorldHit>& hits) {
  Json list = Json::array();
  for (const WorldHit& h : hits) {
    Json hit = Json::object();
    hit["object"] = handle_to_json(h.object);
    hit["t"] = to_json(h.t);
    hit["point"] = to_json(h.point);
    hit["normal"] = to_json(h.normal);
    put_sub(hit, h.sub);
    list.push_back(std::move(hit));
  }
  Json answer = Json::object();
  answer["hits"] = std::move(list);
  return answer;
}

Json overlaps_to_json(const std::vector<WorldOverlap>& overlaps) {
  Json list = Json::array();
  for (const WorldOverlap& o : overlaps) list.push_back(handle_to_json(o.object));
  Json answer = Json::object();
  answer["objects"] = std::move(list);
  return answer;
}

}  // namespace

Json op_world_raycast(WorldSession& session, const Json& request) {
  reject_unknown_fields(request, "", {"id", "op", "origin", "direction", "max_t", "filter", "mode"});
  const Ray ray{member_point(request, "origin"), member_point(request, "direction")};
  // No max_t: the ray is unbounded, as in `proxima query` (the largest finite Real stands
  // for infinity).
  Real max_t = kRealMax;
  if (const Json* m = find_member(request, "max_t")) {
    if (!m->is_number()) throw FieldError("max_t", "wrong_type", "must be a number");
    const double value = m->get<double>();
    if (!(value >= 0.0)) throw FieldError("max_t", "negative", "must not be negative");
    max_t = value >= static_cast<double>(kRealMax) ? kRealMax : static_cast<Real>(value);
  }
  const QueryFilter filter = member_filter(request);
  const QueryMode mode = member_mode(request, QueryMode::Closest);
  const std::vector<WorldHit> hits = unwrap_world(session.world().raycast(ray, max_t, filter, mode));
  if (session.recorder()) session.recorder()->record_ray(ray, max_t, hits);
  return hits_to_json(hits);
}

Json op_world_line_of_sight(WorldSession& session, const Json& request) {
  reject_unknown_fields(request, "", {"id", "op", "from", "to", "filter"});
  const Vec3 from = member_point(request, "from");
  const Vec3 to = member_point(request, "to");
  const QueryFilter filter = member_filter(request);
  Json answer = Json::object();
  answer["clear"] = unwrap_world(session.world().line_of_sight(from, to, filter));
  return answer;
}

Json op_world_overlap(WorldSession& session, const Json& request) {
  reject_unknown_fields(request, "", {"id", "op", "geometry", "pose", "box", "point", "filter", "mode"});
  const Json* geometry = find_member(request, "geometry");
  const Json* box = find_member(request, "box");
  const Json* point = find_member(request, "point");
  const int given = (geometry != nullptr) + (box != nullptr) + (point != nullptr);
  if (given == 0)
    throw FieldError("geometry", "missing", "give one of \"geometry\" (with \"pose\"), \"box\" or \"point\"");
  if (given > 1) {
    throw FieldError(box != nullptr && geometry != nullptr ? "box" : "point", "invalid_argument",
                     "give one of \"geometry\" (with \"pose\"), \"box\" or \"point\", not several");
  }
  if (geometry == nullptr && find_member(request, "pose") != nullptr) {
    throw FieldError("pose", "invalid_argument", "only a \"geometry\" takes a pose");
  }
  const QueryFilter filter = member_filter(request);
  const QueryMode mode = member_mode(request, QueryMode::All);
  const CollisionWorld& world = session.world();
  if (geometry != nullptr) {
    const Shape shape = read_geometry(*geometry, "geometry");
    const Transform pose = member_pose(request);
    return overlaps_to_json(unwrap_world(world.overlap(shape, pose, filter, mode)));
  }
  if (box != nullptr) {
    require_object(*box, "box");
    reject_unknown_fields(*box, "box", {"min", "max"});
    const Aabb aabb{read_vec3(require_member(*box, "box", "min"), "box.min"),
                    read_vec3(require_member(*box, "box", "max"), "box.max")};
    return overlaps_to_json(unwrap_world(world.overlap_box(aabb, filter, mode)));
  }
  return overlaps_to_json(unwrap_world(world.overlap_point(read_vec3(*point, "point"), filter, mode)));
}

Json op_world_sweep(WorldSession& session, const Json& request) {
  reject_unknown_fields(request, "", {"id", "op", "geometry", "pose", "translation", "filter", "mode"});
  const Shape shape = read_shape(require_member(request, "", "geometry"), "geometry");
  const Transform pose = member_pose(request);
  const Vec3 translation = member_point(request, "translation");
  const QueryFilter filter = member_filter(request);
  const QueryMode mode = member_mode(request, QueryMode::Closest);
  return hits_to_json(unwrap_world(session.world().sweep(shape, pose, translation, filter, mode)));
}

Json op_world_closest(WorldSession& session, const Json& request) {
  reject_unknown_fields(request, "", {"id", "op", "point", "geometry", "pose", "max_distance", "filter"});
  const Json* point = find_member(request, "point");
  const Json* geometry = find_member(request, "geometry");
  if (point == nullptr && geometry == nullptr) {
    throw FieldError("point", "missing", "give \"point\", or \"geometry\" (with \"pose\")");
  }
  if (point != nullptr && geometry != nullptr) {
    throw FieldError("geometry", "invalid_argument", "give \"point\" or \"geometry\", not both");
  }
  if (point != nullptr && find_member(request, "pose") != nullptr) {
    throw FieldError("pose", "invalid_argument", "only a \"geometry\" takes a pose");
  }
  const CollisionWorld& world = session.world();
  std::optional<WorldClosest> closest;
  if (point != nullptr) {
    const Vec3 p = read_vec3(*point, "point");
    const Real max_distance = read_real(require_member(request, "", "max_distance"), "max_distance");
    closest = unwrap_world(world.closest_point(p, max_distance, member_filter(request)));
  } else {
    const Shape shape = read_geometry(*geometry, "geometry");
    const Transform pose = member_pose(request);
    const Real max_distance = read_real(require_member(request, "", "max_distance"), "max_distance");
    closest = unwrap_world(world.closest(shape, pose, max_distance, member_filter(request)));
  }
  Json answer = Json::object();
  if (!closest) {
    answer["object"] = nullptr;
    return answer;
  }
  answer["object"] = handle_to_json(closest->object);
  answer["distance"] = to_json(closest->signed_distance);
  answer["point"] = to_json(closest->point_object);
  answer["normal"] = to_json(closest->normal);
  if (geometry != nullptr) answer["point_query"] = to_json(closest->point_query);
  put_sub(answer, closest->sub);
  return answer;
}

}  // namespace proxima::tool
