#include "query_2d_ops.hpp"

#include <proxima/d2/mass_properties.hpp>
#include <proxima/d2/narrowphase.hpp>
#include <proxima/d2/time_of_impact.hpp>

#include <cmath>
#include <initializer_list>
#include <limits>
#include <string>

#include "json_search_options.hpp"
#include "json_shapes_2d.hpp"
#include "pair_names.hpp"

namespace proxima::tool {

namespace {

PlacedShape2d member_shape(const Json& request, std::string_view key) {
  return read_placed_shape_2d(require_member(request, "", key), std::string(key));
}

void put_parts(Json& answer, d2::PartIndex a, d2::PartIndex b) {
  if (a >= 0) answer["part_a"] = Json{{"segment", a}};
  if (b >= 0) answer["part_b"] = Json{{"segment", b}};
}

Real read_non_negative(const Json& request, std::string_view key, Real fallback) {
  const Json* m = find_member(request, key);
  if (m == nullptr) return fallback;
  const Real value = read_real(*m, std::string(key));
  if (value < Real(0)) throw FieldError(std::string(key), "negative", "must not be negative");
  return value;
}

/// A side of toi: {"shape", "pose"?, "pose_end"?}, or a bare shape at rest at the identity.
struct MovingSide2d {
  d2::Shape shape;
  d2::Motion motion{};
};

MovingSide2d read_moving_side(const Json& request, std::string_view key) {
  const std::string path(key);
  const Json& value = require_member(request, "", key);
  require_object(value, path);
  if (find_member(value, "type") != nullptr) return {read_shape_2d(value, path)};
  reject_unknown_fields(value, path, {"shape", "pose", "pose_end"});
  MovingSide2d side{read_shape_2d(require_member(value, path, "shape"), join_path(path, "shape"))};
  Real angle = Real(0);
  if (const Json* pose = find_member(value, "pose")) {
    side.motion.start = read_pose_2d(*pose, join_path(path, "pose"));
    if (const Json* a = find_member(*pose, "angle")) angle = read_real(*a, join_path(path, "pose.angle"));
  }
  if (const Json* end = find_member(value, "pose_end")) {
    const d2::Pose end_pose = read_pose_2d(*end, join_path(path, "pose_end"));
    Real end_angle = Real(0);
    if (const Json* a = find_member(*end, "angle")) end_angle = read_real(*a, join_path(path, "pose_end.angle"));
    side.motion.translation = end_pose.position - side.motion.start.position;
    side.motion.rotation = end_angle - angle;
  }
  return side;
}

/// The answer of toi (with the bracket) or cast (with t), members in the 3D order.
Json toi_answer(const d2::ToiResult& r, bool bracket) {
  const bool contact = r.status == CcdStatus::Hit || r.status == CcdStatus::InitiallyOverlapping;
  Json answer = Json::object();
  answer["hit"] = contact;
  if (bracket) {
    answer["toi"] = to_json(r.toi);
    answer["toi_lower"] = to_json(r.t_lower);
    answer["toi_upper"] = to_json(r.t_upper);
  } else {
    answer["t"] = to_json(r.toi);
  }
  if (contact) {
    answer["point"] = to_json(r.point);
    answer["normal"] = to_json(r.normal);
    if (r.status == CcdStatus::InitiallyOverlapping) answer["depth"] = to_json(r.depth);
    put_parts(answer, r.part_a, r.part_b);
  }
  answer["status"] = to_string(r.status);
  answer["iterations"] = r.iterations;
  return answer;
}

}  // namespace

bool is_2d_request(const Json& request) {
  for (std::string_view key : {"a", "target"}) {
    const Json* side = find_member(request, key);
    if (side == nullptr || !side->is_object()) continue;
    const Json* shape = find_member(*side, "shape");
    const Json& s = shape != nullptr && shape->is_object() ? *shape : *side;
    const Json* type = find_member(s, "type");
    return type != nullptr && type->is_string() && is_2d_type_name(type->get<std::string>());
  }
  return false;
}

Json op_intersect_2d(const Json& request) {
  reject_unknown_fields(request, "", {"id", "op", "a", "b"});
  const PlacedShape2d a = member_shape(request, "a"), b = member_shape(request, "b");
  return Json{{"hit", d2::intersect(a.shape, a.pose, b.shape, b.pose)}};
}

Json op_distance_2d(const Json& request) {
  reject_unknown_fields(request, "", {"id", "op", "a", "b"});
  const PlacedShape2d a = member_shape(request, "a"), b = member_shape(request, "b");
  const d2::DistanceResult d = d2::distance(a.shape, a.pose, b.shape, b.pose);
  Json answer = Json::object();
  answer["distance"] = to_json(d.signed_distance);
  answer["point_a"] = to_json(d.point_a);
  answer["point_b"] = to_json(d.point_b);
  answer["normal"] = to_json(d.normal);
  answer["status"] = status_name(d.status);
  answer["method"] = method_name(d.method);
  put_parts(answer, d.part_a, d.part_b);
  return answer;
}

Json op_collide_2d(const Json& request) {
  reject_unknown_fields(request, "", {"id", "op", "a", "b", "contact_distance"});
  const PlacedShape2d a = member_shape(request, "a"), b = member_shape(request, "b");
  const Real contact_distance = read_non_negative(request, "contact_distance", Real(0));
  const d2::Manifold m = d2::collide(a.shape, a.pose, b.shape, b.pose, contact_distance);
  Json answer = Json::object();
  answer["hit"] = m.count > 0;
  answer["normal"] = to_json(m.normal);
  Json contacts = Json::array();
  for (int i = 0; i < m.count; ++i) {
    const d2::ContactPoint& p = m.points[static_cast<std::size_t>(i)];
    contacts.push_back(Json{{"point_a", to_json(p.point_a)},
                            {"point_b", to_json(p.point_b)},
                            {"normal", to_json(m.normal)},
                            {"depth", to_json(p.depth)},
                            {"feature_id", p.feature_id}});
  }
  answer["contacts"] = std::move(contacts);
  answer["method"] = method_name(m.method);
  if (m.count > 0) put_parts(answer, m.part_a, m.part_b);
  return answer;
}

Json op_raycast_2d(const Json& request) {
  reject_unknown_fields(request, "", {"id", "op", "target", "origin", "direction", "max_t"});
  const PlacedShape2d target = member_shape(request, "target");
  const d2::Ray ray{read_vec2(require_member(request, "", "origin"), "origin"),
                    read_vec2(require_member(request, "", "direction"), "direction")};
  const Real max_t = read_non_negative(request, "max_t", kRealMax);
  const auto hit = d2::raycast(target.shape, target.pose, ray, max_t);
  Json answer = Json::object();
  answer["hit"] = hit.has_value();
  if (hit) {
    answer["t"] = to_json(hit->t);
    answer["point"] = to_json(hit->point);
    answer["normal"] = to_json(hit->normal);
    if (hit->part >= 0) answer["part"] = Json{{"segment", hit->part}};
  }
  return answer;
}

Json op_contains_2d(const Json& request) {
  reject_unknown_fields(request, "", {"id", "op", "target", "point"});
  const PlacedShape2d target = member_shape(request, "target");
  const Vec2 point = read_vec2(require_member(request, "", "point"), "point");
  return Json{{"inside", d2::contains(target.shape, target.pose, point)}};
}

Json op_closest_point_2d(const Json& request) {
  reject_unknown_fields(request, "", {"id", "op", "target", "point"});
  const PlacedShape2d target = member_shape(request, "target");
  const Vec2 point = read_vec2(require_member(request, "", "point"), "point");
  const d2::SurfacePoint s = d2::closest_point(target.shape, target.pose, point);
  return Json{{"point", to_json(s.point)}, {"normal", to_json(s.normal)}, {"distance", to_json(s.signed_distance)}};
}

Json op_mass_2d(const Json& request) {
  reject_unknown_fields(request, "", {"id", "op", "target", "density"});
  const PlacedShape2d target = member_shape(request, "target");
  if (!target.shape.is_convex()) throw FieldError("target.shape", "unsupported_geometry", "a chain has no area");
  const Real density = read_non_negative(request, "density", Real(1));
  const d2::MassProperties m = d2::mass_properties(target.shape.core(), density);
  if (!std::isfinite(m.mass) || !std::isfinite(m.inertia)) {
    throw FieldError("density", "out_of_range",
                     "the mass properties at this density exceed the number range (the inertia grows as density "
                     "times size^4; docs/conventions.md, \"Limits\")");
  }
  return Json{{"area", to_json(m.area)},
              {"mass", to_json(m.mass)},
              {"centroid", to_json(target.pose.apply(m.centroid))},
              {"inertia", to_json(m.inertia)}};
}

Json op_toi_2d(const Json& request) {
  reject_unknown_fields(request, "", {"id", "op", "a", "b", "target_distance", "tolerance", "max_iterations"});
  const MovingSide2d a = read_moving_side(request, "a"), b = read_moving_side(request, "b");
  d2::ToiOptions options;
  read_search_options(request, options);
  Result<d2::ToiResult> result = d2::time_of_impact(a.shape, a.motion, b.shape, b.motion, options);
  if (!result.ok()) {
    throw_renamed(result.error(), {{"motion_a.start", "a.pose"},
                                   {"motion_a.translation", "a.pose_end.position"},
                                   {"motion_a.rotation", "a.pose_end.angle"},
                                   {"motion_b.start", "b.pose"},
                                   {"motion_b.translation", "b.pose_end.position"},
                                   {"motion_b.rotation", "b.pose_end.angle"},
                                   {"options", ""}});
  }
  return toi_answer(result.value(), true);
}

Json op_cast_2d(const Json& request) {
  reject_unknown_fields(request, "",
                        {"id", "op", "a", "translation", "b", "target_distance", "tolerance", "max_iterations"});
  const PlacedShape2d a = member_shape(request, "a"), b = member_shape(request, "b");
  const Vec2 translation = read_vec2(require_member(request, "", "translation"), "translation");
  d2::ToiOptions options;
  read_search_options(request, options);
  Result<d2::ToiResult> result = d2::shape_cast(a.shape, a.pose, translation, b.shape, b.pose, options);
  if (!result.ok()) {
    throw_renamed(result.error(), {{"motion_a.start", "a.pose"},
                                   {"motion_a.translation", "translation"},
                                   {"motion_b.start", "b.pose"},
                                   {"options", ""}});
  }
  return toi_answer(result.value(), false);
}

}  // namespace proxima::tool
