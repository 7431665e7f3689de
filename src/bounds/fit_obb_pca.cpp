// OBB by principal component analysis of the convex hull's surface.
//
// Steps: (1) build the convex hull (qhull); (2) fan-triangulate its polygonal faces and
// accumulate, for each triangle pqr of area A and centroid m, A/12 (9 m m^T + p p^T +
// q q^T + r r^T) and A m, relative to a local origin, in double; (3) covariance =
// sum / total area - mean mean^T; (4) its eigenvectors (Jacobi) are the box axes;
// (5) the box is fitted to all points on those axes. Flat or tiny inputs, for which no hull
// exists, use the covariance of the points instead.
// Sources: S. Gottschalk, M. C. Lin, D. Manocha, "OBBTree: A Hierarchical Structure for
// Rapid Interference Detection", SIGGRAPH 1996 (continuous covariance over the hull's
// triangles); Ericson, Real-Time Collision Detection, 4.4.3.
#include <proxima/bounds/fit_obb.hpp>

#include <glm/geometric.hpp>
#include <glm/gtx/norm.hpp>

#include "bounds/fit_util.hpp"
#include "bounds/obb_fit_internal.hpp"

namespace proxima {
namespace detail {

glm::dmat3 pca_frame_of_hull(const ConvexHull& hull) {
  const std::span<const Vec3> v = hull.vertices();
  const glm::dvec3 origin(v[0]);
  double total = 0.0;
  glm::dvec3 mean(0.0);
  glm::dmat3 second(0.0);
  auto outer = [](const glm::dvec3& a, const glm::dvec3& b) {
    glm::dmat3 m;
    for (int c = 0; c < 3; ++c) m[c] = a * b[c];
    return m;
  };
  for (std::uint32_t f = 0; f < hull.faces().size(); ++f) {
    const std::span<const std::uint32_t> loop = hull.face_vertices(f);
    if (loop.size() < 3) continue;
    const glm::dvec3 p = glm::dvec3(v[loop[0]]) - origin;
    for (std::size_t k = 1; k + 1 < loop.size(); ++k) {
      const glm::dvec3 q = glm::dvec3(v[loop[k]]) - origin;
      const glm::dvec3 r = glm::dvec3(v[loop[k + 1]]) - origin;
      const double area = 0.5 * glm::length(glm::cross(q - p, r - p));
      if (!(area > 0.0)) continue;
      const glm::dvec3 m = (p + q + r) / 3.0;
      total += area;
      mean += area * m;
      second += (area / 12.0) * (9.0 * outer(m, m) + outer(p, p) + outer(q, q) + outer(r, r));
    }
  }
  if (!(total > 0.0)) return pca_frame_of_points(v);
  mean /= total;
  const glm::dmat3 cov = second / total - outer(mean, mean);
  glm::dvec3 values;
  return symmetric_eigen(cov, values);
}

glm::dmat3 pca_frame_of_points(std::span<const Vec3> points) {
  const glm::dvec3 origin(points[0]);
  glm::dvec3 mean(0.0);
  for (const Vec3& p : points) mean += glm::dvec3(p) - origin;
  mean /= static_cast<double>(points.size());
  glm::dmat3 cov(0.0);
  for (const Vec3& p : points) {
    const glm::dvec3 d = glm::dvec3(p) - origin - mean;
    for (int c = 0; c < 3; ++c) cov[c] += d * d[c];
  }
  cov /= static_cast<double>(points.size());
  glm::dvec3 values;
  return symmetric_eigen(cov, values);
}

}  // namespace detail

Result<Obb> fit_obb_pca(std::span<const Vec3> points) {
  if (auto e = detail::validate_points(points)) return *e;
  auto hull = ConvexHull::create(points);
  const glm::dmat3 frame = hull ? detail::pca_frame_of_hull(*hull) : detail::pca_frame_of_points(points);
  return detail::fit_obb_to_frame(points, frame);
}

Result<Obb> fit_obb(std::span<const Vec3> points, ObbFit method) {
  switch (method) {
    case ObbFit::Pca: return fit_obb_pca(points);
    case ObbFit::Dito14: return fit_obb_dito(points, 14);
    case ObbFit::Dito26: return fit_obb_dito(points, 26);
    case ObbFit::MinVolume: break;
  }
  return fit_obb_min_volume(points);
}

}  // namespace proxima
