#include "query_bound_ops.hpp"

#include <proxima/bounds/fit_aabb.hpp>
#include <proxima/bounds/fit_capsule.hpp>
#include <proxima/bounds/fit_hull.hpp>
#include <proxima/bounds/fit_kdop.hpp>
#include <proxima/bounds/fit_obb.hpp>
#include <proxima/bounds/fit_shape.hpp>
#include <proxima/bounds/fit_shape_capsule.hpp>
#include <proxima/bounds/fit_sphere.hpp>
#include <proxima/shapes/shape_queries.hpp>

#include <string_view>
#include <variant>

#include "json_bounds.hpp"
#include "json_shapes.hpp"

namespace proxima::tool {

namespace {

constexpr std::string_view kBoundVolumes[] = {"aabb",  "sphere", "obb",    "capsule",
                                              "kdop6", "kdop14", "kdop18", "kdop26"};
constexpr std::string_view kFitVolumes[] = {"aabb",  "sphere",  "sphere_centroid", "sphere_aabb", "sphere_ritter",
                                            "obb",   "obb_pca", "obb_dito14",      "obb_dito26",  "capsule",
                                            "kdop6", "kdop14",  "kdop18",          "kdop26",      "hull"};

template <std::size_t N>
std::string read_volume_name(const Json& request, const std::string_view (&allowed)[N]) {
  std::string name = read_string(require_member(request, "", "volume"), "volume");
  std::string list;
  for (std::string_view v : allowed) {
    if (v == name) return name;
    list += list.empty() ? "" : ", ";
    list += v;
  }
  throw FieldError("volume", "unknown_volume", "unknown volume \"" + name + "\" (expected one of " + list + ")");
}

template <class V>
Json fitted(const std::string& name, Result<V> result) {
  const V volume = unwrap(std::move(result), "");
  Json answer = Json::object();
  answer["volume"] = name;
  put_volume(answer, volume);
  if constexpr (std::is_same_v<V, ConvexHull>) {
    answer["volume_m3"] = to_json(volume.mass_properties(Real(1)).volume);
  } else {
    answer["volume_m3"] = to_json(volume.volume());
  }
  return answer;
}

}  // namespace

namespace {

// Bounds of a mesh from its world vertices (the hull of the vertices is the hull of the mesh);
// a compound has its box only.
Json geometry_bound(const PlacedShape& target, const std::string& name) {
  Json answer = Json::object();
  answer["volume"] = name;
  if (name == "aabb") {
    put_volume(answer, world_aabb(target.shape, target.pose));
    return answer;
  }
  const TriangleMesh* mesh = std::get_if<TriangleMesh>(&target.shape);
  if (mesh == nullptr) {
    throw FieldError("volume", "unsupported_geometry", "a compound has only the aabb bound");
  }
  std::vector<Vec3> points;
  points.reserve(mesh->vertices().size());
  for (const Vec3& v : mesh->vertices()) points.push_back(target.pose.apply(v));
  if (name == "sphere") put_volume(answer, unwrap(fit_sphere_minimal(points), "target"));
  if (name == "obb") put_volume(answer, unwrap(fit_obb(points, ObbFit::MinVolume), "target"));
  if (name == "capsule") put_volume(answer, unwrap(fit_capsule(points), "target"));
  if (name == "kdop6") put_volume(answer, unwrap(fit_kdop<6>(points), "target"));
  if (name == "kdop14") put_volume(answer, unwrap(fit_kdop<14>(points), "target"));
  if (name == "kdop18") put_volume(answer, unwrap(fit_kdop<18>(points), "target"));
  if (name == "kdop26") put_volume(answer, unwrap(fit_kdop<26>(points), "target"));
  return answer;
}

}  // namespace

Json op_bound(const Json& request) {
  reject_unknown_fields(request, "", {"id", "op", "target", "volume"});
  const PlacedShape target = read_placed_geometry(require_member(request, "", "target"), "target");
  const std::string name = read_volume_name(request, kBoundVolumes);
  if (!is_convex(shape_type(target.shape))) return geometry_bound(target, name);
  Json answer = Json::object();
  answer["volume"] = name;
  const Transform& pose = target.pose;
  std::visit(
      [&](const auto& shape) {
        using S = std::decay_t<decltype(shape)>;
        if constexpr (!is_convex(kShapeTypeOf<S>)) {
          return;  // answered by geometry_bound above
        } else {
          if (name == "aabb") return put_volume(answer, fit_shape_aabb(shape, pose));
          if (name == "sphere") return put_volume(answer, fit_shape_sphere(shape, pose));
          if constexpr (S::kType == ShapeType::HalfSpace) {
            throw FieldError("target.shape.type", "unbounded",
                             "a halfspace is unbounded: only the aabb and sphere bounds exist");
          } else {
            if (name == "obb") return put_volume(answer, fit_shape_obb(shape, pose));
            if (name == "capsule") return put_volume(answer, fit_shape_capsule(shape, pose));
            if (name == "kdop6") return put_volume(answer, fit_shape_kdop<6>(shape, pose));
            if (name == "kdop14") return put_volume(answer, fit_shape_kdop<14>(shape, pose));
            if (name == "kdop18") return put_volume(answer, fit_shape_kdop<18>(shape, pose));
            return put_volume(answer, fit_shape_kdop<26>(shape, pose));
          }
        }
      },
      target.shape);
  return answer;
}

Json op_fit(const Json& request) {
  reject_unknown_fields(request, "", {"id", "op", "points", "volume"});
  const std::vector<Vec3> points = read_points(require_member(request, "", "points"), "points");
  const std::string name = read_volume_name(request, kFitVolumes);
  // Library errors name "points" or "points[i].x", which is also the request's field.
  if (name == "aabb") {
    const Aabb box = unwrap(fit_aabb(points), "");
    Json answer = Json::object();
    answer["volume"] = name;
    put_volume(answer, box);
    answer["volume_m3"] = to_json(box.volume());
    return answer;
  }
  if (name == "sphere") return fitted(name, fit_sphere_minimal(points));
  if (name == "sphere_centroid") return fitted(name, fit_sphere_centroid(points));
  if (name == "sphere_aabb") return fitted(name, fit_sphere_aabb_center(points));
  if (name == "sphere_ritter") return fitted(name, fit_sphere_ritter(points));
  if (name == "obb") return fitted(name, fit_obb(points, ObbFit::MinVolume));
  if (name == "obb_pca") return fitted(name, fit_obb_pca(points));
  if (name == "obb_dito14") return fitted(name, fit_obb_dito(points, 14));
  if (name == "obb_dito26") return fitted(name, fit_obb_dito(points, 26));
  if (name == "capsule") return fitted(name, fit_capsule(points));
  if (name == "kdop6") return fitted(name, fit_kdop<6>(points));
  if (name == "kdop14") return fitted(name, fit_kdop<14>(points));
  if (name == "kdop18") return fitted(name, fit_kdop<18>(points));
  if (name == "kdop26") return fitted(name, fit_kdop<26>(points));
  return fitted(name, fit_hull(points));
}

}  // namespace proxima::tool
