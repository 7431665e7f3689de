#pragma once
/// @file box2d_peers.hpp
/// W9 shapes as Box2D 2.4 builds them (header only; for the peer tests and the benchmarks,
/// which link Box2D: include it where PROXIMA_HAVE_BOX2D is set).
///
/// Each side keeps two forms:
///   * the exact core (vertices, local frame) and rounding radius, for a b2DistanceProxy
///     (a capsule, which Box2D 2.4 lacks, is two vertices and its radius);
///   * the b2Shape that b2Collide* takes, built as a Box2D world builds it: a circle as a
///     b2CircleShape, a polygon or box as a b2PolygonShape, a segment or capsule as a
///     two-sided b2EdgeShape; every polygon and edge carries the b2_polygonRadius skin on
///     top of its own rounding radius, so b2Collide* reports the points whose gap is at
///     most the two skins.
/// Poses: b2Transform with the cosine and sine computed in double and rounded to float.

#include <array>
#include <box2d/b2_circle_shape.h>
#include <box2d/b2_collision.h>
#include <box2d/b2_distance.h>
#include <box2d/b2_edge_shape.h>
#include <box2d/b2_polygon_shape.h>
#include <cmath>

#include "support/polygons2d_workloads.hpp"

namespace proxima::bench {

/// One W9 shape and pose for Box2D.
struct Box2dShape {
  /// The b2Shape that b2Collide* takes: b2CircleShape, b2PolygonShape or b2EdgeShape.
  enum Kind { Circle, Polygon, Edge };
  Kind kind = Circle;                                    ///< which of circle, polygon, edge below is built
  std::array<b2Vec2, b2_maxPolygonVertices> vertices{};  ///< exact core, local frame
  int count = 0;                                         ///< core vertices (1, 2 or 3..8)
  float radius = 0;                                      ///< exact rounding radius (length units)
  float skin = 0;                                        ///< b2_polygonRadius for polygons and edges, 0 for circles
  b2PolygonShape polygon;                                ///< kind Polygon: core, m_radius = radius + skin
  b2CircleShape circle;                                  ///< kind Circle: centre at the origin, m_radius = radius
  b2EdgeShape edge;                                      ///< kind Edge: two-sided, m_radius = radius + skin
  b2Transform xf;                                        ///< local to world
};

/// The core vertices of a W9 shape in its local frame: the centre of a circle, the end
/// points of a segment or capsule, the polygon's vertices, a box's four corners (all
/// counter-clockwise).
inline int box2d_core(const Polygons2dShape& s, std::array<b2Vec2, b2_maxPolygonVertices>& out) {
  if (s.kind == Polygons2dKind::Circle) return out[0].Set(0.0f, 0.0f), 1;
  if (s.kind == Polygons2dKind::Box) {
    const float x = float(s.half_x), y = float(s.half_y);
    out[0].Set(-x, -y), out[1].Set(x, -y), out[2].Set(x, y), out[3].Set(-x, y);
    return 4;
  }
  for (int i = 0; i < s.count; ++i) out[std::size_t(i)].Set(float(s.vertices[i][0]), float(s.vertices[i][1]));
  return s.count;
}

/// Builds both forms of a W9 shape placed at `pose`.
inline Box2dShape make_box2d_shape(const Polygons2dShape& s, const Polygons2dPose& pose) {
  Box2dShape b;
  b.count = box2d_core(s, b.vertices);
  b.radius = float(s.radius);
  b.xf.p.Set(float(pose.x), float(pose.y));
  b.xf.q.s = float(std::sin(pose.angle));
  b.xf.q.c = float(std::cos(pose.angle));
  if (b.count == 1) {
    b.circle.m_radius = b.radius;
    return b;
  }
  b.skin = b2_polygonRadius;
  if (b.count == 2) {
    b.kind = Box2dShape::Edge;
    b.edge.SetTwoSided(b.vertices[0], b.vertices[1]);
    b.edge.m_radius = b.radius + b.skin;
    return b;
  }
  b.kind = Box2dShape::Polygon;
  b.polygon.Set(b.vertices.data(), b.count);
  b.polygon.m_radius = b.radius + b.skin;
  return b;
}

/// The b2Distance input of a pair: proxies of the exact cores and radii, useRadii = true.
/// The proxies point into `a` and `b`, which must outlive it.
inline b2DistanceInput box2d_distance_input(const Box2dShape& a, const Box2dShape& b) {
  b2DistanceInput input;
  input.proxyA.Set(a.vertices.data(), a.count, a.radius);
  input.proxyB.Set(b.vertices.data(), b.count, b.radius);
  input.transformA = a.xf;
  input.transformB = b.xf;
  input.useRadii = true;
  return input;
}

/// The b2Collide* function for (a, b) in Box2D's argument order (circle-circle,
/// polygon-circle, polygon-polygon, edge-circle, edge-polygon); false when Box2D has none
/// for this order.
inline bool box2d_collide_ordered(const Box2dShape& a, const Box2dShape& b, b2Manifold& m) {
  using K = Box2dShape::Kind;
  if (a.kind == K::Circle && b.kind == K::Circle) return b2CollideCircles(&m, &a.circle, a.xf, &b.circle, b.xf), true;
  if (a.kind == K::Polygon && b.kind == K::Circle) {
    return b2CollidePolygonAndCircle(&m, &a.polygon, a.xf, &b.circle, b.xf), true;
  }
  if (a.kind == K::Polygon && b.kind == K::Polygon) {
    return b2CollidePolygons(&m, &a.polygon, a.xf, &b.polygon, b.xf), true;
  }
  if (a.kind == K::Edge && b.kind == K::Circle) return b2CollideEdgeAndCircle(&m, &a.edge, a.xf, &b.circle, b.xf), true;
  if (a.kind == K::Edge && b.kind == K::Polygon) {
    return b2CollideEdgeAndPolygon(&m, &a.edge, a.xf, &b.polygon, b.xf), true;
  }
  return false;
}

/// True when Box2D has a b2Collide* function for the pair in some order (every pair but
/// edge-edge: segments and capsules against each other).
inline bool box2d_has_collide(const Box2dShape& a, const Box2dShape& b) {
  return a.kind != Box2dShape::Edge || b.kind != Box2dShape::Edge;
}

}  // namespace proxima::bench
