#include "json_bounds.hpp"

namespace proxima::tool {

void put_volume(Json& out, const Aabb& box) {
  out["min"] = to_json(box.min);
  out["max"] = to_json(box.max);
}

void put_volume(Json& out, const BoundingSphere& sphere) {
  out["center"] = to_json(sphere.center);
  out["radius"] = to_json(sphere.radius);
}

void put_volume(Json& out, const Obb& box) {
  out["center"] = to_json(box.center);
  out["axes"] = Json::array({to_json(box.axes[0]), to_json(box.axes[1]), to_json(box.axes[2])});
  out["half_extents"] = to_json(box.half_extents);
}

void put_volume(Json& out, const BoundingCapsule& capsule) {
  out["p0"] = to_json(capsule.p0);
  out["p1"] = to_json(capsule.p1);
  out["radius"] = to_json(capsule.radius);
}

template <int K>
void put_volume(Json& out, const Kdop<K>& kdop) {
  Json directions = Json::array();
  Json lo = Json::array();
  Json hi = Json::array();
  for (int i = 0; i < Kdop<K>::kSlabCount; ++i) {
    directions.push_back(to_json(Kdop<K>::direction(i)));
    lo.push_back(to_json(kdop.min[static_cast<std::size_t>(i)]));
    hi.push_back(to_json(kdop.max[static_cast<std::size_t>(i)]));
  }
  out["directions"] = std::move(directions);
  out["min"] = std::move(lo);
  out["max"] = std::move(hi);
}

template void put_volume<6>(Json&, const Kdop<6>&);
template void put_volume<14>(Json&, const Kdop<14>&);
template void put_volume<18>(Json&, const Kdop<18>&);
template void put_volume<26>(Json&, const Kdop<26>&);

void put_volume(Json& out, const ConvexHull& hull) {
  Json vertices = Json::array();
  for (const Vec3& v : hull.vertices()) vertices.push_back(to_json(v));
  Json faces = Json::array();
  for (std::uint32_t f = 0; f < hull.faces().size(); ++f) {
    Json loop = Json::array();
    for (const std::uint32_t i : hull.face_vertices(f)) loop.push_back(i);
    faces.push_back(std::move(loop));
  }
  out["vertices"] = std::move(vertices);
  out["faces"] = std::move(faces);
}

}  // namespace proxima::tool
