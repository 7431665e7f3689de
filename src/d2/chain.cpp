/// @file chain.cpp
/// Validated construction of a chain and its segments with ghost vertices.

#include <proxima/core/tolerance.hpp>
#include <proxima/d2/chain.hpp>

#include <string>

namespace proxima::d2 {

Vec2 ChainSegment::normal() const {
  Vec2 unit;
  Real length;
  return unit_and_length(right_perp(b - a), unit, length) ? unit : Vec2(Real(0), Real(1));
}

ConvexCore ChainSegment::core() const {
  ConvexCore core;
  core.vertices[0] = a;
  core.vertices[1] = b;
  core.count = 2;
  core.radius = Real(0);
  compute_core_normals(core);
  return core;
}

Result<Chain> Chain::create(std::span<const Vec2> points, bool loop) {
  for (std::size_t i = 0; i < points.size(); ++i) {
    const std::string field = "points[" + std::to_string(i) + "]";
    if (!is_finite(points[i])) return Error{ErrorCode::NotFinite, field, "must be finite"};
    if (max_abs_component(points[i]) > kMaxCoordinate)
      return Error{ErrorCode::OutOfRange, field, "must be within kMaxCoordinate"};
    if (i > 0 && points[i] == points[i - 1]) return Error{ErrorCode::Degenerate, field, "equals the previous point"};
  }
  const std::size_t needed = loop ? 3 : 2;
  if (points.size() < needed) {
    return Error{ErrorCode::TooFew, "points",
                 loop ? "a loop needs at least 3 points" : "a chain needs at least 2 points"};
  }
  if (loop && points.front() == points.back()) {
    return Error{ErrorCode::Degenerate, "points[" + std::to_string(points.size() - 1) + "]",
                 "equals the first point (a loop closes itself: leave the repeat out)"};
  }
  Chain chain;
  chain.points_.assign(points.begin(), points.end());
  chain.loop_ = loop;
  for (const Vec2& p : points) chain.local_aabb_.grow(p);
  return chain;
}

ChainSegment Chain::segment(int i) const {
  const int n = static_cast<int>(points_.size());
  ChainSegment s;
  s.a = points_[i];
  s.b = points_[(i + 1) % n];
  s.has_prev = loop_ || i > 0;
  s.has_next = loop_ || i + 2 < n;
  if (s.has_prev) s.ghost_prev = points_[(i + n - 1) % n];
  if (s.has_next) s.ghost_next = points_[(i + 2) % n];
  return s;
}

Aabb Chain::world_aabb(const Pose& pose) const {
  Aabb box;
  for (const Vec2& p : points_) box.grow(pose.apply(p));
  return box;
}

}  // namespace proxima::d2
