#include "query_shape_ops.hpp"

#include <proxima/shapes/geometry.hpp>
#include <proxima/shapes/placed.hpp>

#include <variant>

#include "json_shapes.hpp"

namespace proxima::tool {

namespace {

PlacedGeometry member_target(const Json& request) {
  return read_placed_geometry(require_member(request, "", "target"), "target");
}

// The error for a geometry an operation does not answer for.
[[noreturn]] void unsupported(const PlacedGeometry& target, const char* what) {
  const char* kind = std::holds_alternative<TriangleMesh>(target.geometry) ? "mesh" : "compound";
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
  const PlacedGeometry target = member_target(request);
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
  if (const Shape* convex = convex_shape(target.geometry); convex == nullptr) {
    const auto hit = raycast(GeometryRef(target.geometry), target.pose, ray, max_t);
    answer["hit"] = hit.has_value();
    if (hit) {
      answer["t"] = to_json(hit->hit.t);
      answer["point"] = to_json(hit->hit.point);
      answer["normal"] = to_json(hit->hit.normal);
      put_sub(answer, hit->sub);
    }
    return answer;
  }
  const Shape& shape_variant = *convex_shape(target.geometry);
  const auto hit =
      std::visit([&](const auto& shape) { return raycast(shape, target.pose, ray, max_t); }, shape_variant);
  answer["hit"] = hit.has_value();
  if (hit) {
    answer["t"] = to_json(hit->t);
    answer["point"] = to_json(hit->point);
    answer["normal"] = to_json(hit->normal);
  }
  return answer;
}

Json op_contains(const Json& request) {
  reject_unknown_fields(request, "", {"id", "op", "target", "point"});
  const PlacedGeometry target = member_target(request);
  const Vec3 point = member_point(request, "point");
  bool inside = false;
  if (const Shape* convex = convex_shape(target.geometry)) {
    inside = std::visit([&](const auto& shape) { return contains(shape, target.pose, point); }, *convex);
  } else if (const TriangleMesh* mesh = std::get_if<TriangleMesh>(&target.geometry)) {
    inside = contains(*mesh, target.pose, point);
  } else {
    unsupported(target, "point containment");
  }
  Json answer = Json::object();
  answer["inside"] = inside;
  return answer;
}

Json op_closest_point(const Json& request) {
  reject_unknown_fields(request, "", {"id", "op", "target", "point"});
  const PlacedGeometry target = member_target(request);
  const Vec3 point = member_point(request, "point");
  SurfacePoint sp;
  if (const Shape* convex = convex_shape(target.geometry)) {
    sp = std::visit([&](const auto& shape) { return closest_point(shape, target.pose, point); }, *convex);
  } else if (const TriangleMesh* mesh = std::get_if<TriangleMesh>(&target.geometry)) {
    sp = closest_point(*mesh, target.pose, point);
  } else {
    unsupported(target, "closest point");
  }
  Json answer = Json::object();
  answer["point"] = to_json(sp.point);
  answer["normal"] = to_json(sp.normal);
  answer["distance"] = to_json(sp.signed_distance);
  return answer;
}

Json op_mass(const Json& request) {
  reject_unknown_fields(request, "", {"id", "op", "target", "density"});
  const PlacedGeometry target = member_target(request);
  Real density = Real(1);
  if (const Json* d = find_member(request, "density")) {
    density = read_real(*d, "density");
    if (!(density > Real(0))) throw FieldError("density", "non_positive", "must be greater than zero");
  }
  std::optional<MassProperties> props;
  if (const TriangleMesh* mesh = std::get_if<TriangleMesh>(&target.geometry)) {
    if (!mesh->is_closed()) {
      throw FieldError("target.shape", "open_mesh",
                       "the mesh is not closed and outward oriented: it encloses no volume (see proxima mesh-info)");
    }
    props = mesh->mass_properties(density);
  } else if (const Compound* compound = std::get_if<Compound>(&target.geometry)) {
    props = compound->mass_properties(density);
  } else {
    const Shape& shape_variant = *convex_shape(target.geometry);
    props = std::visit(
        [&](const auto& shape) -> std::optional<MassProperties> {
          if constexpr (requires { shape.mass_properties(density); }) {
            return shape.mass_properties(density);
          } else {
            return std::nullopt;
          }
        },
        shape_variant);
    if (!props) {
      throw FieldError(
          "target.shape.type", "unbounded",
          std::string("a ") + to_string(shape_type(shape_variant)) + " has infinite volume and no mass properties");
    }
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
