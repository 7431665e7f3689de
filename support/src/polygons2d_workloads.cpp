// The W9 2D shape pairs (shared/bench/FORMATS.md, "W9", `polygons2d_pairs.txt`): the
// reader (same machinery as the W1..W8 readers, text_parse.hpp) and the conversion to the
// 2D module's shapes and poses.
#include "support/polygons2d_workloads.hpp"

#include <cmath>

#include "text_parse.hpp"

namespace proxima::bench {
using namespace detail;

namespace {

/// Splits a record at '|' into its fields.
std::vector<std::string_view> split_at_bars(std::string_view line) {
  std::vector<std::string_view> parts;
  std::size_t start = 0;
  while (true) {
    const std::size_t bar = line.find('|', start);
    parts.push_back(line.substr(start, bar == std::string_view::npos ? std::string_view::npos : bar - start));
    if (bar == std::string_view::npos) return parts;
    start = bar + 1;
  }
}

double parse_non_negative(const Source& src, std::string_view token, const char* what) {
  const double v = parse_double(src, token);
  if (!(v >= 0)) src.fail_here(std::string(what) + " must be >= 0, found " + quoted(token));
  return v;
}

/// Reads `count` vertices (x y pairs) from tokens t[at...].
void parse_vertices(const Source& src, const std::vector<std::string_view>& t, std::size_t at, int count,
                    Polygons2dShape& s) {
  s.count = count;
  for (int i = 0; i < count; ++i) {
    s.vertices[std::size_t(i)] = {parse_double(src, t[at + 2 * std::size_t(i)]),
                                  parse_double(src, t[at + 2 * std::size_t(i) + 1])};
  }
}

Polygons2dShape parse_polygon(const Source& src, const std::vector<std::string_view>& t) {
  if (t.size() < 2) src.fail_here("polygon lacks its vertex count (polygon n x1 y1 ... xn yn r)");
  const std::uint64_t n = parse_unsigned(src, t[1], "polygon vertex count");
  if (n < 3 || n > std::uint64_t(kPolygons2dMaxVertices)) src.fail_here("polygon vertex count must be in 3..8");
  expect_tokens(src, t, 3 + 2 * n, "polygon n x1 y1 ... xn yn r");
  Polygons2dShape s;
  s.kind = Polygons2dKind::Polygon;
  parse_vertices(src, t, 2, int(n), s);
  s.radius = parse_non_negative(src, t[2 + 2 * n], "polygon radius");
  return s;
}

Polygons2dShape parse_shape(const Source& src, std::string_view text) {
  const auto t = split(text);
  if (t.empty()) src.fail_here("empty shape field");
  if (t[0] == "polygon") return parse_polygon(src, t);
  Polygons2dShape s;
  if (t[0] == "circle") {
    expect_tokens(src, t, 2, "circle r");
    s.kind = Polygons2dKind::Circle;
    s.radius = parse_positive(src, t[1], "circle radius");
  } else if (t[0] == "capsule2d") {
    expect_tokens(src, t, 6, "capsule2d x1 y1 x2 y2 r");
    s.kind = Polygons2dKind::Capsule;
    parse_vertices(src, t, 1, 2, s);
    s.radius = parse_positive(src, t[5], "capsule radius");
  } else if (t[0] == "segment2d") {
    expect_tokens(src, t, 5, "segment2d x1 y1 x2 y2");
    s.kind = Polygons2dKind::Segment;
    parse_vertices(src, t, 1, 2, s);
  } else if (t[0] == "box2d") {
    expect_tokens(src, t, 4, "box2d hx hy r");
    s.kind = Polygons2dKind::Box;
    s.half_x = parse_positive(src, t[1], "box half extent");
    s.half_y = parse_positive(src, t[2], "box half extent");
    s.radius = parse_non_negative(src, t[3], "box radius");
  } else {
    src.fail_here("unknown shape " + quoted(t[0]) + " (expected circle, capsule2d, segment2d, polygon or box2d)");
  }
  return s;
}

Polygons2dPose parse_pose2d(const Source& src, std::string_view text) {
  const auto t = split(text);
  expect_tokens(src, t, 3, "x y angle");
  return {parse_double(src, t[0]), parse_double(src, t[1]), parse_double(src, t[2])};
}

d2::Vec2 to_vec2(const std::array<double, 2>& p) { return {static_cast<Real>(p[0]), static_cast<Real>(p[1])}; }

/// The error of converting pair `index`'s shape `side` ("a" or "b").
Error pair_error(const Error& e, std::size_t index, const char* side) {
  return make_error(e.code, "pairs[" + std::to_string(index) + "]." + side + (e.field.empty() ? "" : "." + e.field),
                    e.message);
}

}  // namespace

Result<std::vector<Polygons2dPair>> read_polygons2d_pairs(const std::string& path) {
  return guarded<std::vector<Polygons2dPair>>([&] {
    Source src(path);
    const Header h = expect_header(src, "polygons2d_pairs");
    const std::uint64_t count = require_count(src, h, "count");
    std::vector<Polygons2dPair> pairs;
    pairs.reserve(reservable(src, count));
    std::string_view line;
    for (std::uint64_t k = 0; k < count; ++k) {
      if (!src.next_record(line)) {
        fail(path, src.line(), "file ends after " + std::to_string(k) + " of the " + std::to_string(count) + " pairs");
      }
      const auto fields = split_at_bars(line);
      if (fields.size() != 4) src.fail_here("expected 4 fields '<shapeA> | xA yA angleA | <shapeB> | xB yB angleB'");
      pairs.push_back({parse_shape(src, fields[0]), parse_pose2d(src, fields[1]), parse_shape(src, fields[2]),
                       parse_pose2d(src, fields[3])});
    }
    if (src.next_record(line)) src.fail_here("more records than the header's count=" + std::to_string(count));
    return pairs;
  });
}

Result<d2::Shape> to_d2_shape(const Polygons2dShape& shape) {
  const Real r = static_cast<Real>(shape.radius);
  const auto wrap = [](auto made) -> Result<d2::Shape> {
    if (!made) return made.error();
    return d2::Shape(*made);
  };
  switch (shape.kind) {
    case Polygons2dKind::Circle: return wrap(d2::Circle::create(r));
    case Polygons2dKind::Capsule:
      return wrap(d2::Capsule::create(to_vec2(shape.vertices[0]), to_vec2(shape.vertices[1]), r));
    case Polygons2dKind::Segment:
      return wrap(d2::Segment::create(to_vec2(shape.vertices[0]), to_vec2(shape.vertices[1])));
    case Polygons2dKind::Box:
      return wrap(d2::Polygon::box(static_cast<Real>(shape.half_x), static_cast<Real>(shape.half_y), r));
    case Polygons2dKind::Polygon: {
      std::array<d2::Vec2, kPolygons2dMaxVertices> points;
      for (int i = 0; i < shape.count; ++i) points[std::size_t(i)] = to_vec2(shape.vertices[std::size_t(i)]);
      return wrap(d2::Polygon::create(std::span<const d2::Vec2>(points.data(), std::size_t(shape.count)), r));
    }
  }
  return make_error(ErrorCode::InvalidArgument, "kind", "unknown shape kind");
}

d2::Pose to_d2_pose(const Polygons2dPose& pose) {
  d2::Pose p;
  p.position = {static_cast<Real>(pose.x), static_cast<Real>(pose.y)};
  p.rotation = {static_cast<Real>(std::cos(pose.angle)), static_cast<Real>(std::sin(pose.angle))};
  return p;
}

Result<std::vector<Polygons2dShapePair>> to_d2_pairs(const std::vector<Polygons2dPair>& pairs) {
  std::vector<Polygons2dShapePair> out;
  out.reserve(pairs.size());
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    auto a = to_d2_shape(pairs[i].a);
    if (!a) return pair_error(a.error(), i, "a");
    auto b = to_d2_shape(pairs[i].b);
    if (!b) return pair_error(b.error(), i, "b");
    out.push_back({std::move(*a), to_d2_pose(pairs[i].pose_a), std::move(*b), to_d2_pose(pairs[i].pose_b)});
  }
  return out;
}

}  // namespace proxima::bench
