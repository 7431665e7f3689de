// OBB by a minimum-volume search over the convex hull's face normals and edge directions.
//
// Steps:
//  1. Build the convex hull (qhull) and take its vertices (double, relative to vertex 0).
//  2. Candidate first axes: every face normal and every edge direction (O'Rourke's
//     characterisation: a minimum box has faces flush with hull faces or edges on hull
//     edges), plus the axis-aligned and the PCA frames as whole-frame candidates.
//  3. For a candidate axis u: project the vertices on the plane orthogonal to u, take
//     their 2-D convex hull (Andrew's monotone chain) and its minimum-area enclosing
//     rectangle by rotating calipers (the rectangle has a side on a polygon edge:
//     Freeman-Shapira); box volume = rectangle area * extent along u (measured on the
//     resulting frame).
//  2b. Hulls of more than kObbExactHullVertices vertices: steps 2-3 run on the hull of the
//     hull vertices extreme along 512 directions spread over the sphere (a Fibonacci
//     lattice), and the frames found (and that hull's PCA frame) are measured on all hull
//     vertices, beside the axis-aligned and PCA frames. More than 8,192 input points: the
//     same on the points themselves, without their exact hull. This bounds the work at
//     O(n log n) for the hull (or none) plus O(512 n) for the extremes; the box is then
//     near-minimal rather than searched exactly.
//  4. The smallest-volume frame is fitted to all the points.
// Flat inputs (no hull): the normal of the points' plane (their smallest principal axis)
// is the only candidate, so the result is the minimum-area rectangle in that plane;
// collinear and coincident inputs use the frame along the line / the axes.
// Sources: J. O'Rourke, "Finding minimal enclosing boxes", Int. J. Computer and
// Information Sciences 14(3), 1985; H. Freeman, R. Shapira, "Determining the
// minimum-area encasing rectangle for an arbitrary closed curve", CACM 18(7), 1975;
// G. Toussaint, "Solving geometric problems with the rotating calipers", MELECON 1983;
// A. M. Andrew, "Another efficient algorithm for convex hulls in two dimensions", 1979.
#include <proxima/bounds/fit_obb.hpp>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

#include <algorithm>
#include <limits>
#include <vector>

#include "bounds/fit_util.hpp"
#include "bounds/obb_fit_internal.hpp"

