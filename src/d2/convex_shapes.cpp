/// @file convex_shapes.cpp
/// Validated construction of the 2D convex shapes and their cores.
///
/// Polygon hull (Andrew's monotone chain, Computational Geometry, de Berg et al. §1.1):
///   1. sort the points by (x, y);
///   2. build the lower and the upper chain, popping a vertex while the last turn is not
///      strictly counter-clockwise beyond a weld tolerance (so collinear and near-duplicate
///      points are dropped);
///   3. check that 3..16 vertices enclose an area, then fill the normals and the centroid.
/// Polygon::restore keeps given vertices in their order after checking that each lies
/// strictly left of every edge it is not on (O(n^2), n <= 16).

#include <proxima/core/tolerance.hpp>
#include <proxima/core/validate.hpp>
#include <proxima/d2/convex_shapes.hpp>

#include <algorithm>
#include <string>
#include <vector>

namespace proxima::d2 {
namespace {

std::optional<Error> check_point(const Vec2& p, const std::string& field) {
  if (!is_finite(p)) return Error{ErrorCode::NotFinite, field, "must be finite"};
  if (max_abs_component(p) > kMaxCoordinate) {
    return Error{ErrorCode::OutOfRange, field, "must be within kMaxCoordinate"};
  }
  return std::nullopt;
}

ConvexCore make_core(std::initializer_list<Vec2> vertices, Real radius) {
  ConvexCore core;
  core.count = 0;
  for (const Vec2& v : vertices) core.vertices[core.count++] = v;
  core.radius = radius;
  compute_core_normals(core);
  return core;
}

/// Twice the signed area of triangle (o, a, b), > 0 when counter-clockwise.
Real turn(const Vec2& o, const Vec2& a, const Vec2& b) { return cross(a - o, b - o); }

/// The convex hull of `points`, counter-clockwise, without collinear or welded vertices.
std::vector<Vec2> monotone_chain_hull(std::span<const Vec2> points) {
  std::vector<Vec2> sorted(points.begin(), points.end());
  std::sort(sorted.begin(), sorted.end(),
            [](const Vec2& a, const Vec2& b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
  Real scale = Real(0);
  for (const Vec2& p : sorted) scale = std::max(scale, max_abs_component(p));
  // A turn counts only beyond the precision's weld tolerance on the points' scale.
  const Real weld = Real(16) * kEpsilon * scale * scale + std::numeric_limits<Real>::min();
  std::vector<Vec2> hull(2 * sorted.size() + 1);
  std::size_t k = 0;
  for (const Vec2& p : sorted) {  // lower chain
    while (k >= 2 && turn(hull[k - 2], hull[k - 1], p) <= weld) --k;
    hull[k++] = p;
  }
  const std::size_t lower = k + 1;
  for (std::size_t i = sorted.size() - 1; i-- > 0;) {  // upper chain
    while (k >= lower && turn(hull[k - 2], hull[k - 1], sorted[i]) <= weld) --k;
    hull[k++] = sorted[i];
  }
  hull.resize(k > 1 ? k - 1 : k);  // the last point repeats the first
  return hull;
}

/// True when every vertex not on an edge lies strictly left of it (turn > 0).
bool strictly_convex(std::span<const Vec2> v) {
  const std::size_t n = v.size();
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t k = 0; k < n; ++k) {
      if (k != i && k != (i + 1) % n && !(turn(v[i], v[(i + 1) % n], v[k]) > Real(0))) return false;
    }
  }
  return true;
}

/// Area centroid of a counter-clockwise polygon (triangle fan about vertex 0).
Vec2 polygon_centroid(const ConvexCore& core) {
  Real area = Real(0);
  Vec2 sum(Real(0));
  const Vec2 origin = core.vertices[0];
  for (int i = 1; i + 1 < core.count; ++i) {
    const Vec2 e1 = core.vertices[i] - origin;
    const Vec2 e2 = core.vertices[i + 1] - origin;
    const Real a = Real(0.5) * cross(e1, e2);
    area += a;
    sum += a * (e1 + e2) / Real(3);
  }
  return origin + sum / area;
}

}  // namespace

void compute_core_normals(ConvexCore& core) {
  if (core.count < 2) {
    core.normals[0] = Vec2(Real(1), Real(0));  // unused; set so that copies read no indeterminate value
    return;
  }
  // Two vertices: edge (1, 0) is edge (0, 1) reversed, and unit_and_length's scaling and
  // rounding are symmetric in sign, so its normal is exactly the negation.
  const int distinct = core.count == 2 ? 1 : core.count;
  for (int i = 0; i < distinct; ++i) {
    const Vec2 edge = core.vertices[(i + 1) % core.count] - core.vertices[i];
    Vec2 unit;
    Real length;
    core.normals[i] = unit_and_length(right_perp(edge), unit, length) ? unit : Vec2(Real(1), Real(0));
  }
  if (core.count == 2) core.normals[1] = -core.normals[0];
}

Result<Point> Point::create(const Vec2& position) {
  if (auto e = check_point(position, "position")) return *e;
  return Point(make_core({position}, Real(0)));
}

Result<Circle> Circle::create(Real radius, const Vec2& center) {
  if (auto e = validate::positive(radius, "radius")) return *e;
  if (auto e = check_point(center, "center")) return *e;
  return Circle(make_core({center}, radius));
}

Result<Segment> Segment::create(const Vec2& a, const Vec2& b) {
  if (auto e = check_point(a, "vertices[0]")) return *e;
  if (auto e = check_point(b, "vertices[1]")) return *e;
  if (a == b) return Error{ErrorCode::Degenerate, "vertices", "the two end points are equal"};
  return Segment(make_core({a, b}, Real(0)));
}

Result<Capsule> Capsule::create(const Vec2& a, const Vec2& b, Real radius) {
  if (auto e = check_point(a, "vertices[0]")) return *e;
  if (auto e = check_point(b, "vertices[1]")) return *e;
  if (auto e = validate::positive(radius, "radius")) return *e;
  return Capsule(a == b ? make_core({a}, radius) : make_core({a, b}, radius));
}

Result<Polygon> Polygon::create(std::span<const Vec2> points, Real radius) {
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (auto e = check_point(points[i], "points[" + std::to_string(i) + "]")) return *e;
  }
  if (auto e = validate::non_negative(radius, "radius")) return *e;
  if (points.size() < 3) return Error{ErrorCode::TooFew, "points", "a polygon needs at least 3 points"};
  const std::vector<Vec2> hull = monotone_chain_hull(points);
  if (hull.size() < 3) return Error{ErrorCode::Degenerate, "points", "the points enclose no area (collinear or equal)"};
  if (hull.size() > static_cast<std::size_t>(kMaxPolygonVertices)) {
    return Error{ErrorCode::OutOfRange, "points", "the convex hull has more than 16 vertices"};
  }
  Polygon polygon;
  polygon.core_.count = static_cast<int>(hull.size());
  std::copy(hull.begin(), hull.end(), polygon.core_.vertices.begin());
  polygon.core_.radius = radius;
  compute_core_normals(polygon.core_);
  polygon.centroid_ = polygon_centroid(polygon.core_);
  return polygon;
}

