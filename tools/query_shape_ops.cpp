#include "query_shape_ops.hpp"

#include <proxima/shapes/placed.hpp>
#include <proxima/shapes/shape_queries.hpp>

#include <type_traits>
#include <variant>

#include "json_shapes.hpp"

namespace proxima::tool {

namespace {

PlacedShape member_target(const Json& request) {
  return read_placed_geometry(require_member(request, "", "target"), "target");
}

// The error for a geometry an operation does not answer for.
[[noreturn]] void unsupported(const PlacedShape& target, const char* what) {
  const char* kind = std::holds_alternative<TriangleMesh>(target.shape) ? "mesh" : "compound";
  throw FieldError("target.shape.type", "unsupported_geometry", std::string("a ") + kind + " has no " + what);
}

// "child" and "triangle" of a sub-shape, where they apply.
void put_sub(Json& answer, const SubShapeId& sub) {
  if (sub.child != kNoIndex) answer["child"] = sub.child;
  if (sub.triangle != kNoIndex) answer["triangle"] = sub.triangle;
}

Vec3 member_point(const Json& request, std::string_view key) {
  return read_vec3(require_member(request, "", key), std::string(key));
}

}  // namespace

Json op_raycast(const Json& request) {
  reject_unknown_fields(request, "", {"id", "op", "target", "origin", "direction", "max_t"});
  const PlacedShape target = member_target(request);
  const Ray ray{member_point(request, "origin"), member_point(request, "direction")};
  // No max_t: the ray is unbounded. The largest finite Real stands for infinity so that no
  // arithmetic on it can produce inf - inf.
  Real max_t = kRealMax;
  if (const Json* m = find_member(request, "max_t")) {
    if (!m->is_number()) throw FieldError("max_t", "wrong_type", "must be a number");
    const double value = m->get<double>();
    if (!(value >= 0.0)) throw FieldError("max_t", "negative", "must not be negative");
    max_t = value >= static_cast<double>(kRealMax) ? kRealMax : static_cast<Real>(value);
  }
  Json answer = Json::object();
  const auto hit = raycast(target.shape, target.pose, ray, max_t);
  answer["hit"] = hit.has_value();
  if (hit) {
    answer["t"] = to_json(hit->t);
    answer["point"] = to_json(hit->point);
    answer["normal"] = to_json(hit->normal);
    put_sub(answer, hit->sub);  // the triangle of a mesh, the child of a compound
  }
  return answer;
}

Json op_contains(const Json& request) {
  reject_unknown_fields(request, "", {"id", "op", "target", "point"});
  const PlacedShape target = member_target(request);
  const Vec3 point = member_point(request, "point");
  if (std::holds_alternative<Compound>(target.shape)) unsupported(target, "point containment");
  const bool inside = std::visit(
      [&](const auto& shape) {
        if constexpr (PointQueryable<std::decay_t<decltype(shape)>>)
          return contains(shape, target.pose, point);
        else
          return false;  // a compound: refused above
      },
      target.shape);
  Json answer = Json::object();
  answer["inside"] = inside;
  return answer;
}

Json op_closest_point(const Json& request) {
  reject_unknown_fields(request, "", {"id", "op", "target", "point"});
  const PlacedShape target = member_target(request);
  const Vec3 point = member_point(request, "point");
  if (std::holds_alternative<Compound>(target.shape)) unsupported(target, "closest point");
  const SurfacePoint sp = std::visit(
      [&](const auto& shape) {
        if constexpr (PointQueryable<std::decay_t<decltype(shape)>>)
          return closest_point(shape, target.pose, point);
        else
          return SurfacePoint{};  // a compound: refused above
      },
      target.shape);
  Json answer = Json::object();
  answer["point"] = to_json(sp.point);
  answer["normal"] = to_json(sp.normal);
  answer["distance"] = to_json(sp.signed_distance);
  return answer;
}

Json op_mass(const Json& request) {
  reject_unknown_fields(request, "", {"id", "op", "target", "density"});
  const PlacedShape target = member_target(request);
  Real density = Real(1);
  if (const Json* d = find_member(request, "density")) {
    density = read_real(*d, "density");
    if (!(density > Real(0))) throw FieldError("density", "non_positive", "must be greater than zero");
  }
  std::optional<MassProperties> props;
  if (const TriangleMesh* mesh = std::get_if<TriangleMesh>(&target.shape)) {
    if (!mesh->is_closed()) {
      throw FieldError("target.shape", "open_mesh",
                       "the mesh is not closed and outward oriented: it encloses no volume (see proxima mesh-info)");
    }
    props = mesh->mass_properties(density);
  } else {
    props = std::visit(
        [&](const auto& shape) -> std::optional<MassProperties> {
          if constexpr (requires { shape.mass_properties(density); }) {
            return shape.mass_properties(density);
          } else {
            return std::nullopt;
          }
        },
        target.shape);
    if (!props) {
      throw FieldError(
          "target.shape.type", "unbounded",
          std::string("a ") + to_string(shape_type(target.shape)) + " has infinite volume and no mass properties");
    }
  }
  if (!is_finite(*props)) {
    throw FieldError("density", "out_of_range",
                     "the mass properties at this density exceed the number range (the inertia grows as density "
                     "times size^5; docs/conventions.md, \"Limits\")");
  }
  // World frame: the centroid moves with the pose, the inertia turns with it (R I R^T).
  const Mat3 r = target.pose.rotation_matrix();
  const Mat3 inertia = r * props->inertia * glm::transpose(r);
  Json answer = Json::object();
  answer["volume"] = to_json(props->volume);
  answer["mass"] = to_json(props->mass);
  answer["centroid"] = to_json(target.pose.apply(props->centroid));
  answer["inertia"] = matrix_to_json(inertia);
  return answer;
}

}  // namespace proxima::tool
