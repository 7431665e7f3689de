// Shared fitting helpers: validation, boxes in a given frame, exact-containment finishing.
#include "bounds/fit_util.hpp"

#include <proxima/core/tolerance.hpp>
#include <proxima/core/validate.hpp>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace proxima::detail {

std::optional<Error> validate_points(std::span<const Vec3> points, const std::string& field) {
  if (points.empty()) return make_error(ErrorCode::TooFew, field, "needs at least one point");
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Vec3& p = points[i];
    if (is_finite(p) && std::abs(p.x) <= kMaxCoordinate && std::abs(p.y) <= kMaxCoordinate &&
        std::abs(p.z) <= kMaxCoordinate) {
      continue;
    }
    if (auto e = validate::finite(p, field + "[" + std::to_string(i) + "]")) return e;
  }
  return std::nullopt;
}

Obb fit_obb_to_frame(std::span<const Vec3> points, const glm::dmat3& frame) {
  const glm::dmat3 q = orthonormalize(frame);
  Mat3 axes;
  for (int i = 0; i < 3; ++i) axes[i] = Vec3(q[i]);
  // Centre from the projection ranges, computed in double around the first point.
  const glm::dvec3 origin(points[0]);
  glm::dvec3 lo(std::numeric_limits<double>::max());
  glm::dvec3 hi(-std::numeric_limits<double>::max());
  for (const Vec3& p : points) {
    const glm::dvec3 d = glm::dvec3(p) - origin;
    for (int i = 0; i < 3; ++i) {
      const double s = glm::dot(d, q[i]);
      lo[i] = std::min(lo[i], s);
      hi[i] = std::max(hi[i], s);
    }
  }
  glm::dvec3 c = origin;
  for (int i = 0; i < 3; ++i) c += 0.5 * (lo[i] + hi[i]) * q[i];
  Obb box{Vec3(c), axes, Vec3(Real(0))};
  // Half extents exactly as Obb::contains evaluates them.
  for (const Vec3& p : points) {
    const Vec3 d = p - box.center;
    for (int i = 0; i < 3; ++i) box.half_extents[i] = std::max(box.half_extents[i], std::abs(glm::dot(d, axes[i])));
  }
  for (const Vec3& p : points) {
    while (!box.contains(p)) {
      const Vec3 d = p - box.center;
      for (int i = 0; i < 3; ++i) {
        if (!(std::abs(glm::dot(d, axes[i])) <= box.half_extents[i])) {
          box.half_extents[i] = std::nextafter(box.half_extents[i], kRealMax);
        }
      }
    }
  }
  return box;
}

FrameExtent frame_extent(std::span<const glm::dvec3> points, const glm::dmat3& frame) {
  glm::dvec3 lo(std::numeric_limits<double>::max());
  glm::dvec3 hi(-std::numeric_limits<double>::max());
  for (const glm::dvec3& p : points) {
    for (int i = 0; i < 3; ++i) {
      const double s = glm::dot(p, frame[i]);
      lo[i] = std::min(lo[i], s);
      hi[i] = std::max(hi[i], s);
    }
  }
  const glm::dvec3 e = hi - lo;
  return {e.x * e.y + e.y * e.z + e.z * e.x, e.x * e.y * e.z};
}

BoundingSphere finish_sphere(std::span<const Vec3> points, const Vec3& center) {
  Real r2 = Real(0);
  for (const Vec3& p : points) {
    const Vec3 d = p - center;
    r2 = std::max(r2, glm::dot(d, d));
  }
  BoundingSphere s{center, std::sqrt(r2)};
  while (s.radius * s.radius < r2) s.radius = std::nextafter(s.radius, kRealMax);
  for (const Vec3& p : points) {
    while (!s.contains(p)) s.radius = std::nextafter(s.radius, kRealMax);
  }
  return s;
}

}  // namespace proxima::detail

namespace proxima::detail {

std::vector<std::size_t> extreme_points(std::span<const glm::dvec3> points, int directions) {
  const double golden = 3.14159265358979323846 * (3.0 - std::sqrt(5.0));
  std::vector<std::size_t> best(static_cast<std::size_t>(directions), 0);
  std::vector<glm::dvec3> dirs(static_cast<std::size_t>(directions));
  for (int k = 0; k < directions; ++k) {
    const double z = 1.0 - (2.0 * k + 1.0) / directions;
    const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
    dirs[std::size_t(k)] = glm::dvec3(r * std::cos(golden * k), r * std::sin(golden * k), z);
  }
  std::vector<double> top(static_cast<std::size_t>(directions), -std::numeric_limits<double>::max());
  for (std::size_t i = 0; i < points.size(); ++i) {
    for (std::size_t k = 0; k < dirs.size(); ++k) {
      const double d = glm::dot(points[i], dirs[k]);
      if (d > top[k]) {
        top[k] = d;
        best[k] = i;
      }
    }
  }
  std::sort(best.begin(), best.end());
  best.erase(std::unique(best.begin(), best.end()), best.end());
  return best;
}

}  // namespace proxima::detail