Result<Polygon> Polygon::restore(std::span<const Vec2> vertices, Real radius) {
  for (std::size_t i = 0; i < vertices.size(); ++i) {
    if (auto e = check_point(vertices[i], "points[" + std::to_string(i) + "]")) return *e;
  }
  if (auto e = validate::non_negative(radius, "radius")) return *e;
  if (vertices.size() < 3) return Error{ErrorCode::TooFew, "points", "a polygon needs at least 3 points"};
  if (vertices.size() > static_cast<std::size_t>(kMaxPolygonVertices)) {
    return Error{ErrorCode::OutOfRange, "points", "a polygon has at most 16 vertices"};
  }
  if (!strictly_convex(vertices)) {
    return Error{ErrorCode::Degenerate, "points", "not a strictly convex counter-clockwise polygon"};
  }
  Polygon polygon;
  polygon.core_.count = static_cast<int>(vertices.size());
  std::copy(vertices.begin(), vertices.end(), polygon.core_.vertices.begin());
  polygon.core_.radius = radius;
  compute_core_normals(polygon.core_);
  polygon.centroid_ = polygon_centroid(polygon.core_);
  return polygon;
}

Result<Polygon> Polygon::box(Real hx, Real hy, Real radius) { return box(hx, hy, Vec2(Real(0)), Real(0), radius); }

Result<Polygon> Polygon::box(Real hx, Real hy, const Vec2& center, Real angle, Real radius) {
  if (auto e = validate::positive(hx, "half_extents.x")) return *e;
  if (auto e = validate::positive(hy, "half_extents.y")) return *e;
  if (auto e = check_point(center, "center")) return *e;
  if (!std::isfinite(angle)) return Error{ErrorCode::NotFinite, "angle", "must be finite"};
  if (auto e = validate::non_negative(radius, "radius")) return *e;
  const Pose place = Pose::from(center, angle);
  Polygon polygon;
  polygon.core_ = make_core(
      {place.apply({-hx, -hy}), place.apply({hx, -hy}), place.apply({hx, hy}), place.apply({-hx, hy})}, radius);
  polygon.centroid_ = center;
  return polygon;
}

}  // namespace proxima::d2
