/// @file chain_manifold.cpp
/// Contact manifold of a one-sided chain segment with a rounded core: smooth seams.
///
/// Steps (ghost vertices as in Box2D's chain shapes; the admissible-normal reasoning of
/// Catto, "Solving Rigid Body Contacts", GDC 2016 on internal edges):
///   1. move B into the segment's frame; B whose vertex centroid is behind the segment line
///      touches nothing (one-sided);
///   2. the two-sided manifold of the segment and B (core_manifold);
///   3. its normal is admissible when it is the segment's normal, or lies in the cone of
///      a convex end: between the previous segment's normal and this one's at the start,
///      between this one's and the next's at the end (an open end admits the quarter
///      between the normal and the chain's direction away from the segment); then keep it;
///   4. otherwise: a 1-vertex B belongs to the neighbour (no contact here); a B with edges
///      gets the manifold on the segment's own normal (its incident edge clipped to the
///      segment), so a seam between collinear segments never yields a sideways normal.

#include <proxima/d2/convex_queries.hpp>

#include "d2/core_pair.hpp"
#include "d2/edge_clipping.hpp"

namespace proxima::d2 {
namespace {

Vec2 unit_right_normal(const Vec2& from, const Vec2& to) {
  Vec2 unit;
  Real length;
  return unit_and_length(right_perp(to - from), unit, length) ? unit : Vec2(Real(0), Real(1));
}

/// True when `n` lies on the counter-clockwise arc from `from` to `to` (less than a half turn).
bool on_arc(const Vec2& from, const Vec2& n, const Vec2& to) {
  return cross(from, n) >= Real(0) && cross(n, to) >= Real(0);
}

/// True when the chain may produce normal `n` (segment frame) on this segment.
bool admissible(const ChainSegment& s, const Vec2& n) {
  const Vec2 normal = unit_right_normal(s.a, s.b);
  if (glm::dot(n, normal) >= Real(1) - Real(1e-5)) return true;
  const Vec2 t = glm::normalize(s.b - s.a);
  if (glm::dot(n, t) < Real(0)) {  // the start's side
    if (!s.has_prev) return on_arc(-t, n, normal);
    const bool convex = cross(s.a - s.ghost_prev, s.b - s.a) > Real(0);
    return convex && on_arc(unit_right_normal(s.ghost_prev, s.a), n, normal);
  }
  if (!s.has_next) return on_arc(normal, n, t);
  const bool convex = cross(s.b - s.a, s.ghost_next - s.b) > Real(0);
  return convex && on_arc(normal, n, unit_right_normal(s.b, s.ghost_next));
}

Vec2 vertex_centroid(const ConvexCore& core) {
  Vec2 c(Real(0));
  for (int i = 0; i < core.count; ++i) c += core.vertices[i];
  return c / static_cast<Real>(core.count);
}

}  // namespace

Manifold chain_segment_manifold(const ChainSegment& a, const Pose& pose_a, const ConvexCore& b, const Pose& pose_b,
                                Real contact_distance) {
  const ConvexCore segment = a.core();
  const detail::CorePair pair = detail::make_core_pair(segment, pose_a, b, pose_b);
  if (!std::isfinite(pair.scale) || !is_finite(pair.b.vertices[0])) return Manifold{};
  const Vec2 normal = segment.normals[0];
  if (glm::dot(normal, vertex_centroid(pair.b) - a.a) < Real(0)) return Manifold{};
  Manifold m = core_manifold(segment, Pose::identity(), pair.b, Pose::identity(), contact_distance);
  if (m.count == 0 || admissible(a, m.normal)) return detail::to_world(m, pose_a);
  if (pair.b.count < 2) return Manifold{};
  Real separation = std::numeric_limits<Real>::infinity();
  for (int j = 0; j < pair.b.count; ++j) separation = std::min(separation, glm::dot(normal, pair.b.vertices[j] - a.a));
  if (separation - pair.b.radius > contact_distance) return Manifold{};
  m = detail::clip_manifold(segment, 0, pair.b, separation, contact_distance, Real(0), false);
  return detail::to_world(m, pose_a);
}

}  // namespace proxima::d2
