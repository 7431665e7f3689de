// Point sets of triangle soups and indexed meshes, validated with the exact field named.
#include <proxima/bounds/triangle_soup.hpp>
#include <proxima/core/validate.hpp>

#include <string>

namespace proxima {

Result<std::vector<Vec3>> soup_points(std::span<const SoupTriangle> triangles) {
  if (triangles.empty()) return make_error(ErrorCode::TooFew, "triangles", "needs at least one triangle");
  std::vector<Vec3> out;
  out.reserve(triangles.size() * 3);
  for (std::size_t i = 0; i < triangles.size(); ++i) {
    for (std::size_t c = 0; c < 3; ++c) {
      const Vec3& p = triangles[i][c];
      if (auto e = validate::finite(p, "triangles[" + std::to_string(i) + "][" + std::to_string(c) + "]")) return *e;
      out.push_back(p);
    }
  }
  return out;
}

Result<std::vector<Vec3>> mesh_points(std::span<const Vec3> vertices,
                                      std::span<const std::array<std::uint32_t, 3>> triangles) {
  if (triangles.empty()) return make_error(ErrorCode::TooFew, "triangles", "needs at least one triangle");
  std::vector<char> used(vertices.size(), 0);
  for (std::size_t i = 0; i < triangles.size(); ++i) {
    for (std::size_t c = 0; c < 3; ++c) {
      const std::uint32_t v = triangles[i][c];
      if (v >= vertices.size()) {
        return make_error(
            ErrorCode::OutOfRange, "triangles[" + std::to_string(i) + "][" + std::to_string(c) + "]",
            "vertex index " + std::to_string(v) + " is past the " + std::to_string(vertices.size()) + " vertices");
      }
      used[v] = 1;
    }
  }
  std::vector<Vec3> out;
  for (std::size_t v = 0; v < vertices.size(); ++v) {
    if (!used[v]) continue;
    if (auto e = validate::finite(vertices[v], "vertices[" + std::to_string(v) + "]")) return *e;
    out.push_back(vertices[v]);
  }
  return out;
}

}  // namespace proxima
