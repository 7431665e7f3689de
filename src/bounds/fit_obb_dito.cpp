// OBB by DiTO (ditetrahedron OBB).
//
// Steps:
//  1. Extremal points: the min and max point of the projections on the 7 (DiTO-14) or 13
//     (DiTO-26) k-DOP directions.
//  2. Base triangle: the extremal pair farthest apart (p0, p1), then the extremal point
//     farthest from the line p0p1 (p2).
//  3. The extremal points farthest below and above the base triangle's plane (q0, q1) form
//     with it a ditetrahedron of up to 7 triangles.
//  4. Each triangle gives three candidate frames: (edge, triangle normal, edge x normal).
//     A frame's quality is the surface area of the box of the extremal points in it; the
//     axis-aligned frame is a candidate too.
//  5. The best frame is fitted to all the points.
// Degenerate inputs: coincident points give the axis-aligned (zero) box, collinear ones a
// frame along the line, flat ones only the base triangle's frames.
// Source: T. Larsson, L. Kallberg, "Fast Computation of Tight-Fitting Oriented Bounding
// Boxes", Game Engine Gems 2, 2011.
#include <proxima/bounds/fit_obb.hpp>
#include <proxima/bounds/kdop.hpp>

#include <glm/geometric.hpp>

#include <vector>

#include "bounds/fit_util.hpp"

namespace proxima {

Result<Obb> fit_obb_dito(std::span<const Vec3> points, int k) {
  if (auto e = detail::validate_points(points)) return *e;
  if (k != 14 && k != 26) return make_error(ErrorCode::InvalidArgument, "k", "DiTO supports k = 14 or 26");
  const int directions = k / 2;
  const glm::dvec3 origin(points[0]);
  // 1. Extremal points.
  std::vector<glm::dvec3> extremal;
  extremal.reserve(2 * static_cast<std::size_t>(directions));
  for (int j = 0; j < directions; ++j) {
    const glm::dvec3 d(kdop_base_direction(j));
    glm::dvec3 lo_p(0.0), hi_p(0.0);
    double lo = 0.0, hi = 0.0;
    bool first = true;
    for (const Vec3& p : points) {
      const glm::dvec3 q = glm::dvec3(p) - origin;
      const double s = glm::dot(d, q);
      if (first || s < lo) {
        lo = s;
        lo_p = q;
      }
      if (first || s > hi) {
        hi = s;
        hi_p = q;
      }
      first = false;
    }
    extremal.push_back(lo_p);
    extremal.push_back(hi_p);
  }
  double scale2 = 0.0;
  for (const glm::dvec3& e : extremal) scale2 = std::max(scale2, glm::dot(e, e));
  const double tiny2 = 1e-24 * scale2;

  detail::LeastFrame best{glm::dmat3(1.0), detail::frame_extent(extremal, glm::dmat3(1.0)).area};
  auto consider = [&](const glm::dmat3& frame) { best.offer(frame, detail::frame_extent(extremal, frame).area); };

  // 2. Base triangle.
  std::size_t pair = 0;
  double pair_d2 = -1.0;
  for (std::size_t j = 0; j < extremal.size(); j += 2) {
    const glm::dvec3 d = extremal[j + 1] - extremal[j];
    if (glm::dot(d, d) > pair_d2) {
      pair_d2 = glm::dot(d, d);
      pair = j;
    }
  }
  if (pair_d2 > tiny2) {
    const glm::dvec3 p0 = extremal[pair];
    const glm::dvec3 p1 = extremal[pair + 1];
    const glm::dvec3 e0 = glm::normalize(p1 - p0);
    glm::dvec3 p2 = p0;
    double line_d2 = -1.0;
    for (const glm::dvec3& q : extremal) {
      const glm::dvec3 w = q - p0;
      const glm::dvec3 perp = w - glm::dot(w, e0) * e0;
      if (glm::dot(perp, perp) > line_d2) {
        line_d2 = glm::dot(perp, perp);
        p2 = q;
      }
    }
    if (!(line_d2 > tiny2)) {
      consider(detail::frame_from_axis(e0));  // collinear
    } else {
      // 3. Ditetrahedron.
      const glm::dvec3 n = glm::normalize(glm::cross(p1 - p0, p2 - p0));
      glm::dvec3 q0 = p0, q1 = p0;
      double lo = 0.0, hi = 0.0;
      const double base = glm::dot(n, p0);
      for (const glm::dvec3& q : extremal) {
        const double s = glm::dot(n, q) - base;
        if (s < lo) {
          lo = s;
          q0 = q;
        }
        if (s > hi) {
          hi = s;
          q1 = q;
        }
      }
      // 4. Candidate frames from each triangle's edges.
      auto triangle_frames = [&](const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
        const glm::dvec3 cr = glm::cross(b - a, c - a);
        const double len = glm::length(cr);
        if (!(len * len > tiny2 * tiny2) || !(len > 0.0)) return;
        const glm::dvec3 nt = cr / len;
        const glm::dvec3 edges[3] = {b - a, c - b, a - c};
        for (const glm::dvec3& e : edges) {
          const double el = glm::length(e);
          if (!(el > 0.0)) continue;
          const glm::dvec3 u = e / el;
          glm::dmat3 f;
          f[0] = u;
          f[1] = nt;
          f[2] = glm::cross(u, nt);
          consider(f);
        }
      };
      triangle_frames(p0, p1, p2);
      const double flat = std::sqrt(tiny2);
      if (lo < -flat) {
        triangle_frames(p0, p1, q0);
        triangle_frames(p1, p2, q0);
        triangle_frames(p2, p0, q0);
      }
      if (hi > flat) {
        triangle_frames(p0, p1, q1);
        triangle_frames(p1, p2, q1);
        triangle_frames(p2, p0, q1);
      }
    }
  }
  // 5. Fit all points.
  return detail::fit_obb_to_frame(points, best.frame);
}

}  // namespace proxima
