#pragma once
/// @file convex_shapes.hpp
/// The convex shapes of the plane: point, circle, segment, capsule and convex polygon (boxes
/// are polygons). Each is a **core** — a convex polygon of 1 to 16 vertices — plus a radius:
/// the shape is the set of points within `radius` of its core (Box2D's rounded polygons,
/// the 3D module's "core + radius"). Every 2D algorithm works on the core (ConvexCore).
///
/// | shape   | core                    | radius |
/// |---------|-------------------------|--------|
/// | Point   | 1 vertex                | 0      |
/// | Circle  | 1 vertex (the centre)   | > 0    |
/// | Segment | 2 vertices              | 0      |
/// | Capsule | 2 vertices (1 if equal) | > 0    |
/// | Polygon | 3–16 vertices           | >= 0   |
///
/// All coordinates are in the shape's local frame; lengths have the caller's unit. Each shape
/// stores its core, so the algorithms take it by reference, never rebuilding it per query.

#include <proxima/core/result.hpp>
#include <proxima/d2/math.hpp>

#include <array>
#include <span>

namespace proxima::d2 {

/// Most vertices a polygon core may have.
inline constexpr int kMaxPolygonVertices = 16;

/// A convex polygon of 1 to kMaxPolygonVertices vertices, counter-clockwise, plus a radius.
/// Edge i runs from vertices[i] to vertices[(i + 1) % count]; normals[i] is its outward unit
/// normal (right_perp of the edge direction). A 2-vertex core has the two edges (0, 1) and
/// (1, 0) with opposite normals; a 1-vertex core has no edge (its normals are unused).
struct ConvexCore {
  std::array<Vec2, kMaxPolygonVertices> vertices;  ///< counter-clockwise, local frame
  std::array<Vec2, kMaxPolygonVertices> normals;   ///< outward unit edge normals, local frame
  int count = 0;                                   ///< number of vertices, 1..kMaxPolygonVertices
  Real radius = Real(0);                           ///< rounding radius (>= 0)

  /// Index of the core vertex farthest along `direction` (the first of equals).
  int support_index(const Vec2& direction) const {
    int best = 0;
    Real best_dot = glm::dot(vertices[0], direction);
    for (int i = 1; i < count; ++i) {
      const Real d = glm::dot(vertices[i], direction);
      if (d > best_dot) {
        best_dot = d;
        best = i;
      }
    }
    return best;
  }
  /// Tight rectangle of the shape (core and radius) under `pose`.
  Aabb world_aabb(const Pose& pose) const {
    Aabb box;
    for (int i = 0; i < count; ++i) box.grow(pose.apply(vertices[i]));
    return box.inflated(radius);
  }
};

/// A point (no area): its core is one vertex, radius 0.
class Point {
 public:
  /// Validated construction: finite position within kMaxCoordinate (field "position").
  static Result<Point> create(const Vec2& position = Vec2(Real(0)));
  /// The point, local frame.
  Vec2 position() const { return core_.vertices[0]; }
  /// The core: one vertex, radius 0.
  const ConvexCore& core() const { return core_; }

 private:
  explicit Point(const ConvexCore& core) : core_(core) {}
  ConvexCore core_;
};

/// A solid disc: the points within `radius` of its centre.
class Circle {
 public:
  /// Validated construction: radius finite and > 0 (field "radius"), finite centre (field
  /// "center").
  static Result<Circle> create(Real radius, const Vec2& center = Vec2(Real(0)));
  /// Radius (> 0).
  Real radius() const { return core_.radius; }
  /// Centre, local frame.
  Vec2 center() const { return core_.vertices[0]; }
  /// The core: the centre, with the circle's radius.
  const ConvexCore& core() const { return core_; }

