// Bounding capsule: principal axis, then tightened segment ends and radius.
//
// Steps (on the convex hull's vertices when there are many points: a capsule is convex,
// so containing them is containing all), for an axis direction a:
//  1. Project the points on the plane orthogonal to a; the axis line goes through the
//     centre of the projections' smallest enclosing circle (Welzl), so the smallest
//     admissible radius r0 is that circle's radius.
//  2. For a radius r >= r0, a point at axial coordinate s and distance rho from the line is
//     covered by a segment ending at s_hi when s - sqrt(r^2 - rho^2) <= s_hi (and
//     symmetrically for s_lo): s_hi = max(s - sqrt(r^2 - rho^2)), s_lo = min(s +
//     sqrt(r^2 - rho^2)); when s_lo > s_hi a single point in between suffices (a ball).
//  3. Larger radii shorten the segment; volume(r) = pi r^2 (s_hi - s_lo) + 4/3 pi r^3 is
//     minimised over [r0, r_ball] (r_ball covers everything with a point segment) by
//     sampling and a golden-section refinement around the best sample (coarsely while the
//     axis is searched, finely for the final axis).
//  Axis: the best of the three principal axes of the points' covariance, refined by a
//     pattern search over tilts of the axis (halving the angle when no tilt helps).
//  4. The radius is reduced to the largest distance of a point from the final segment
//     (evaluated as BoundingCapsule::contains does, nudged by ulps until all pass).
//  Bounded work: with more than 2,048 (hull) points (the hull is built only up to 8,192
//  points), the axis search runs on the points
//  extreme along 512 directions spread over the sphere; only the final fine fit along the
//  chosen axis and step 4 see every point, so the cost is O(n log n) for the hull plus a
//  fixed number of passes.
// Sources: Ericson, Real-Time Collision Detection, 4.5 (capsule/sphere-swept volumes);
// Welzl 1991 for the enclosing circle; the end-shrinking rule is the exact condition for a
// point to lie within r of the segment.
#include <proxima/bounds/fit_capsule.hpp>
#include <proxima/shapes/convex_hull.hpp>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "bounds/fit_util.hpp"
#include "bounds/obb_fit_internal.hpp"

