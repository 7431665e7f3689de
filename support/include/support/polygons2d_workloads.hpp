#pragma once
/// @file polygons2d_workloads.hpp
/// The W9 2D shape pairs of shared/bench/FORMATS.md (`polygons2d_pairs.txt`): the reader,
/// which keeps the file's numbers (so that a peer library builds its own shapes from
/// them), and the conversion of each pair to the 2D module's shapes and poses.
///
/// As for W1..W8 (workloads.hpp): the decimal text is parsed in double precision, the
/// header is checked (kind `polygons2d_pairs`, version 1, count=), blank and `#` lines are
/// skipped, and a malformed file gives an Error whose field is "<path>:<line>".

#include <proxima/core/result.hpp>
#include <proxima/d2/math.hpp>
#include <proxima/d2/shape.hpp>

#include <array>
#include <string>
#include <vector>

namespace proxima::bench {

/// Kind of a W9 shape (local frame of its pose).
enum class Polygons2dKind {
  Circle,   ///< `circle r`: the disc of radius r around the local origin
  Capsule,  ///< `capsule2d x1 y1 x2 y2 r`: the points within r of the segment
  Segment,  ///< `segment2d x1 y1 x2 y2`: the closed segment
  Polygon,  ///< `polygon n x1 y1 ... xn yn r`: convex, counter-clockwise, rounded by r
  Box,      ///< `box2d hx hy r`: [-hx, hx] x [-hy, hy], rounded by r
};

/// Most vertices of a W9 polygon.
inline constexpr int kPolygons2dMaxVertices = 8;

/// One W9 shape as written, lengths in the file's unit, local frame.
struct Polygons2dShape {
  Polygons2dKind kind = Polygons2dKind::Circle;  ///< which fields are used
  /// Vertices: the two end points of a capsule or segment, the n vertices of a polygon
  /// (counter-clockwise, as written); unused for circles and boxes.
  std::array<std::array<double, 2>, kPolygons2dMaxVertices> vertices{};
  int count = 0;      ///< number of `vertices` used (2, or n = 3..8; 0 otherwise)
  double radius = 0;  ///< circle radius (> 0), capsule radius (> 0), rounding (>= 0)
  double half_x = 0;  ///< box half extent along the local x axis (> 0)
  double half_y = 0;  ///< box half extent along the local y axis (> 0)
};

/// A W9 pose `x y angle`: a local point l is at R(angle) l + (x, y).
struct Polygons2dPose {
  double x = 0;      ///< position, x
  double y = 0;      ///< position, y
  double angle = 0;  ///< radians, counter-clockwise
};

/// One record: `<shapeA> | xA yA angleA | <shapeB> | xB yB angleB`.
struct Polygons2dPair {
  Polygons2dShape a;      ///< shape A, its local frame
  Polygons2dPose pose_a;  ///< placement of A in the world
  Polygons2dShape b;      ///< shape B, its local frame
  Polygons2dPose pose_b;  ///< placement of B in the world
};

/// Reads `polygons2d_pairs` (needs count=). Checks the kinds and their token counts,
/// positive sizes, n in 3..8, radii >= 0 (> 0 for circles and capsules).
Result<std::vector<Polygons2dPair>> read_polygons2d_pairs(const std::string& path);

/// The 2D module's shape of a W9 shape (coordinates rounded to Real): Circle, Capsule,
/// Segment, or Polygon (a box through Polygon::box). Errors: those of the shape's create.
Result<d2::Shape> to_d2_shape(const Polygons2dShape& shape);
/// The 2D module's pose: the position rounded to Real, the rotation's cosine and sine
/// computed in double and then rounded.
d2::Pose to_d2_pose(const Polygons2dPose& pose);

/// A W9 pair as the 2D module's shapes and poses.
struct Polygons2dShapePair {
  d2::Shape a;      ///< shape A, local frame
  d2::Pose pose_a;  ///< placement of A
  d2::Shape b;      ///< shape B, local frame
  d2::Pose pose_b;  ///< placement of B
};
/// Every pair converted (to_d2_shape, to_d2_pose); an error names the pair ("pairs[i].a").
Result<std::vector<Polygons2dShapePair>> to_d2_pairs(const std::vector<Polygons2dPair>& pairs);

}  // namespace proxima::bench
