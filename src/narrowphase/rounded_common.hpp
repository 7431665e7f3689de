#pragma once
/// @file rounded_common.hpp
/// Private building blocks of the rounded pair routines (pairs_rounded.hpp): the result of
/// two cores plus radii, the pair's scale for tolerances, a point's region against a
/// cylinder, segment-box closest points, clipping a segment to a polygon's prism and the
/// feature ids of capsule and box features.

#include <proxima/core/math.hpp>
#include <proxima/core/transform.hpp>
#include <proxima/geometry/closest_points.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <initializer_list>
#include <limits>

#include "pair_support.hpp"

namespace proxima::narrow::detail {

/// Unit vector of v and its length; `fallback` (unit) and 0 when v is zero or not finite.
inline Vec3 unit_or(const Vec3& v, const Vec3& fallback, Real& length) {
  Vec3 u;
  if (unit_and_length(v, u, length)) return u;
  length = Real(0);
  return fallback;
}

/// Core offsets no longer than this are rounding noise: 16 units in the last place of the
/// pair's coordinates (`scale`, as pair_scale). Closer cores are taken as touching (core
/// distance 0, along a normal from the shapes' geometry); a longer offset is the core
/// distance, however far inside the tolerance, which sets the status, never the distance
/// (snapping every offset within the tolerance to 0 had taken capsules 0.08 apart, far from
/// the origin in float, for touching cores: 68 ulps of the pair's size off).
inline Real offset_noise(Real scale) { return Real(16) * kEpsilon * scale; }

/// Largest |coordinate| of two positions and `size`: the scale of a pair for tolerances
/// (always inlined, as unit_and_length).
[[gnu::always_inline]] inline Real pair_scale(const Transform& pose_a, const Transform& pose_b, Real size) {
  return std::max({max_abs_component(pose_a.position), max_abs_component(pose_b.position), size});
}

/// The distance result of two cores: `core_a` on A's core, `core_b` on B's, `normal` unit from
/// A to B, `core_distance` = normal . (core_b - core_a) >= 0 apart (or the core penetration,
/// < 0), radii ra and rb added.
inline DistanceResult rounded_result(const Vec3& core_a, const Vec3& core_b, const Vec3& normal, Real core_distance,
                                     Real ra, Real rb, Real tolerance) {
  DistanceResult r;
  r.signed_distance = core_distance - ra - rb;
  r.normal = normal;
  r.point_a = core_a + ra * normal;
  r.point_b = core_b - rb * normal;
  r.status = status_from_distance(r.signed_distance, tolerance);
  r.method = PairMethod::Analytic;
  r.tolerance = tolerance;
  return r;
}

/// A point against a cylinder (the cylinder's frame: axis z, radius R, half length h), seen
/// in the meridian half-plane through the point, where the cylinder is the rectangle
/// [0, R] x [-h, h] of (rho, z).
struct CylinderRegion {
  enum Kind { kRim, kBarrel, kCap };
  Kind kind = kBarrel;  ///< beyond a rim, beside the barrel, or over a cap (inside: the nearer of
                        ///< barrel and cap, ties to the cap)
  Real distance = 0;    ///< signed distance of the point to the cylinder (< 0 inside)
  Vec3 normal;          ///< outward unit normal of the nearest feature, from the axis and u
  Vec3 u;               ///< radial unit towards the point (x when it is on the axis)
  Vec3 axis;            ///< unit axis towards the point's cap (+z when z >= 0)
  Real rho = 0;         ///< the point's distance from the axis
};

/// The region of point c against the cylinder of radius R and half length h (CylinderRegion).
inline CylinderRegion cylinder_region(const Vec3& c, Real R, Real h) {
  CylinderRegion g;
  g.rho = std::sqrt(c.x * c.x + c.y * c.y);
  g.u = g.rho > Real(0) ? Vec3(c.x / g.rho, c.y / g.rho, Real(0)) : Vec3(Real(1), Real(0), Real(0));
  g.axis = Vec3(Real(0), Real(0), c.z >= Real(0) ? Real(1) : Real(-1));
  const Real over_side = g.rho - R;         // > 0: beyond the barrel
  const Real over_cap = std::abs(c.z) - h;  // > 0: beyond the cap plane
  if (over_side > Real(0) && over_cap > Real(0)) {
    g.kind = CylinderRegion::kRim;
    g.distance = std::sqrt(over_side * over_side + over_cap * over_cap);
    g.normal = (over_side / g.distance) * g.u + (over_cap / g.distance) * g.axis;
  } else if (over_side > Real(0) || (over_cap <= Real(0) && over_side > over_cap)) {
    g.kind = CylinderRegion::kBarrel;
    g.distance = over_side;
    g.normal = g.u;
  } else {
    g.kind = CylinderRegion::kCap;
    g.distance = over_cap;
    g.normal = g.axis;
  }
  return g;
}

/// Closest points of segment p0p1 and the solid box [-h, h] (box frame).
struct SegmentBoxClosest {
  Vec3 on_segment{Real(0)};         ///< point of the segment
  Vec3 on_box{Real(0)};             ///< point of the solid box (on_segment itself when inside)
  Real t = Real(0);                 ///< parameter of on_segment (p0 + t (p1 - p0))
  Real distance_squared = Real(0);  ///< |on_segment - on_box|^2
};

/// Exact closest points of a segment and a solid box [-h, h], both in the box frame. The
/// squared distance g(t) from p0 + t d to the box is convex and piecewise quadratic, with
/// breaks where the segment crosses a slab plane (at most 6); on each piece the clamped axes
/// are fixed, so its minimum is a clamped quadratic vertex. O(1), no iteration.
inline SegmentBoxClosest closest_segment_box(const Vec3& p0, const Vec3& p1, const Vec3& h) {
  const Vec3 d = p1 - p0;
  std::array<Real, 8> breaks{};
  int n = 0;
  breaks[static_cast<std::size_t>(n++)] = Real(0);
  for (int i = 0; i < 3; ++i) {
    if (d[i] == Real(0)) continue;
    for (const Real s : {Real(-1), Real(1)}) {
      const Real t = (s * h[i] - p0[i]) / d[i];
      if (t > Real(0) && t < Real(1)) breaks[static_cast<std::size_t>(n++)] = t;
    }
  }
  breaks[static_cast<std::size_t>(n++)] = Real(1);
  for (int i = 2; i < n - 1; ++i) {  // insertion sort of the inner breaks (at most 6)
    for (int j = i; j > 1 && breaks[static_cast<std::size_t>(j)] < breaks[static_cast<std::size_t>(j - 1)]; --j) {
      std::swap(breaks[static_cast<std::size_t>(j)], breaks[static_cast<std::size_t>(j - 1)]);
    }
  }
  SegmentBoxClosest best;
  best.distance_squared = std::numeric_limits<Real>::infinity();
  const auto evaluate = [&](Real t) {
    const Vec3 p = p0 + t * d;
    const Vec3 q = glm::clamp(p, -h, h);
    const Real d2 = length_squared(p - q);
    if (d2 < best.distance_squared) best = {p, q, t, d2};
  };
  for (int k = 0; k + 1 < n; ++k) {
    const Real ta = breaks[static_cast<std::size_t>(k)];
    const Real tb = breaks[static_cast<std::size_t>(k + 1)];
    const Vec3 mid = p0 + (Real(0.5) * (ta + tb)) * d;
    Real qa = Real(0);
    Real qb = Real(0);
    for (int i = 0; i < 3; ++i) {
      const Real c = mid[i] > h[i] ? h[i] : (mid[i] < -h[i] ? -h[i] : mid[i]);
      if (c == mid[i]) continue;
      qa += d[i] * d[i];
      qb += d[i] * (p0[i] - c);
    }
    const Real t = qa > Real(0) ? std::clamp(-qb / qa, ta, tb) : ta;
    evaluate(t);
    if (best.distance_squared == Real(0)) break;
  }
  evaluate(Real(1));
  return best;
}

/// Clips the segment p0 + t (p1 - p0), t in [t0, t1], to the half-space m . x <= o. Returns
/// false when nothing is left.
inline bool clip_segment(const Vec3& p0, const Vec3& p1, const Vec3& m, Real o, Real& t0, Real& t1) {
  const Real f0 = glm::dot(m, p0) - o;
  const Real f1 = glm::dot(m, p1) - o;
  if (f0 > Real(0) && f1 > Real(0)) return false;
  if (f0 > Real(0)) {
    t0 = std::max(t0, f0 / (f0 - f1));
  } else if (f1 > Real(0)) {
    t1 = std::min(t1, f0 / (f0 - f1));
  }
  return t0 <= t1;
}

/// Feature of a capsule's core at parameter t along bottom -> top: the bottom end (vertex 0),
/// the top end (vertex 1) or the side (edge 0).
inline void capsule_feature(Real t, FeatureKind& kind, std::uint32_t& index) {
  kind = t <= Real(0) ? FeatureKind::Vertex : (t >= Real(1) ? FeatureKind::Vertex : FeatureKind::Edge);
  index = t >= Real(1) ? 1u : 0u;
}

/// Feature of a box at the clamped point q of the box frame (half extents h): the number of
/// coordinates on a face plane picks the kind (3 vertex, 2 edge, else face), and the index
/// packs, per axis, 0 (not on a face), 1 (- face) or 2 (+ face) in base 3.
inline void box_feature(const Vec3& q, const Vec3& h, FeatureKind& kind, std::uint32_t& index) {
  int on = 0;
  index = 0;
  std::uint32_t weight = 1;
  for (int i = 0; i < 3; ++i) {
    const std::uint32_t c = q[i] >= h[i] ? 2u : (q[i] <= -h[i] ? 1u : 0u);
    on += c != 0u ? 1 : 0;
    index += c * weight;
    weight *= 3u;
  }
  kind = on == 3 ? FeatureKind::Vertex : (on == 2 ? FeatureKind::Edge : FeatureKind::Face);
}

}  // namespace proxima::narrow::detail

namespace proxima::narrow::detail {

/// Feature kind and index of a triangle's closest-point feature: vertices 0..2 (a, b, c),
/// edges 0 (ab), 1 (bc), 2 (ca), the face 0.
inline void triangle_feature(geometry::TriangleFeature f, FeatureKind& kind, std::uint32_t& index) {
  switch (f) {
    case geometry::TriangleFeature::VertexA: kind = FeatureKind::Vertex, index = 0; return;
    case geometry::TriangleFeature::VertexB: kind = FeatureKind::Vertex, index = 1; return;
    case geometry::TriangleFeature::VertexC: kind = FeatureKind::Vertex, index = 2; return;
    case geometry::TriangleFeature::EdgeAB: kind = FeatureKind::Edge, index = 0; return;
    case geometry::TriangleFeature::EdgeBC: kind = FeatureKind::Edge, index = 1; return;
    case geometry::TriangleFeature::EdgeCA: kind = FeatureKind::Edge, index = 2; return;
    case geometry::TriangleFeature::Face: break;
  }
  kind = FeatureKind::Face;
  index = 0;
}

}  // namespace proxima::narrow::detail
