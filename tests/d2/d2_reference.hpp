#pragma once
/// @file d2_reference.hpp
/// Independent references for the 2D narrow phase, in long double, sharing no code with the
/// library: shapes are rebuilt from their defining numbers, poses from their angles.
///   - signed distance of two rounded cores: the convex hull of every vertex difference
///     b_j - a_i is the Minkowski difference of the cores; the origin's distance to it (or,
///     inside, to its nearest edge line) is the cores' signed distance; the radii are then
///     subtracted;
///   - signed distance of a point to a rounded core: inside a polygon core the nearest edge
///     line, outside the nearest edge or vertex; minus the radius;
///   - a ray's first entry: the signed distance along a ray is convex in t, so its first
///     zero is found by a ternary search for the minimum and a bisection before it;
///   - random shapes of every convex kind with their defining numbers.

#include <proxima/d2/convex_shapes.hpp>
#include <proxima/d2/shape.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <support/random.hpp>
#include <vector>

namespace proxima::d2::test {

using LD = long double;

/// A point in long double.
struct P {
  LD x = 0, y = 0;
  P operator-(const P& o) const { return {x - o.x, y - o.y}; }
  P operator+(const P& o) const { return {x + o.x, y + o.y}; }
  P operator*(LD s) const { return {x * s, y * s}; }
};
inline LD dot(const P& a, const P& b) { return a.x * b.x + a.y * b.y; }
inline LD cross(const P& a, const P& b) { return a.x * b.y - a.y * b.x; }
inline LD norm(const P& a) { return std::sqrt(dot(a, a)); }

/// A shape's defining numbers: core vertices (local frame, counter-clockwise) and radius.
struct RefShape {
  std::vector<P> core;
  LD radius = 0;
};

/// A pose by its defining numbers.
struct RefPose {
  LD x = 0, y = 0, angle = 0;
  P apply(const P& p) const {
    const LD c = std::cos(angle), s = std::sin(angle);
    return {c * p.x - s * p.y + x, s * p.x + c * p.y + y};
  }
  Pose pose() const { return Pose::from(Vec2(Real(x), Real(y)), Real(angle)); }
};

inline std::vector<P> placed(const RefShape& s, const RefPose& pose) {
  std::vector<P> out;
  for (const P& p : s.core) out.push_back(pose.apply(p));
  return out;
}

/// Distance from the origin-free point q to segment (a, b).
inline LD point_segment_distance(const P& q, const P& a, const P& b) {
  const P e = b - a;
  const LD ee = dot(e, e);
  const LD t = ee > 0 ? std::clamp(dot(q - a, e) / ee, LD(0), LD(1)) : LD(0);
  return norm(q - (a + e * t));
}

/// Convex hull (counter-clockwise, collinear points dropped) in long double.
inline std::vector<P> hull(std::vector<P> pts) {
  std::sort(pts.begin(), pts.end(), [](const P& a, const P& b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
  pts.erase(std::unique(pts.begin(), pts.end(), [](const P& a, const P& b) { return a.x == b.x && a.y == b.y; }),
            pts.end());
  if (pts.size() < 3) return pts;
  std::vector<P> h(2 * pts.size());
  std::size_t k = 0;
  for (const P& p : pts) {
    while (k >= 2 && cross(h[k - 1] - h[k - 2], p - h[k - 2]) <= 0) --k;
    h[k++] = p;
  }
  for (std::size_t i = pts.size() - 1, lower = k + 1; i-- > 0;) {
    while (k >= lower && cross(h[k - 1] - h[k - 2], pts[i] - h[k - 2]) <= 0) --k;
    h[k++] = pts[i];
  }
  h.resize(k - 1);
  return h;
}

/// Signed distance from point q to a convex polygon given counter-clockwise by `poly`
/// (1 or 2 points: a point or a segment, never "inside").
inline LD point_polygon_signed_distance(const P& q, const std::vector<P>& poly) {
  if (poly.size() == 1) return norm(q - poly[0]);
  if (poly.size() == 2) return point_segment_distance(q, poly[0], poly[1]);
  bool inside = true;
  LD outside = std::numeric_limits<LD>::infinity(), inner = std::numeric_limits<LD>::infinity();
  for (std::size_t i = 0; i < poly.size(); ++i) {
    const P a = poly[i], b = poly[(i + 1) % poly.size()];
    const LD side = cross(b - a, q - a) / norm(b - a);  // > 0: inner side of a ccw edge
    if (side < 0) inside = false;
    inner = std::min(inner, side);
    outside = std::min(outside, point_segment_distance(q, a, b));
  }
  // Inside, the nearest boundary point is the foot on the nearest edge line, so the edge
  // distance equals the line distance; a point beyond the end of a sliver (the difference of
  // two collinear segments) can pass the edge-line test by rounding alone, and is outside.
  return inside && outside - inner <= LD(1e-12) * (1 + outside) ? -inner : outside;
}

/// Signed distance of two placed rounded shapes (the Minkowski-difference hull).
inline LD signed_distance(const RefShape& a, const RefPose& pa, const RefShape& b, const RefPose& pb) {
  const std::vector<P> wa = placed(a, pa), wb = placed(b, pb);
  std::vector<P> diff;
  for (const P& q : wb) {
    for (const P& p : wa) diff.push_back(q - p);
  }
  return point_polygon_signed_distance(P{0, 0}, hull(diff)) - a.radius - b.radius;
}

/// Signed distance from a world point to a placed rounded shape.
inline LD point_signed_distance(const RefShape& s, const RefPose& pose, const P& q) {
  return point_polygon_signed_distance(q, placed(s, pose)) - s.radius;
}

/// First t in [0, max_t] where the ray o + t d touches the shape, or -1.
inline LD ray_entry(const RefShape& s, const RefPose& pose, const P& o, const P& d, LD max_t) {
  const auto f = [&](LD t) { return point_signed_distance(s, pose, o + d * t); };
  if (f(0) <= 0) return 0;
  LD lo = 0, hi = max_t;
  for (int i = 0; i < 100; ++i) {  // ternary search for the minimum of the convex f
    const LD m1 = lo + (hi - lo) / 3, m2 = hi - (hi - lo) / 3;
    if (f(m1) < f(m2))
      hi = m2;
    else
      lo = m1;
  }
  const LD t_min = (lo + hi) / 2;
  if (f(t_min) > 0) return -1;
  lo = 0, hi = t_min;
  for (int i = 0; i < 70; ++i) {
    const LD mid = (lo + hi) / 2;
    (f(mid) > 0 ? lo : hi) = mid;
  }
  return hi;
}

/// Every convex kind (all but Chain).
inline constexpr std::array<ShapeType, 5> kConvexKinds = {ShapeType::Point, ShapeType::Circle, ShapeType::Segment,
                                                          ShapeType::Capsule, ShapeType::Polygon};

/// A random convex shape of kind `type` (every kind but Chain), about `size` across, with
/// its defining numbers.
struct RandomShape {
  Shape shape;
  RefShape ref;
};

inline RandomShape random_shape(proxima::test::Random& rng, ShapeType type, Real size) {
  RefShape ref;
  const auto point = [&] {
    const Real x = rng.uniform(-size, size);
    const Real y = rng.uniform(-size, size);
    return Vec2(x, y);
  };
  const auto to_p = [](const Vec2& v) { return P{v.x, v.y}; };
  switch (type) {
    case ShapeType::Point: {
      const Vec2 p = point() * Real(0.2);
      ref.core = {to_p(p)};
      return {Shape(Point::create(p).value()), ref};
    }
    case ShapeType::Circle: {
      const Real r = rng.uniform(Real(0.1), size);
      const Vec2 c = point() * Real(0.2);
      ref.core = {to_p(c)};
      ref.radius = r;
      return {Shape(Circle::create(r, c).value()), ref};
    }
    case ShapeType::Segment:
    case ShapeType::Capsule: {
      const Vec2 a = point();
      Vec2 b = point();
      if (length_squared(b - a) < Real(1e-4) * size * size) b = a + Vec2(size, Real(0));
      ref.core = {to_p(a), to_p(b)};
      if (type == ShapeType::Segment) return {Shape(Segment::create(a, b).value()), ref};
      const Real r = rng.uniform(Real(0.05), Real(0.5) * size);
      ref.radius = r;
      return {Shape(Capsule::create(a, b, r).value()), ref};
    }
    default: {
      const int n = rng.integer(3, kMaxPolygonVertices);
      std::vector<Vec2> pts;
      const Real base = rng.uniform(Real(0), Real(6.2831853));
      for (int i = 0; i < n; ++i) {  // on an ellipse, so every point is a hull vertex
        const Real angle =
            base + Real(6.2831853) * (static_cast<Real>(i) + rng.uniform(Real(0.1), Real(0.9))) / static_cast<Real>(n);
        pts.push_back({size * std::cos(angle), Real(0.6) * size * std::sin(angle)});
      }
      const Real r = rng.integer(0, 2) == 0 ? rng.uniform(Real(0.02), Real(0.3) * size) : Real(0);
      std::vector<P> defining;
      for (const Vec2& p : pts) defining.push_back(to_p(p));
      ref.core = hull(defining);
      ref.radius = r;
      return {Shape(Polygon::create(pts, r).value()), ref};
    }
  }
}

}  // namespace proxima::d2::test
