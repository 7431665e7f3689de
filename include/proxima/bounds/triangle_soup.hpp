#pragma once
/// @file triangle_soup.hpp
/// Fitting bounding volumes to triangle soups and indexed meshes: the volumes bound the
/// triangles' corners (a convex volume containing the corners contains the triangles).

#include <proxima/core/math.hpp>
#include <proxima/core/result.hpp>

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace proxima {

/// One triangle of a soup: its three corners.
using SoupTriangle = std::array<Vec3, 3>;

/// The corners of a triangle soup as one point set (3 per triangle, in order). Errors:
/// TooFew for no triangle ("triangles"), NotFinite / OutOfRange naming the corner
/// ("triangles[4][2].y"). O(n).
Result<std::vector<Vec3>> soup_points(std::span<const SoupTriangle> triangles);

/// The vertices of an indexed mesh that some triangle uses, each once, in increasing
/// index order. Errors: TooFew for no triangle ("triangles"), OutOfRange for an index past
/// the vertex array ("triangles[4][2]"), NotFinite / OutOfRange for a used vertex
/// ("vertices[7].x"). O(n + v).
Result<std::vector<Vec3>> mesh_points(std::span<const Vec3> vertices,
                                      std::span<const std::array<std::uint32_t, 3>> triangles);

/// Applies a point-set fitter (any callable taking std::span<const Vec3> and returning a
/// Result) to the corners of a triangle soup, passing soup_points' errors through.
/// Example: fit_triangle_soup(tris, [](auto p) { return fit_obb(p, ObbFit::Dito14); }).
template <class Fitter>
auto fit_triangle_soup(std::span<const SoupTriangle> triangles, Fitter&& fitter)
    -> decltype(fitter(std::span<const Vec3>{})) {
  auto points = soup_points(triangles);
  if (!points) return points.error();
  return fitter(std::span<const Vec3>(*points));
}

/// Applies a point-set fitter to the used vertices of an indexed mesh (see mesh_points).
template <class Fitter>
auto fit_mesh(std::span<const Vec3> vertices, std::span<const std::array<std::uint32_t, 3>> triangles, Fitter&& fitter)
    -> decltype(fitter(std::span<const Vec3>{})) {
  auto points = mesh_points(vertices, triangles);
  if (!points) return points.error();
  return fitter(std::span<const Vec3>(*points));
}

}  // namespace proxima
