#pragma once
/// @file world2d_workloads.hpp
/// The W9 2D collision world of shared/bench/FORMATS.md (`world2d_mixed_20k.txt`): the
/// `world2d` reader into plain structs (shape kind and numbers, pose, velocities) and the W9
/// motion rule (position folded into [lo, hi] as W8, angle0 + w t), in double precision
/// exactly as FORMATS.md writes it; and the conversion of a record's shape and pose to the 2D
/// module's (to_d2_shape, to_d2_pose).
///
/// As for W1..W8 (workloads.hpp): the header checked (kind, version 1, the keys needed;
/// unknown keys ignored), blank and `#` lines skipped, and a malformed file gives an Error
/// whose field is "<path>:<line>".

#include <proxima/d2/shape.hpp>

#include <cstdint>
#include <string>
#include <vector>

#include "support/workloads.hpp"

namespace proxima::bench {

/// A point or vector of the plane in double precision (frame given by its use).
struct Vec2d {
  double x = 0;  ///< x coordinate
  double y = 0;  ///< y coordinate

  /// Exact equality of both components.
  bool operator==(const Vec2d&) const = default;
};

/// Kind of a W9 shape.
enum class World2dShapeKind {
  Circle,     ///< `circle r`: the disc of radius r around the local origin
  Capsule2d,  ///< `capsule2d x1 y1 x2 y2 r`: points within r of the segment
  Segment2d,  ///< `segment2d x1 y1 x2 y2`: the closed segment
  Polygon,    ///< `polygon n x1 y1 ... xn yn r`: convex, counter-clockwise, rounded by r
  Box2d,      ///< `box2d hx hy r`: [-hx, hx] x [-hy, hy], rounded by r
};

/// One W9 shape in its object's local frame (lengths in the file's unit).
struct World2dShape {
  World2dShapeKind kind = World2dShapeKind::Circle;  ///< which of the fields below are used
  std::vector<Vec2d> points;  ///< capsule2d, segment2d: the two end points; polygon: the vertices
  double radius = 0;          ///< circle radius; capsule2d radius; polygon and box2d rounding (>= 0)
  Vec2d half_extents;         ///< box2d half extents hx, hy
};

/// A W9 pose `x y angle`: a local point l is at (c lx - s ly + x, s lx + c ly + y), c and s
/// the cosine and sine of the angle (radians, counter-clockwise).
struct Pose2d {
  Vec2d position;    ///< origin of the local frame in the world
  double angle = 0;  ///< rotation, radians, counter-clockwise
};

/// One W9 object: its shape, its pose at t = 0 and its constant velocities.
struct World2dObject {
  std::uint32_t id = 0;         ///< object id (= its index in World2d::objects)
  bool is_static = false;       ///< static objects never move (velocities zero)
  World2dShape shape;           ///< the shape, local frame
  Pose2d pose;                  ///< pose at t = 0
  Vec2d velocity;               ///< linear velocity of the local origin, world, per unit time
  double angular_velocity = 0;  ///< w, radians per unit time, counter-clockwise
};

/// W9 `world2d` file.
struct World2d {
  std::string name;                    ///< header name= (default: the file stem)
  int frames = 0;                      ///< header frames=: the frames are 0..frames
  double dt = 0;                       ///< header dt=: frame k is at t = k * dt
  Vec2d lo;                            ///< header lo=: lower corner of the fold rectangle
  Vec2d hi;                            ///< header hi=: upper corner of the fold rectangle
  std::vector<World2dObject> objects;  ///< object i = record i

  /// Number of objects.
  std::uint64_t size() const { return objects.size(); }
};

/// W9 `world2d` (needs objects, frames, dt, lo, hi; name defaults to the file stem).
/// Checks: ids 0..N-1 in order, positive circle and capsule radii and box half extents,
/// rounding radii >= 0, polygons of 3..8 vertices, static objects with zero velocities.
/// Polygon convexity and orientation are not checked.
Result<World2d> read_world2d(const std::string& path);

/// The W9 motion rule at time t in double precision, every operation rounded as FORMATS.md
/// writes it: x and y folded into [lo, hi] as in W8 (fold_coordinate), angle0 + w t (not
/// wrapped). Static objects: their pose as written.
Pose2d pose2d_at_time(const World2dObject& object, double t, const Vec2d& lo, const Vec2d& hi);
/// The pose of object `index` at frame k (t = frame_time(k, dt), world_workloads.hpp).
Pose2d pose2d_at_frame(const World2d& world, std::size_t index, int frame);

/// The 2D module's shape of a W9 shape (coordinates rounded to Real): Circle, Capsule,
/// Segment, or Polygon (box2d through Polygon::box). Errors: those of the shape's create.
Result<d2::Shape> to_d2_shape(const World2dShape& shape);
/// The 2D module's pose (position rounded to Real; the angle's cosine and sine computed in
/// double, then rounded).
d2::Pose to_d2_pose(const Pose2d& pose);

}  // namespace proxima::bench
