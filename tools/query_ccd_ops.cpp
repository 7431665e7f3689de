#include "query_ccd_ops.hpp"

#include <proxima/ccd/motion.hpp>
#include <proxima/ccd/safe_step.hpp>
#include <proxima/ccd/shape_cast.hpp>
#include <proxima/ccd/time_of_impact.hpp>

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <limits>
#include <string>
#include <string_view>

#include "json_search_options.hpp"
#include "json_shapes.hpp"

namespace proxima::tool {

namespace {

// {"child":…, "triangle":…} of a mesh or compound side (null for a convex side).
Json part_json(const Shape& shape, const SubShapeId& sub) {
  if (is_convex(shape_type(shape))) return nullptr;
  Json j = Json::object();
  if (sub.child != kNoIndex) j["child"] = sub.child;
  if (sub.triangle != kNoIndex) j["triangle"] = sub.triangle;
  return j;
}

// A side of toi: {"shape", "pose"?, "pose_end"?} (no pose_end: it stays at pose), or a bare
// geometry at rest at the identity.
struct MovingSide {
  Shape shape;
  Motion motion = Motion::stationary(Transform::identity());
  bool has_end = false;
};

MovingSide read_moving_side(const Json& request, std::string_view key) {
  const std::string path(key);
  const Json& value = require_member(request, "", key);
  require_object(value, path);
  if (find_member(value, "type") != nullptr) return MovingSide{read_geometry(value, path)};
  reject_unknown_fields(value, path, {"shape", "pose", "pose_end"});
  MovingSide side{read_geometry(require_member(value, path, "shape"), join_path(path, "shape"))};
  if (const Json* pose = find_member(value, "pose")) side.motion.start = read_pose(*pose, join_path(path, "pose"));
  side.motion.end = side.motion.start;
  if (const Json* end = find_member(value, "pose_end")) {
    side.motion.end = read_pose(*end, join_path(path, "pose_end"));
    side.has_end = true;
  }
  return side;
}

// A side of safe_step: {"shape", "pose"?, "linear_velocity"?, "angular_velocity"?}, or a bare
// geometry at rest at the identity.
struct BodySide {
  Shape shape;
  Transform pose = Transform::identity();
  Vec3 linear{Real(0)};
  Vec3 angular{Real(0)};
};

BodySide read_body_side(const Json& request, std::string_view key) {
  const std::string path(key);
  const Json& value = require_member(request, "", key);
  require_object(value, path);
  if (find_member(value, "type") != nullptr) return BodySide{read_geometry(value, path)};
  reject_unknown_fields(value, path, {"shape", "pose", "linear_velocity", "angular_velocity"});
  BodySide side{read_geometry(require_member(value, path, "shape"), join_path(path, "shape"))};
  if (const Json* pose = find_member(value, "pose")) side.pose = read_pose(*pose, join_path(path, "pose"));
  if (const Json* v = find_member(value, "linear_velocity")) {
    side.linear = read_vec3(*v, join_path(path, "linear_velocity"));
  }
  if (const Json* w = find_member(value, "angular_velocity")) {
    side.angular = read_vec3(*w, join_path(path, "angular_velocity"));
  }
  return side;
}

bool read_bool(const Json& value, const std::string& path) {
  if (!value.is_boolean()) throw FieldError(path, "wrong_type", "must be true or false");
  return value.get<bool>();
}

// The contact members shared by toi and cast: point, normal, depth (overlap), part_a/part_b.
template <class R>
void add_contact(Json& answer, const R& r, const Shape& a, const Shape& b) {
  answer["point"] = to_json(r.point);
  answer["normal"] = to_json(r.normal);
  if (r.status == CcdStatus::InitiallyOverlapping) answer["depth"] = to_json(r.depth);
  if (Json p = part_json(a, r.sub_a); !p.is_null()) answer["part_a"] = std::move(p);
  if (Json p = part_json(b, r.sub_b); !p.is_null()) answer["part_b"] = std::move(p);
}

bool in_contact(CcdStatus status) { return status == CcdStatus::Hit || status == CcdStatus::InitiallyOverlapping; }

}  // namespace

Json op_toi(const Json& request) {
  reject_unknown_fields(request, "", {"id", "op", "a", "b", "target_distance", "tolerance", "max_iterations"});
  const MovingSide a = read_moving_side(request, "a");
  const MovingSide b = read_moving_side(request, "b");
  ToiOptions options;
  read_search_options(request, options);
  Result<ToiResult> result = time_of_impact(a.shape, a.motion, b.shape, b.motion, options);
  if (!result.ok()) {
    throw_renamed(result.error(), {{"motion_a.start", "a.pose"},
                                   {"motion_a.end", a.has_end ? "a.pose_end" : "a.pose"},
                                   {"motion_b.start", "b.pose"},
                                   {"motion_b.end", b.has_end ? "b.pose_end" : "b.pose"},
                                   {"options", ""}});
  }
  const ToiResult& r = result.value();
  Json answer = Json::object();
  answer["hit"] = in_contact(r.status);
  answer["toi"] = to_json(r.toi);
  answer["toi_lower"] = to_json(r.t_lower);
  answer["toi_upper"] = to_json(r.t_upper);
  if (in_contact(r.status)) add_contact(answer, r, a.shape, b.shape);
  answer["status"] = to_string(r.status);
  answer["iterations"] = r.iterations;
  return answer;
}

Json op_cast(const Json& request) {
  reject_unknown_fields(
      request, "",
      {"id", "op", "a", "translation", "b", "target_distance", "tolerance", "max_iterations", "cull_back_faces"});
  const PlacedShape a = read_placed_geometry(require_member(request, "", "a"), "a");
  const Vec3 translation = read_vec3(require_member(request, "", "translation"), "translation");
  const PlacedShape b = read_placed_geometry(require_member(request, "", "b"), "b");
  CastOptions options;
  read_search_options(request, options);
  if (const Json* c = find_member(request, "cull_back_faces"))
    options.cull_back_faces = read_bool(*c, "cull_back_faces");
  Result<CastResult> result = shape_cast(a.shape, a.pose, translation, b.shape, b.pose, options);
  if (!result.ok()) throw_renamed(result.error(), {{"pose_a", "a.pose"}, {"pose_b", "b.pose"}, {"options", ""}});
  const CastResult& r = result.value();
  Json answer = Json::object();
  answer["hit"] = in_contact(r.status);
  answer["t"] = to_json(r.t);
  if (in_contact(r.status)) add_contact(answer, r, a.shape, b.shape);
  answer["status"] = to_string(r.status);
  answer["iterations"] = r.iterations;
  return answer;
}

Json op_safe_step(const Json& request) {
  reject_unknown_fields(request, "", {"id", "op", "a", "b", "target_distance"});
  const BodySide a = read_body_side(request, "a");
  const BodySide b = read_body_side(request, "b");
  Real target = Real(0);
  if (const Json* d = find_member(request, "target_distance")) target = read_real(*d, "target_distance");
  const MovingBody body_a{a.shape, a.pose, a.linear, a.angular};
  const MovingBody body_b{b.shape, b.pose, b.linear, b.angular};
  Result<Real> result = safe_time_step(body_a, body_b, target);
  if (!result.ok()) {
    throw_renamed(result.error(), {{"a.linear", "a.linear_velocity"},
                                   {"a.angular", "a.angular_velocity"},
                                   {"b.linear", "b.linear_velocity"},
                                   {"b.angular", "b.angular_velocity"}});
  }
  const Real dt = result.value();
  Json answer = Json::object();
  answer["dt"] = std::isinf(dt) ? Json(nullptr) : to_json(dt);
  return answer;
}

}  // namespace proxima::tool
