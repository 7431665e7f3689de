#pragma once
// Internal: principal frames and the per-axis minimum-area rectangle shared by the OBB
// fitters.

#include <proxima/core/math.hpp>
#include <proxima/shapes/convex_hull.hpp>

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

#include <span>

namespace proxima::detail {

/// Principal axes (decreasing variance) of the hull's surface, area-weighted over its
/// triangles (Gottschalk).
glm::dmat3 pca_frame_of_hull(const ConvexHull& hull);

/// Principal axes of the points themselves (covariance about their mean).
glm::dmat3 pca_frame_of_points(std::span<const Vec3> points);

/// Best frame with first axis `axis` for the points (double, any origin): the second and
/// third axes are those of the minimum-area rectangle of the points projected on the
/// plane orthogonal to `axis` (rotating calipers). `volume` receives the box volume.
glm::dmat3 min_area_frame_for_axis(std::span<const glm::dvec3> points, const glm::dvec3& axis, double& volume);

}  // namespace proxima::detail
