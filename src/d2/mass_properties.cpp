/// @file mass_properties.cpp
/// Mass properties of rounded 2D cores.
///
/// Steps: decompose the rounded core into pieces whose properties have closed forms — the
/// core polygon (a fan of triangles about its first vertex: area, first and second moments
/// per triangle), one rectangle of width `radius` on each edge, one disc sector at each
/// vertex (polar moment θ r⁴ / 4 about its apex, centroid 4 r sin(θ/2) / (3 θ) along its
/// bisector) — then add the masses, the first moments, and the polar moments moved to the
/// common centroid by the parallel-axis theorem. A 2-vertex core has two edges (one on each
/// side) and two half-disc sectors, a 1-vertex core one full-turn sector.

#include <proxima/d2/mass_properties.hpp>

#include <cmath>

namespace proxima::d2 {
namespace {

/// A piece: area, centroid, polar moment of area about its own centroid.
struct Piece {
  Real area = Real(0);
  Vec2 centroid{Real(0)};
  Real polar = Real(0);
};

Piece polygon_piece(const ConvexCore& core) {
  Piece p;
  if (core.count < 3) return p;
  const Vec2 o = core.vertices[0];
  Vec2 first(Real(0));
  Real polar_at_o = Real(0);
  for (int i = 1; i + 1 < core.count; ++i) {
    const Vec2 e1 = core.vertices[i] - o, e2 = core.vertices[i + 1] - o;
    const Real twice = cross(e1, e2);
    p.area += Real(0.5) * twice;
    first += Real(0.5) * twice * (e1 + e2) / Real(3);
    polar_at_o += twice / Real(12) * (glm::dot(e1, e1) + glm::dot(e1, e2) + glm::dot(e2, e2));
  }
  const Vec2 c = first / p.area;
  p.centroid = o + c;
  p.polar = polar_at_o - p.area * glm::dot(c, c);
  return p;
}

Piece edge_band_piece(const Vec2& a, const Vec2& b, const Vec2& normal, Real radius) {
  const Real length = glm::length(b - a);
  return {length * radius, (a + b) * Real(0.5) + Real(0.5) * radius * normal,
          length * radius * (length * length + radius * radius) / Real(12)};
}

Piece sector_piece(const Vec2& apex, const Vec2& bisector, Real angle, Real radius) {
  const Real area = Real(0.5) * angle * radius * radius;
  const Real offset = angle > Real(0) ? Real(4) * radius * std::sin(Real(0.5) * angle) / (Real(3) * angle) : Real(0);
  const Real polar_at_apex = angle * radius * radius * radius * radius / Real(4);
  return {area, apex + offset * bisector, polar_at_apex - area * offset * offset};
}

/// The exterior angle at vertex i (between the normals of the edges meeting there) and the
/// unit bisector of those normals.
void vertex_sector(const ConvexCore& core, int i, Real& angle, Vec2& bisector) {
  if (core.count == 1) {
    angle = Real(2) * kPi;
    bisector = Vec2(Real(1), Real(0));
    return;
  }
  const Vec2 before = core.normals[(i + core.count - 1) % core.count], after = core.normals[i];
  angle = std::atan2(cross(before, after), glm::dot(before, after));
  if (core.count == 2) angle = kPi;  // a half disc at each end of a segment core
  Vec2 unit;
  Real length;
  bisector = unit_and_length(before + after, unit, length) ? unit : right_perp(after);
}

}  // namespace

MassProperties mass_properties(const ConvexCore& core, Real density) {
  Piece pieces[1 + 2 * kMaxPolygonVertices];
  int n = 0;
  pieces[n++] = polygon_piece(core);
  if (core.radius > Real(0)) {
    const int edges = core.count == 1 ? 0 : core.count;
    for (int i = 0; i < edges; ++i) {
      pieces[n++] =
          edge_band_piece(core.vertices[i], core.vertices[(i + 1) % core.count], core.normals[i], core.radius);
    }
    for (int i = 0; i < core.count; ++i) {
      Real angle;
      Vec2 bisector;
      vertex_sector(core, i, angle, bisector);
      pieces[n++] = sector_piece(core.vertices[i], bisector, angle, core.radius);
    }
  }
  MassProperties m;
  Vec2 first(Real(0));
  for (int i = 0; i < n; ++i) m.area += pieces[i].area, first += pieces[i].area * pieces[i].centroid;
  if (!(m.area > Real(0))) {
    for (int i = 0; i < core.count; ++i) m.centroid += core.vertices[i];
    m.centroid /= static_cast<Real>(core.count);
    return m;
  }
  m.centroid = first / m.area;
  Real polar = Real(0);
  for (int i = 0; i < n; ++i)
    polar += pieces[i].polar + pieces[i].area * length_squared(pieces[i].centroid - m.centroid);
  m.mass = density * m.area;
  m.inertia = density * polar;
  return m;
}

}  // namespace proxima::d2
