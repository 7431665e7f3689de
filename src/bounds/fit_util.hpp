#pragma once
// Internal helpers shared by the fitters: input validation, boxes in a given frame,
// exact-containment finishing passes. The eigen solver and frames: geometry/eigen_frame.hpp.

#include <proxima/bounds/bounding_sphere.hpp>
#include <proxima/bounds/obb.hpp>
#include <proxima/core/math.hpp>
#include <proxima/core/result.hpp>

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "geometry/eigen_frame.hpp"

namespace proxima::detail {

/// Non-empty set of finite points: TooFew "<field>" or the first bad "<field>[i].x".
std::optional<Error> validate_points(std::span<const Vec3> points, const std::string& field = "points");

/// The tightest box with axes `frame` (orthonormal columns) containing every point, in the
/// exact sense of Obb::contains.
Obb fit_obb_to_frame(std::span<const Vec3> points, const glm::dmat3& frame);

/// Surface area of the box of `points` in `frame` (DiTO's quality measure) and its volume.
struct FrameExtent {
  double area = 0.0;    ///< half surface area (ex ey + ey ez + ez ex)
  double volume = 0.0;  ///< ex ey ez
};
/// Extents of the points (any representation with operator[] -> dvec3) in `frame`.
FrameExtent frame_extent(std::span<const glm::dvec3> points, const glm::dmat3& frame);

/// The frame of least cost among those offered to a search (the first of equal ones).
struct LeastFrame {
  glm::dmat3 frame;  ///< orthonormal columns
  double cost;       ///< its cost (area, volume, ...)
  /// Keeps `f` when its cost `c` is below the best so far.
  void offer(const glm::dmat3& f, double c) {
    if (c < cost) {
      cost = c;
      frame = f;
    }
  }
};

/// Sphere centred at `center` whose radius is the smallest Real for which every point
/// passes BoundingSphere::contains.
BoundingSphere finish_sphere(std::span<const Vec3> points, const Vec3& center);

/// The indices of the points (double, any origin) extreme along `directions` directions
/// spread evenly over the sphere (a Fibonacci lattice), each once, increasing: a subset of at
/// most `directions` points whose hull approximates the points' hull. O(n directions).
std::vector<std::size_t> extreme_points(std::span<const glm::dvec3> points, int directions);

/// splitmix64: the deterministic generator behind the fitters' fixed-seed shuffles.
inline std::uint64_t splitmix64(std::uint64_t& state) {
  std::uint64_t z = (state += 0x9E3779B97F4A7C15ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

/// Minimal enclosing ball of points given in double (relative coordinates), by the
/// move-to-front Welzl algorithm with pivoting; `center` and squared radius out.
void minimal_ball(std::span<const glm::dvec3> points, glm::dvec3& center, double& radius_squared);

}  // namespace proxima::detail
