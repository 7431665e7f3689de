// The W9 2D collision world (shared/bench/FORMATS.md, "W9 2D workloads",
// `world2d_mixed_20k.txt`): the `world2d` reader (same machinery as the other readers,
// text_parse.hpp) and the W9 motion rule. Like world_workloads.cpp this file is compiled
// with -ffp-contract=off (support/CMakeLists.txt) and keeps FORMATS.md's order of
// operations, so the positions are the reference's to the last bit.
#include "support/world2d_workloads.hpp"

#include <cmath>

#include "support/world_workloads.hpp"
#include "text_parse.hpp"

namespace proxima::bench {
using namespace detail;

namespace {

Vec2d parse_point(const Source& src, const std::vector<std::string_view>& t, std::size_t at) {
  return {parse_double(src, t[at]), parse_double(src, t[at + 1])};
}

double parse_rounding(const Source& src, std::string_view token) {
  const double r = parse_double(src, token);
  if (!(r >= 0)) src.fail_here("rounding radius must be >= 0, found " + quoted(token));
  return r;
}

World2dShape parse_polygon(const Source& src, const std::vector<std::string_view>& t) {
  if (t.size() < 2) src.fail_here("expected 'polygon n x1 y1 ... xn yn r'");
  const std::uint64_t n = parse_unsigned(src, t[1], "polygon vertex count");
  if (n < 3 || n > 8) src.fail_here("a polygon has 3..8 vertices, found " + std::string(t[1]));
  expect_tokens(src, t, 3 + 2 * n, "polygon n x1 y1 ... xn yn r");
  World2dShape s;
  s.kind = World2dShapeKind::Polygon;
  for (std::size_t k = 0; k < n; ++k) s.points.push_back(parse_point(src, t, 2 + 2 * k));
  s.radius = parse_rounding(src, t[2 + 2 * n]);
  return s;
}

World2dShape parse_shape2d(const Source& src, std::string_view text) {
  const auto t = split(text);
  if (t.empty()) src.fail_here("empty shape field");
  World2dShape s;
  if (t[0] == "circle") {
    expect_tokens(src, t, 2, "circle r");
    s.radius = parse_positive(src, t[1], "circle radius");
  } else if (t[0] == "capsule2d" || t[0] == "segment2d") {
    const bool capsule = t[0] == "capsule2d";
    expect_tokens(src, t, capsule ? 6 : 5, capsule ? "capsule2d x1 y1 x2 y2 r" : "segment2d x1 y1 x2 y2");
    s.kind = capsule ? World2dShapeKind::Capsule2d : World2dShapeKind::Segment2d;
    s.points = {parse_point(src, t, 1), parse_point(src, t, 3)};
    if (capsule) s.radius = parse_positive(src, t[5], "capsule radius");
  } else if (t[0] == "polygon") {
    s = parse_polygon(src, t);
  } else if (t[0] == "box2d") {
    expect_tokens(src, t, 4, "box2d hx hy r");
    s.kind = World2dShapeKind::Box2d;
    s.half_extents = {parse_positive(src, t[1], "box half extent"), parse_positive(src, t[2], "box half extent")};
    s.radius = parse_rounding(src, t[3]);
  } else {
    src.fail_here("unknown shape " + quoted(t[0]) + " (expected circle, capsule2d, segment2d, polygon or box2d)");
  }
  return s;
}

World2dObject parse_object2d(const Source& src, std::string_view line, std::uint64_t k) {
  const ObjectRecord record = parse_object_record(src, line, k);
  World2dObject o;
  o.id = static_cast<std::uint32_t>(k);
  o.is_static = record.is_static;
  o.shape = parse_shape2d(src, record.shape);
  const auto pose = split(record.pose);
  expect_tokens(src, pose, 3, "x y angle");
  o.pose = {parse_point(src, pose, 0), parse_double(src, pose[2])};
  const auto velocities = split(record.velocities);
  expect_tokens(src, velocities, 3, "vx vy w");
  o.velocity = parse_point(src, velocities, 0);
  o.angular_velocity = parse_double(src, velocities[2]);
  if (o.is_static && (o.velocity != Vec2d{} || o.angular_velocity != 0)) {
    src.fail_here("a static object has non-zero velocities");
  }
  return o;
}

World2d parse_world2d(const std::string& path) {
  Source src(path);
  const Header h = expect_header(src, "world2d");
  World2d w;
  const std::uint64_t n = require_count(src, h, "objects");
  if (n > 0xffffffffu) fail(path, 1, "objects= is too large");
  const std::uint64_t frames = require_count(src, h, "frames");
  if (frames > 100000000u) fail(path, 1, "frames= is too large");
  w.frames = static_cast<int>(frames);
  w.dt = require_number(src, h, "dt");
  if (!(w.dt > 0)) fail(path, 1, "dt= must be > 0");
  const auto lo = require_numbers<2>(src, h, "lo");
  const auto hi = require_numbers<2>(src, h, "hi");
  w.lo = {lo[0], lo[1]};
  w.hi = {hi[0], hi[1]};
  if (!(w.lo.x < w.hi.x && w.lo.y < w.hi.y)) fail(path, 1, "lo= must be smaller than hi= on both axes");
  const auto name = h.keys.find("name");
  w.name = name != h.keys.end() ? name->second : file_stem(path);
  w.objects.reserve(reservable(src, n));
  std::string_view line;
  for (std::uint64_t k = 0; k < n; ++k) {
    if (!src.next_record(line)) {
      fail(path, src.line(), "file ends after " + std::to_string(k) + " of the " + std::to_string(n) + " objects");
    }
    w.objects.push_back(parse_object2d(src, line, k));
  }
  if (src.next_record(line)) src.fail_here("more objects than the header's objects=" + std::to_string(n));
  return w;
}

}  // namespace

Result<World2d> read_world2d(const std::string& path) {
  return guarded<World2d>([&]() { return parse_world2d(path); });
}

Pose2d pose2d_at_time(const World2dObject& object, double t, const Vec2d& lo, const Vec2d& hi) {
  if (object.is_static) return object.pose;
  Pose2d p;
  const double x = object.pose.position.x + object.velocity.x * t;
  const double y = object.pose.position.y + object.velocity.y * t;
  p.position = {fold_coordinate(x, lo.x, hi.x), fold_coordinate(y, lo.y, hi.y)};
  p.angle = object.pose.angle + object.angular_velocity * t;
  return p;
}

Pose2d pose2d_at_frame(const World2d& world, std::size_t index, int frame) {
  return pose2d_at_time(world.objects[index], frame_time(frame, world.dt), world.lo, world.hi);
}

Result<d2::Shape> to_d2_shape(const World2dShape& s) {
  std::vector<Vec2> points;
  for (const Vec2d& p : s.points) points.push_back({static_cast<Real>(p.x), static_cast<Real>(p.y)});
  const Real r = static_cast<Real>(s.radius);
  const auto shape = [](auto result) -> Result<d2::Shape> {
    if (!result.ok()) return result.error();
    return d2::Shape(std::move(result).value());
  };
  switch (s.kind) {
    case World2dShapeKind::Circle: return shape(d2::Circle::create(r));
    case World2dShapeKind::Capsule2d: return shape(d2::Capsule::create(points[0], points[1], r));
    case World2dShapeKind::Segment2d: return shape(d2::Segment::create(points[0], points[1]));
    case World2dShapeKind::Polygon: return shape(d2::Polygon::create(points, r));
    case World2dShapeKind::Box2d:
      return shape(d2::Polygon::box(static_cast<Real>(s.half_extents.x), static_cast<Real>(s.half_extents.y), r));
  }
  return Error{ErrorCode::InvalidArgument, "kind", "unknown W9 shape kind"};
}

d2::Pose to_d2_pose(const Pose2d& p) {
  return {{static_cast<Real>(p.position.x), static_cast<Real>(p.position.y)},
          {static_cast<Real>(std::cos(p.angle)), static_cast<Real>(std::sin(p.angle))}};
}

}  // namespace proxima::bench