 private:
  explicit Circle(const ConvexCore& core) : core_(core) {}
  ConvexCore core_;
};

/// A closed segment (no area), two-sided.
class Segment {
 public:
  /// Validated construction: finite end points (fields "vertices[0]", "vertices[1]") that
  /// differ (field "vertices": Degenerate when equal).
  static Result<Segment> create(const Vec2& a, const Vec2& b);
  /// First end point, local frame.
  Vec2 a() const { return core_.vertices[0]; }
  /// Second end point, local frame.
  Vec2 b() const { return core_.vertices[1]; }
  /// The core: the two end points, radius 0.
  const ConvexCore& core() const { return core_; }

 private:
  explicit Segment(const ConvexCore& core) : core_(core) {}
  ConvexCore core_;
};

/// A capsule (stadium): the points within `radius` of the segment a–b.
class Capsule {
 public:
  /// Validated construction: finite end points (fields "vertices[0]", "vertices[1]"; they
  /// may be equal, giving a circle), radius finite and > 0 (field "radius").
  static Result<Capsule> create(const Vec2& a, const Vec2& b, Real radius);
  /// First end of the core segment, local frame.
  Vec2 a() const { return core_.vertices[0]; }
  /// Second end of the core segment, local frame.
  Vec2 b() const { return core_.vertices[core_.count - 1]; }
  /// Radius (> 0).
  Real radius() const { return core_.radius; }
  /// The core: the two end points (one when they are equal), with the radius.
  const ConvexCore& core() const { return core_; }

 private:
  explicit Capsule(const ConvexCore& core) : core_(core) {}
  ConvexCore core_;
};

/// A convex polygon with 3 to 16 vertices, optionally rounded by a radius. Built as the
/// convex hull of the given points (Andrew's monotone chain), so the input order does not
/// matter; a point whose turn is within 16 machine epsilons of the points' squared scale
/// (collinear or nearly duplicate) is dropped, so the kept vertices are strictly convex.
class Polygon {
 public:
  /// Validated construction from points (any order): every coordinate finite within
  /// kMaxCoordinate (field "points[i]"), at least 3 hull vertices that enclose an area
  /// (field "points": TooFew or Degenerate), at most kMaxPolygonVertices hull vertices
  /// (field "points": OutOfRange), radius finite and >= 0 (field "radius").
  static Result<Polygon> create(std::span<const Vec2> points, Real radius = Real(0));
  /// The rectangle [-hx, hx] x [-hy, hy] (half extents finite and > 0: fields
  /// "half_extents.x", "half_extents.y"), rounded by `radius` (field "radius").
  static Result<Polygon> box(Real hx, Real hy, Real radius = Real(0));
  /// The rectangle of half extents (hx, hy) centred at `center` and turned by `angle`
  /// radians in the local frame.
  static Result<Polygon> box(Real hx, Real hy, const Vec2& center, Real angle, Real radius = Real(0));
  /// A polygon rebuilt from its vertices as vertex(i) lists them (a saved polygon): kept in
  /// this order, so vertex and edge numbers (and the feature ids of contacts) stay. Fields as
  /// in create; "points": Degenerate unless every vertex lies strictly left of every edge it
  /// is not on (a strictly convex, counter-clockwise polygon). The centroid is computed from
  /// the vertices (a box's may differ from its centre in the last bits).
  static Result<Polygon> restore(std::span<const Vec2> vertices, Real radius = Real(0));

  /// Number of vertices (3..16).
  int count() const { return core_.count; }
  /// Vertex i, counter-clockwise, local frame.
  Vec2 vertex(int i) const { return core_.vertices[i]; }
  /// Outward unit normal of edge i (vertex i to vertex i + 1).
  Vec2 normal(int i) const { return core_.normals[i]; }
  /// Rounding radius (>= 0).
  Real radius() const { return core_.radius; }
  /// Area centroid of the core polygon, local frame.
  Vec2 centroid() const { return centroid_; }
  /// The core: the vertices and normals, with the radius.
  const ConvexCore& core() const { return core_; }

 private:
  Polygon() = default;
  ConvexCore core_{};
  Vec2 centroid_{Real(0)};
};

/// Fills the outward unit normals of a counter-clockwise core whose vertices and count are
/// set (1-vertex cores get none).
void compute_core_normals(ConvexCore& core);

}  // namespace proxima::d2
