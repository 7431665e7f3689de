/// @file core_manifold.cpp
/// Contact manifold of two rounded 2D cores.
///
/// Steps (reference/incident edge clipping: Ericson, Real-Time Collision Detection §5.2.1
/// on separating axes; Catto, "Contact Manifolds", GDC 2007, as Box2D builds polygon
/// manifolds):
///   1. a 1-vertex core on either side: one point from the cores' distance (its closed
///      form); otherwise move B into A's frame;
///   2. the largest edge separation on A's normals, then on B's; as soon as an edge
///      separates by more than the contact distance plus both radii, no contact;
///   3. the reference edge is A's unless B's axis separates more by a tie margin (so the
///      choice does not flicker between frames); the incident edge is the other core's edge
///      whose normal is most anti-parallel to the reference normal;
///   4. cores apart whose nearest features are two vertices (a corner meeting a corner): one
///      point along the line between them, at their exact distance;
///   5. otherwise clip the incident edge by the two side lines of the reference edge and keep
///      each clipped point within the contact distance; the point on the reference surface is
///      its projection on the reference edge moved out by the reference radius.

#include <proxima/d2/convex_queries.hpp>

#include "d2/core_pair.hpp"
#include "d2/edge_clipping.hpp"

namespace proxima::d2 {
namespace {

using detail::CorePair;

/// A clip point on the incident edge and the feature that made it.
struct ClipPoint {
  Vec2 p{Real(0)};
  std::uint32_t id = 0;
};

/// Keeps the part of segment (in[0], in[1]) where dot(normal, p) <= offset; returns the
/// number of points kept (2 when both or one side survive, 0 when none). A point made by the
/// clip gets `clip_id`.
int clip_segment(const ClipPoint in[2], ClipPoint out[2], const Vec2& normal, Real offset, std::uint32_t clip_id) {
  const Real d0 = glm::dot(normal, in[0].p) - offset;
  const Real d1 = glm::dot(normal, in[1].p) - offset;
  int n = 0;
  if (d0 <= Real(0)) out[n++] = in[0];
  if (d1 <= Real(0)) out[n++] = in[1];
  if (d0 * d1 < Real(0) && n < 2) {
    const Real t = d0 / (d0 - d1);
    out[n++] = {in[0].p + t * (in[1].p - in[0].p), clip_id};
  }
  return n;
}

}  // namespace

namespace detail {

void closest_segment_parameters(const Vec2& p1, const Vec2& q1, const Vec2& p2, const Vec2& q2, Real& s, Real& t) {
  const Vec2 d1 = q1 - p1, d2 = q2 - p2, r = p1 - p2;
  const Real a = glm::dot(d1, d1), e = glm::dot(d2, d2), f = glm::dot(d2, r);
  const Real c = glm::dot(d1, r), b = glm::dot(d1, d2);
  const Real denom = a * e - b * b;
  s = denom > Real(0) ? std::clamp((b * f - c * e) / denom, Real(0), Real(1)) : Real(0);
  t = (b * s + f) / e;
  if (t < Real(0)) {
    t = Real(0);
    s = std::clamp(-c / a, Real(0), Real(1));
  } else if (t > Real(1)) {
    t = Real(1);
    s = std::clamp((b - c) / a, Real(0), Real(1));
  }
}

Manifold clip_manifold(const ConvexCore& ref, int edge, const ConvexCore& inc, Real separation, Real contact_distance,
                       Real tie, bool allow_corner) {
  Manifold m;
  m.method = PairMethod::Sat;
  const Vec2 n = ref.normals[edge];
  const int e2 = (edge + 1) % ref.count;
  const Vec2 v1 = ref.vertices[edge], v2 = ref.vertices[e2];
  int incident = 0;
  for (int i = 1; i < inc.count; ++i) {
    if (glm::dot(inc.normals[i], n) < glm::dot(inc.normals[incident], n)) incident = i;
  }
  const int i2 = (incident + 1) % inc.count;
  const Vec2 w1 = inc.vertices[incident], w2 = inc.vertices[i2];
  const Real radius = ref.radius + inc.radius;
  m.normal = n;
  if (allow_corner && separation > tie) {  // cores apart: maybe corner to corner
    Real s, t;
    closest_segment_parameters(v1, v2, w1, w2, s, t);
    const bool ref_end = s == Real(0) || s == Real(1);
    const bool inc_end = t == Real(0) || t == Real(1);
    if (ref_end && inc_end) {
      const Vec2 p = s == Real(0) ? v1 : v2;
      const Vec2 q = t == Real(0) ? w1 : w2;
      Vec2 u;
      Real d;
      if (unit_and_length(q - p, u, d) && glm::dot(u, n) < Real(1) - Real(1e-4)) {
        if (d - radius > contact_distance) return m;
        m.normal = u;
        m.count = 1;
        m.points[0] = {p + ref.radius * u, q - inc.radius * u, radius - d,
                       make_feature_id(FeatureKind::Vertex, s == Real(0) ? edge : e2, FeatureKind::Vertex,
                                       t == Real(0) ? incident : i2)};
        return m;
      }
    }
  }
  const Vec2 tangent = glm::normalize(v2 - v1);
  const ClipPoint incident_points[2] = {{w1, make_feature_id(FeatureKind::Edge, edge, FeatureKind::Vertex, incident)},
                                        {w2, make_feature_id(FeatureKind::Edge, edge, FeatureKind::Vertex, i2)}};
  ClipPoint after_first[2], after_second[2];
  if (clip_segment(incident_points, after_first, -tangent, -glm::dot(tangent, v1),
                   make_feature_id(FeatureKind::Vertex, edge, FeatureKind::Edge, incident)) < 2) {
    return m;
  }
  if (clip_segment(after_first, after_second, tangent, glm::dot(tangent, v2),
                   make_feature_id(FeatureKind::Vertex, e2, FeatureKind::Edge, incident)) < 2) {
    return m;
  }
  for (const ClipPoint& c : after_second) {
    const Real gap = glm::dot(n, c.p - v1);
    const Real s = gap - radius;
    if (s > contact_distance) continue;
    m.points[m.count++] = {c.p - gap * n + ref.radius * n, c.p - inc.radius * n, -s, c.id};
  }
  return m;
}

Manifold to_world(Manifold m, const Pose& pose_a) {
  m.normal = pose_a.apply_vector(m.normal);
  for (int i = 0; i < m.count; ++i) {
    m.points[i].point_a = pose_a.apply(m.points[i].point_a);
    m.points[i].point_b = pose_a.apply(m.points[i].point_b);
  }
  return m;
}

}  // namespace detail

namespace {

/// The feature of `core` (placed at `core_pose`) at `point` given in `frame`: its vertex
/// farthest along the point's direction in its own frame (0 for a 1-vertex core).
std::uint32_t vertex_feature(const ConvexCore& core, const Pose& core_pose, const Pose& frame, const Vec2& point,
                             bool in_own_frame) {
  if (core.count == 1) return 0;
  return static_cast<std::uint32_t>(
      core.support_index(in_own_frame ? point : core_pose.inverse_apply(frame.apply(point))));
}

/// One point from the cores' signed distance (a 1-vertex core on either side, or a clip
/// that found nothing), in the frame local_core_distance measured in, then in the world.
Manifold single_point_manifold(const ConvexCore& a, const Pose& pose_a, const ConvexCore& b, const Pose& pose_b,
                               Real contact_distance) {
  Manifold m;
  if (!detail::valid_poses(pose_a, pose_b)) return m;
  const Real radii = a.radius + b.radius;
  const detail::LocalDistance d = detail::local_core_distance(a, pose_a, b, pose_b, contact_distance + radii);
  const Real gap = d.distance - radii;
  if (gap > contact_distance) return m;
  const Pose& frame = d.in_b_frame ? pose_b : pose_a;
  const Vec2 on_a = d.point_a + a.radius * d.normal, on_b = d.point_b - b.radius * d.normal;
  m.method = d.method;
  m.normal = d.normal;
  m.count = 1;
  m.points[0] = {on_a, on_b, -gap,
                 make_feature_id(FeatureKind::Vertex, vertex_feature(a, pose_a, frame, on_a, !d.in_b_frame),
                                 FeatureKind::Vertex, vertex_feature(b, pose_b, frame, on_b, d.in_b_frame))};
  return detail::to_world(m, frame);
}

}  // namespace

Manifold core_manifold(const ConvexCore& a, const Pose& pose_a, const ConvexCore& b, const Pose& pose_b,
                       Real contact_distance) {
  if (a.count < 2 || b.count < 2) return single_point_manifold(a, pose_a, b, pose_b, contact_distance);
  if (!detail::valid_poses(pose_a, pose_b)) return Manifold{};
  CorePair pair = detail::place_core_b(a, pose_a, b, pose_b);
  const Real radius = a.radius + b.radius, reach = contact_distance + radius;
  const detail::AxisSeparation on_a = detail::max_edge_separation(a, pair.b, reach);
  if (on_a.separation > reach) return Manifold{};
  detail::complete_core_pair(pair, b);
  if (!std::isfinite(pair.scale)) return Manifold{};
  const detail::AxisSeparation on_b = detail::max_edge_separation(pair.b, a, reach);
  if (on_b.separation > reach) return Manifold{};
  const Real tie = Real(1e-4) * pair.scale;
  Manifold m;
  if (on_b.separation > on_a.separation + tie) {
    m = mirrored(detail::clip_manifold(pair.b, on_b.edge, a, on_b.separation, contact_distance, tie, true));
  } else {
    m = detail::clip_manifold(a, on_a.edge, pair.b, on_a.separation, contact_distance, tie, true);
  }
  if (m.count == 0) {
    // The clip can miss only for rounded corners just within reach; measure them directly.
    return single_point_manifold(a, pose_a, b, pose_b, contact_distance);
  }
  return detail::to_world(m, pose_a);
}

}  // namespace proxima::d2
