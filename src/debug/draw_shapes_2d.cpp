// Emitters of 2D shapes (debug/draw_shapes_2d.hpp).
//
// Steps of a convex shape:
//   1. its outline in the local frame (core_outline: vertices pushed out by the radius,
//      arcs around them), placed by the pose at z = 0;
//   2. with area: the outline fanned into triangles from the mean of the core's vertices
//      (inside the convex core, so every triangle is counter-clockwise), then the outline's
//      lines; without (a segment or a point): a line or a marker.
#include <proxima/d2/math.hpp>
#include <proxima/debug/draw_shapes_2d.hpp>

#include <algorithm>
#include <cmath>

namespace proxima::debug {

namespace {

constexpr Real kTwoPi = Real(6.283185307179586);

/// The counter-clockwise turn from edge normal `from` to `to`, in (0, 2 pi]; a core of two
/// vertices turns half a circle at each end.
Real turn_between(const Vec2& from, const Vec2& to, int count) {
  if (count == 2) return kTwoPi / 2;
  Real turn = std::atan2(d2::cross(from, to), glm::dot(from, to));
  if (turn < Real(0)) turn += kTwoPi;
  return turn;
}

/// Chords of an arc turning by `turn` at `segments` per full turn (at least 1; a turn a
/// rounding error past a multiple of the chord angle takes no extra chord).
int arc_steps(int segments, Real turn) {
  if (!(turn > Real(0) && turn <= kTwoPi)) return 1;
  return std::max(1, static_cast<int>(std::ceil(Real(segments) * turn / kTwoPi - Real(1e-3))));
}

/// Appends the arc of radius `radius` about `center` from direction angle `start` over
/// `turn` in `steps` chords (steps + 1 points, both ends included).
void append_arc(std::vector<Vec2>& out, const Vec2& center, Real radius, Real start, Real turn, int steps) {
  for (int k = 0; k <= steps; ++k) {
    const Real angle = start + turn * Real(k) / Real(steps);
    out.push_back(center + radius * Vec2(std::cos(angle), std::sin(angle)));
  }
}

void draw_outline_lines(DebugDraw& sink, std::span<const Vec3> loop, Rgba color, DrawTag tag) {
  std::vector<DrawLine> lines;
  lines.reserve(loop.size());
  for (std::size_t i = 0; i < loop.size(); ++i) lines.push_back({loop[i], loop[(i + 1) % loop.size()], color, tag});
  sink.draw_lines(lines);
}

void draw_fan(DebugDraw& sink, const Vec3& center, std::span<const Vec3> loop, Rgba color, DrawTag tag) {
  std::vector<DrawTriangle> triangles;
  triangles.reserve(loop.size());
  for (std::size_t i = 0; i < loop.size(); ++i) {
    triangles.push_back({center, loop[i], loop[(i + 1) % loop.size()], color, tag});
  }
  sink.draw_triangles(triangles);
}

/// The mean of the core's vertices: inside the convex core, so a fan from it is
/// counter-clockwise throughout.
Vec2 core_mean(const d2::ConvexCore& core, int count) {
  Vec2 mean(Real(0));
  for (int i = 0; i < count; ++i) mean += core.vertices[static_cast<std::size_t>(i)] / Real(count);
  return mean;
}

}  // namespace

Transform plane_pose(const d2::Pose& pose) {
  // cos(a/2) and sin(a/2) from cos a and sin a, each from the larger half-angle term so that
  // neither divides by a small number.
  const Real c = std::clamp(pose.rotation.c, Real(-1), Real(1)), s = pose.rotation.s;
  Real w, z;
  if (c >= Real(0)) {
    w = std::sqrt((Real(1) + c) / Real(2));
    z = s / (Real(2) * w);
  } else {
    z = std::copysign(std::sqrt((Real(1) - c) / Real(2)), s);
    w = s / (Real(2) * z);
  }
  return Transform{plane_point(pose.position), Quat(w, Real(0), Real(0), z)};
}

Rgba outline_color(Rgba color) {
  const auto dim = [](std::uint8_t c) { return static_cast<std::uint8_t>(c * 55 / 100); };
  return Rgba{dim(color.r), dim(color.g), dim(color.b), color.a};
}

std::vector<Vec2> core_outline(const d2::ConvexCore& core, int segments) {
  const int count = std::clamp(core.count, 0, d2::kMaxPolygonVertices);
  const int n = std::clamp(segments, 3, 256);
  std::vector<Vec2> out;
  if (count == 0) return out;
  if (!(core.radius > Real(0))) return {core.vertices.begin(), core.vertices.begin() + count};
  if (count == 1) {
    append_arc(out, core.vertices[0], core.radius, Real(0), kTwoPi, n);
    out.pop_back();  // the full turn ends where it began
    return out;
  }
  for (int i = 0; i < count; ++i) {
    const Vec2 from = core.normals[static_cast<std::size_t>((i + count - 1) % count)];
    const Vec2 to = core.normals[static_cast<std::size_t>(i)];
    const Real turn = turn_between(from, to, count);
    append_arc(out, core.vertices[static_cast<std::size_t>(i)], core.radius, std::atan2(from.y, from.x), turn,
               arc_steps(n, turn));
  }
  return out;
}

DrawMesh tessellate_2d(const d2::Shape& shape, int segments) {
  DrawMesh mesh;
  if (!shape.is_convex()) return mesh;
  const d2::ConvexCore& core = shape.core();
  const std::vector<Vec2> loop = core_outline(core, segments);
  if (loop.size() < 3) return mesh;
  mesh.positions.push_back(plane_point(core_mean(core, std::clamp(core.count, 1, d2::kMaxPolygonVertices))));
  for (const Vec2& p : loop) mesh.positions.push_back(plane_point(p));
  const auto n = static_cast<std::uint32_t>(loop.size());
  for (std::uint32_t i = 0; i < n; ++i) mesh.indices.insert(mesh.indices.end(), {0u, i + 1, (i + 1) % n + 1});
  return mesh;
}

void draw_convex_2d(DebugDraw& sink, const d2::ConvexCore& core, const d2::Pose& pose, Rgba color,
                    const Shape2DDrawOptions& options) {
  const int count = std::clamp(core.count, 0, d2::kMaxPolygonVertices);
  if (count == 0) return;
  const DrawTag tag{options.layer, 0};
  std::vector<Vec3> loop;
  for (const Vec2& p : core_outline(core, options.segments)) loop.push_back(plane_point(pose.apply(p)));
  if (loop.size() == 1) {
    const DrawPoint marker{loop[0], options.point_size, color, tag};
    sink.draw_points({&marker, 1});
    return;
  }
  if (loop.size() == 2) {
    const DrawLine line{loop[0], loop[1], color, tag};
    sink.draw_lines({&line, 1});
    return;
  }
  if (options.fill) draw_fan(sink, plane_point(pose.apply(core_mean(core, count))), loop, color, tag);
  if (options.outline) draw_outline_lines(sink, loop, outline_color(color), tag);
}

void draw_chain(DebugDraw& sink, const d2::Chain& chain, const d2::Pose& pose, Rgba color,
                const Shape2DDrawOptions& options) {
  const DrawTag tag{options.layer, 0};
  std::vector<DrawLine> segments, normals;
  for (int i = 0; i < chain.segment_count(); ++i) {
    const d2::ChainSegment s = chain.segment(i);
    const Vec2 a = pose.apply(s.a), b = pose.apply(s.b), middle = (a + b) * Real(0.5);
    segments.push_back({plane_point(a), plane_point(b), color, tag});
    if (options.chain_normal_length > Real(0)) {
      const Vec2 tip = middle + options.chain_normal_length * pose.apply_vector(s.normal());
      normals.push_back({plane_point(middle), plane_point(tip), outline_color(color), DrawTag{DrawLayer::Normals, 0}});
    }
  }
  sink.draw_lines(segments);
  if (!normals.empty()) sink.draw_lines(normals);
}

void draw_shape_2d(DebugDraw& sink, const d2::Shape& shape, const d2::Pose& pose, Rgba color,
                   const Shape2DDrawOptions& options) {
  if (shape.is_convex()) {
    draw_convex_2d(sink, shape.core(), pose, color, options);
  } else {
    draw_chain(sink, shape.chain(), pose, color, options);
  }
}

void draw_sprite_chains(DebugDraw& sink, std::span<const d2::Chain> chains, const d2::Pose& pose, Rgba color,
                        const Shape2DDrawOptions& options) {
  for (const d2::Chain& chain : chains) draw_chain(sink, chain, pose, color, options);
}

void draw_bounds_2d(DebugDraw& sink, const d2::Shape& shape, const d2::Pose& pose, Rgba color) {
  const d2::Aabb box = shape.world_aabb(pose);
  const Vec2 center = box.center(), half = box.half_extents();
  const DrawBox drawn{plane_point(center), Vec3(half.x, half.y, Real(0)), kIdentityQuat, color,
                      DrawTag{DrawLayer::Bounds, 0}};
  sink.draw_boxes({&drawn, 1});
}

}  // namespace proxima::debug