namespace proxima {
namespace {

constexpr double kPiD = 3.14159265358979323846;

// Beyond this many (hull) points the axis search runs on the extreme points along
// kCapsuleSearchDirections directions: each of its ~250 trial axes costs a pass over the
// points, which took seconds on hulls of 100,000 vertices.
constexpr std::size_t kCapsuleSearchPoints = 2048;
constexpr int kCapsuleSearchDirections = 512;

// Beyond this many points the hull is not built (qhull's facet merging took minutes on
// 100,000 points of a sphere): the search subset comes from the points themselves.
constexpr std::size_t kCapsuleHullPoints = 8192;

struct AxisData {
  std::vector<double> s;     // axial coordinates
  std::vector<double> rho2;  // squared distances from the line
};

void segment_for_radius(const AxisData& d, double r, double& s_lo, double& s_hi) {
  s_hi = -std::numeric_limits<double>::max();
  s_lo = std::numeric_limits<double>::max();
  const double r2 = r * r;
  for (std::size_t i = 0; i < d.s.size(); ++i) {
    const double slack = std::sqrt(std::max(r2 - d.rho2[i], 0.0));
    s_hi = std::max(s_hi, d.s[i] - slack);
    s_lo = std::min(s_lo, d.s[i] + slack);
  }
}

double volume_for_radius(const AxisData& d, double r) {
  double s_lo, s_hi;
  segment_for_radius(d, r, s_lo, s_hi);
  return kPiD * r * r * (std::max(s_hi - s_lo, 0.0) + 4.0 / 3.0 * r);
}

BoundingCapsule finish_capsule(std::span<const Vec3> points, const Vec3& p0, const Vec3& p1) {
  BoundingCapsule c{p0, p1, Real(0)};
  Real r2 = Real(0);
  for (const Vec3& p : points) r2 = std::max(r2, c.distance_squared_to_core(p));
  c.radius = std::sqrt(r2);
  for (const Vec3& p : points) {
    while (!c.contains(p)) c.radius = std::nextafter(c.radius, kRealMax);
  }
  return c;
}

// The best capsule with axis direction `a` for the points (double, relative coordinates):
// steps 1-3 of the header comment.
struct AxisFit {
  double volume = std::numeric_limits<double>::max();
  glm::dvec3 p0{0.0};
  glm::dvec3 p1{0.0};
};

AxisFit fit_along_axis(std::span<const glm::dvec3> rel, const glm::dvec3& axis, std::vector<glm::dvec3>& perp,
                       bool fine) {
  const glm::dvec3 a = glm::normalize(axis);
  perp.resize(rel.size());
  for (std::size_t i = 0; i < rel.size(); ++i) perp[i] = rel[i] - glm::dot(rel[i], a) * a;
  glm::dvec3 line_point;
  double circle_r2;
  detail::minimal_ball(perp, line_point, circle_r2);
  line_point -= glm::dot(line_point, a) * a;
  AxisData d;
  d.s.resize(rel.size());
  d.rho2.resize(rel.size());
  double rho2_max = 0.0, s_min = std::numeric_limits<double>::max(), s_max = -s_min;
  for (std::size_t i = 0; i < rel.size(); ++i) {
    d.s[i] = glm::dot(rel[i], a);
    const glm::dvec3 w = perp[i] - line_point;
    d.rho2[i] = glm::dot(w, w);
    rho2_max = std::max(rho2_max, d.rho2[i]);
    s_min = std::min(s_min, d.s[i]);
    s_max = std::max(s_max, d.s[i]);
  }
  const double r0 = std::sqrt(rho2_max);
  const double half = 0.5 * (s_max - s_min);
  const double r1 = std::sqrt(rho2_max + half * half);
  // Sample, then golden-section around the best sample.
  const int samples = fine ? 16 : 6;
  double best_r = r0;
  double best_v = volume_for_radius(d, r0);
  int best_k = 0;
  for (int k = 1; k <= samples; ++k) {
    const double r = r0 + (r1 - r0) * k / samples;
    const double v = volume_for_radius(d, r);
    if (v < best_v) {
      best_v = v;
      best_r = r;
      best_k = k;
    }
  }
  if (r1 > r0) {
    double lo = r0 + (r1 - r0) * std::max(best_k - 1, 0) / samples;
    double hi = r0 + (r1 - r0) * std::min(best_k + 1, samples) / samples;
    const double g = 0.5 * (std::sqrt(5.0) - 1.0);
    double x1 = hi - g * (hi - lo), x2 = lo + g * (hi - lo);
    double f1 = volume_for_radius(d, x1), f2 = volume_for_radius(d, x2);
    for (int it = 0, iterations = fine ? 24 : 8; it < iterations; ++it) {
      if (f1 < f2) {
        hi = x2;
        x2 = x1;
        f2 = f1;
        x1 = hi - g * (hi - lo);
        f1 = volume_for_radius(d, x1);
      } else {
        lo = x1;
        x1 = x2;
        f1 = f2;
        x2 = lo + g * (hi - lo);
        f2 = volume_for_radius(d, x2);
      }
    }
    const double xm = 0.5 * (lo + hi);
    const double fm = volume_for_radius(d, xm);
    if (fm < best_v) {
      best_v = fm;
      best_r = xm;
    }
  }
  double s_lo, s_hi;
  segment_for_radius(d, best_r, s_lo, s_hi);
  if (s_lo > s_hi) s_lo = s_hi = 0.5 * (s_lo + s_hi);
  AxisFit f;
  f.volume = best_v;
  f.p0 = line_point + s_lo * a;
  f.p1 = line_point + s_hi * a;
  return f;
}

}  // namespace

Result<BoundingCapsule> fit_capsule(std::span<const Vec3> points) {
  if (auto e = detail::validate_points(points)) return *e;
  // A capsule is convex: containing the hull's vertices is containing every point.
  std::vector<Vec3> hull_vertices;
  if (points.size() > 256 && points.size() <= kCapsuleHullPoints) {
    if (auto hull = ConvexHull::create(points)) hull_vertices.assign(hull->vertices().begin(), hull->vertices().end());
  }
  const std::span<const Vec3> work = hull_vertices.empty() ? points : std::span<const Vec3>(hull_vertices);
  const glm::dvec3 origin(work[0]);
  std::vector<glm::dvec3> rel;
  rel.reserve(work.size());
  for (const Vec3& p : work) rel.push_back(glm::dvec3(p) - origin);
  const glm::dmat3 frame = detail::pca_frame_of_points(work);

  // Step 0: the best principal axis; then a pattern search on the axis direction (tilts
  // of a shrinking angle about two orthogonal directions) while the volume decreases.
  // Many points: the axis is searched on the points extreme along a fixed set of directions
  // (the hull of the subset approximates theirs), then fitted finely on all of them.
  std::vector<glm::dvec3> subset;
  if (rel.size() > kCapsuleSearchPoints) {
    for (const std::size_t i : detail::extreme_points(rel, kCapsuleSearchDirections)) subset.push_back(rel[i]);
  }
  const std::span<const glm::dvec3> search = subset.empty() ? std::span<const glm::dvec3>(rel) : subset;
  std::vector<glm::dvec3> perp;
  glm::dvec3 axis = frame[0];
  AxisFit best = fit_along_axis(search, axis, perp, false);
  for (int k = 1; k < 3; ++k) {
    const AxisFit f = fit_along_axis(search, frame[k], perp, false);
    if (f.volume < best.volume) {
      best = f;
      axis = frame[k];
    }
  }
  double angle = 0.1;
  for (int it = 0; it < 60 && angle > 2e-4; ++it) {
    const glm::dmat3 basis = detail::frame_from_axis(axis);
    bool improved = false;
    for (int k = 0; k < 4; ++k) {
      const glm::dvec3 tilt = (k < 2 ? basis[1] : basis[2]) * (k % 2 == 0 ? 1.0 : -1.0);
      const glm::dvec3 candidate = glm::normalize(std::cos(angle) * axis + std::sin(angle) * tilt);
      const AxisFit f = fit_along_axis(search, candidate, perp, false);
      if (f.volume < best.volume * (1.0 - 1e-5)) {
        best = f;
        axis = candidate;
        improved = true;
        break;
      }
    }
    if (!improved) angle *= 0.5;
  }
  best = fit_along_axis(rel, axis, perp, true);
  // Step 4: reduce the radius to the farthest point from the final segment (all points).
  return finish_capsule(points, Vec3(origin + best.p0), Vec3(origin + best.p1));
}

}  // namespace proxima
