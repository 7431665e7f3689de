#include "query_pair_ops.hpp"

#include <proxima/narrowphase/narrowphase.hpp>

#include <cmath>

#include "json_shapes.hpp"
#include "pair_names.hpp"

namespace proxima::tool {

namespace {

PlacedShape member_shape(const Json& request, std::string_view key) {
  return read_placed_geometry(require_member(request, "", key), std::string(key));
}

bool both_convex(const PlacedShape& a, const PlacedShape& b) {
  return is_convex(shape_type(a.shape)) && is_convex(shape_type(b.shape));
}

// {"child":…, "triangle":…} of a mesh or compound side (null for a convex side).
Json sub_json(const PlacedShape& side, const SubShapeId& sub) {
  if (is_convex(shape_type(side.shape))) return nullptr;
  Json j = Json::object();
  if (sub.child != kNoIndex) j["child"] = sub.child;
  if (sub.triangle != kNoIndex) j["triangle"] = sub.triangle;
  return j;
}

}  // namespace

Json op_intersect(const Json& request) {
  reject_unknown_fields(request, "", {"id", "op", "a", "b"});
  const PlacedShape a = member_shape(request, "a");
  const PlacedShape b = member_shape(request, "b");
  Json answer = Json::object();
  answer["hit"] = intersect(a.shape, a.pose, b.shape, b.pose);
  return answer;
}

Json op_distance(const Json& request) {
  reject_unknown_fields(request, "", {"id", "op", "a", "b"});
  const PlacedShape a = member_shape(request, "a");
  const PlacedShape b = member_shape(request, "b");
  const DistanceResult d = distance(a.shape, a.pose, b.shape, b.pose);
  Json answer = Json::object();
  answer["distance"] = to_json(d.signed_distance);
  answer["point_a"] = to_json(d.point_a);
  answer["point_b"] = to_json(d.point_b);
  answer["normal"] = to_json(d.normal);
  answer["status"] = status_name(d.status);
  answer["method"] = method_name(d.method);
  if (!both_convex(a, b)) {
    if (Json s = sub_json(a, d.sub_a); !s.is_null()) answer["part_a"] = std::move(s);
    if (Json s = sub_json(b, d.sub_b); !s.is_null()) answer["part_b"] = std::move(s);
  }
  return answer;
}

Json op_collide(const Json& request) {
  reject_unknown_fields(request, "", {"id", "op", "a", "b", "max_contacts", "contact_distance"});
  const PlacedShape a = member_shape(request, "a");
  const PlacedShape b = member_shape(request, "b");
  PairRequest options;
  if (const Json* m = find_member(request, "max_contacts")) {
    if (!m->is_number_integer()) throw FieldError("max_contacts", "wrong_type", "must be an integer");
    const auto n = m->get<long long>();
    if (n < 1 || n > kMaxContactPoints) throw FieldError("max_contacts", "out_of_range", "must be in 1..4");
    options.max_contacts = static_cast<int>(n);
  }
  if (const Json* c = find_member(request, "contact_distance")) {
    options.contact_distance = read_real(*c, "contact_distance");
    if (options.contact_distance < Real(0)) throw FieldError("contact_distance", "negative", "must not be negative");
  }
  const ContactManifold m = collide(a.shape, a.pose, b.shape, b.pose, options);
  Json answer = Json::object();
  answer["hit"] = m.count > 0;
  answer["normal"] = to_json(m.normal);
  Json contacts = Json::array();
  for (int i = 0; i < m.count; ++i) {
    const ContactPoint& p = m.points[static_cast<std::size_t>(i)];
    Json c = Json::object();
    c["point_a"] = to_json(p.point_a);
    c["point_b"] = to_json(p.point_b);
    c["normal"] = to_json(p.normal);
    c["depth"] = to_json(p.depth);
    contacts.push_back(std::move(c));
  }
  answer["contacts"] = std::move(contacts);
  answer["status"] = status_name(m.status);
  answer["method"] = method_name(m.method);
  return answer;
}

}  // namespace proxima::tool