namespace proxima {
namespace detail {
namespace {

double cross2(const glm::dvec2& o, const glm::dvec2& a, const glm::dvec2& b) {
  return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
}

// Convex hull of 2-D points, counter-clockwise, without collinear or nearly coincident
// points (a turn must exceed a relative 1e-12 of the squared diameter: sliver edges would
// give the calipers meaningless directions).
std::vector<glm::dvec2> convex_hull_2d(std::vector<glm::dvec2> p) {
  std::sort(p.begin(), p.end(),
            [](const glm::dvec2& a, const glm::dvec2& b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
  p.erase(std::unique(p.begin(), p.end()), p.end());
  if (p.size() < 3) return p;
  const glm::dvec2 span = p.back() - p.front();
  double scale2 = glm::dot(span, span);
  for (const glm::dvec2& q : p) scale2 = std::max(scale2, glm::dot(q - p.front(), q - p.front()));
  const double eps = 1e-12 * scale2;
  std::vector<glm::dvec2> h(2 * p.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    while (k >= 2 && cross2(h[k - 2], h[k - 1], p[i]) <= eps) --k;
    h[k++] = p[i];
  }
  for (std::size_t i = p.size() - 1, t = k + 1; i-- > 0;) {
    while (k >= t && cross2(h[k - 2], h[k - 1], p[i]) <= eps) --k;
    h[k++] = p[i];
  }
  h.resize(k - 1);
  return h;
}

}  // namespace

glm::dmat3 min_area_frame_for_axis(std::span<const glm::dvec3> points, const glm::dvec3& axis, double& volume) {
  const glm::dmat3 base = frame_from_axis(axis);
  std::vector<glm::dvec2> proj;
  proj.reserve(points.size());
  for (const glm::dvec3& p : points) proj.emplace_back(glm::dot(p, base[1]), glm::dot(p, base[2]));
  const std::vector<glm::dvec2> h = convex_hull_2d(std::move(proj));
  glm::dvec2 best_dir(1.0, 0.0);
  double best_area = std::numeric_limits<double>::max();
  if (h.size() < 3) {
    // Collinear (or single) projection: the rectangle degenerates to a segment.
    if (h.size() == 2 && glm::length(h[1] - h[0]) > 0.0) best_dir = glm::normalize(h[1] - h[0]);
  } else {
    const std::size_t n = h.size();
    auto next = [n](std::size_t i) { return i + 1 == n ? 0 : i + 1; };
    std::size_t right = 0, top = 0, left = 0;  // max along edge, max height, min along edge
    for (std::size_t i = 0; i < n; ++i) {
      const glm::dvec2 e = glm::normalize(h[next(i)] - h[i]);
      const glm::dvec2 nrm(-e.y, e.x);  // inward for a CCW polygon
      if (i == 0) {
        for (std::size_t j = 0; j < n; ++j) {
          if (glm::dot(h[j], e) > glm::dot(h[right], e)) right = j;
          if (glm::dot(h[j], nrm) > glm::dot(h[top], nrm)) top = j;
          if (glm::dot(h[j], e) < glm::dot(h[left], e)) left = j;
        }
      } else {
        for (std::size_t g = 0; g < n && glm::dot(h[next(right)], e) >= glm::dot(h[right], e); ++g) right = next(right);
        for (std::size_t g = 0; g < n && glm::dot(h[next(top)], nrm) >= glm::dot(h[top], nrm); ++g) top = next(top);
        for (std::size_t g = 0; g < n && glm::dot(h[next(left)], e) <= glm::dot(h[left], e); ++g) left = next(left);
      }
      const double width = glm::dot(h[right] - h[left], e);
      const double height = glm::dot(h[top] - h[i], nrm);
      const double area = width * height;
      if (area < best_area) {
        best_area = area;
        best_dir = e;
      }
    }
  }
  glm::dmat3 f;
  f[0] = base[0];
  f[1] = glm::normalize(best_dir.x * base[1] + best_dir.y * base[2]);
  f[2] = glm::cross(f[0], f[1]);
  // The volume is measured on the frame itself, so a rounding slip of the calipers can
  // only make this candidate worse, never make it look better than it is.
  volume = frame_extent(points, f).volume;
  return f;
}

}  // namespace detail

namespace {

// Extreme directions sampled for the subset of step 2b (at most this many subset points).
constexpr int kObbSubsetDirections = 512;

// Beyond this many input points the exact hull (qhull with facet merging, which took
// minutes on 100,000 points of a sphere) is not built: step 2b runs on the points.
constexpr std::size_t kObbHullPoints = 8192;

// Steps 2-3 on one hull: every face normal and edge direction, each frame measured on `v`
// (the hull's vertices relative to an origin, in the hull's vertex order).
void search_hull_axes(const ConvexHull& hull, std::span<const glm::dvec3> v, detail::LeastFrame& best) {
  auto consider_axis = [&](const glm::dvec3& axis) {
    double volume = 0.0;
    const glm::dmat3 f = detail::min_area_frame_for_axis(v, axis, volume);
    best.offer(f, volume);
  };
  for (const HullFace& f : hull.faces()) consider_axis(glm::dvec3(f.normal));
  for (const HullEdge& e : hull.edges()) consider_axis(v[e.v1] - v[e.v0]);
}

// Step 2b: the search runs on the hull of the points of `source` extreme along a fixed set of
// directions; the frames it finds (and that hull's PCA frame) are measured on `v` (`source`
// relative to `origin`). False when the subset has no hull (flat).
bool search_extreme_subset(std::span<const Vec3> source, std::span<const glm::dvec3> v, const glm::dvec3& origin,
                           detail::LeastFrame& best) {
  std::vector<Vec3> subset;
  for (const std::size_t i : detail::extreme_points(v, kObbSubsetDirections)) subset.push_back(source[i]);
  auto sub = ConvexHull::create(subset);
  if (!sub) return false;
  std::vector<glm::dvec3> sv;
  sv.reserve(sub->vertices().size());
  for (const Vec3& p : sub->vertices()) sv.push_back(glm::dvec3(p) - origin);
  detail::LeastFrame sub_best{glm::dmat3(1.0), std::numeric_limits<double>::max()};
  search_hull_axes(*sub, sv, sub_best);
  best.offer(sub_best.frame, detail::frame_extent(v, sub_best.frame).volume);
  const glm::dmat3 pca = detail::pca_frame_of_hull(*sub);
  best.offer(pca, detail::frame_extent(v, pca).volume);
  return true;
}

std::vector<glm::dvec3> relative_to(std::span<const Vec3> points, const glm::dvec3& origin) {
  std::vector<glm::dvec3> rel;
  rel.reserve(points.size());
  for (const Vec3& p : points) rel.push_back(glm::dvec3(p) - origin);
  return rel;
}

// Flat, collinear, coincident or fewer than 4 points: the plane normal (smallest principal
// axis) with the minimum-area rectangle in the plane.
Obb fit_flat(std::span<const Vec3> points) {
  const glm::dmat3 pca = detail::pca_frame_of_points(points);
  const std::vector<glm::dvec3> rel = relative_to(points, glm::dvec3(points[0]));
  double volume = 0.0;
  const glm::dmat3 frame = detail::min_area_frame_for_axis(rel, pca[2], volume);
  return detail::fit_obb_to_frame(points, frame);
}

}  // namespace

Result<Obb> fit_obb_min_volume(std::span<const Vec3> points) {
  if (auto e = detail::validate_points(points)) return *e;
  if (points.size() > kObbHullPoints) {
    // Step 2b on the points themselves: their exact hull is not built.
    const glm::dvec3 origin(points[0]);
    const std::vector<glm::dvec3> v = relative_to(points, origin);
    detail::LeastFrame best{glm::dmat3(1.0), detail::frame_extent(v, glm::dmat3(1.0)).volume};
    if (!search_extreme_subset(points, v, origin, best)) return fit_flat(points);
    return detail::fit_obb_to_frame(points, best.frame);
  }
  auto hull = ConvexHull::create(points);
  if (!hull) return fit_flat(points);
  const std::span<const Vec3> hv = hull->vertices();
  const glm::dvec3 origin(hv[0]);
  const std::vector<glm::dvec3> v = relative_to(hv, origin);
  detail::LeastFrame best{glm::dmat3(1.0), detail::frame_extent(v, glm::dmat3(1.0)).volume};
  const glm::dmat3 pca = detail::pca_frame_of_hull(*hull);
  best.offer(pca, detail::frame_extent(v, pca).volume);
  if (v.size() <= kObbExactHullVertices) {
    search_hull_axes(*hull, v, best);
  } else {
    search_extreme_subset(hv, v, origin, best);
  }
  return detail::fit_obb_to_frame(points, best.frame);
}

}  // namespace proxima
