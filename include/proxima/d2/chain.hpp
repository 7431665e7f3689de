#pragma once
/// @file chain.hpp
/// Chain: a polyline of one-sided segments (open, or a closed loop) for level geometry —
/// terrain, tile rows, walls. Each segment knows its neighbours (ghost vertices), so a body
/// sliding over the seam between two segments meets one smooth surface and never catches
/// on an internal corner.
///
/// Sidedness: a segment collides only on the **right** side of its direction (the outside
/// of a counter-clockwise loop, the same side as a polygon's outward normals): a floor that
/// bodies stand on runs right to left (from larger x to smaller x). Contacts, ray hits and
/// casts see only that side; distance and containment-free queries (closest point) treat
/// the segments as two-sided lines.

#include <proxima/core/result.hpp>
#include <proxima/d2/convex_shapes.hpp>

#include <span>
#include <vector>

namespace proxima::d2 {

/// One segment of a chain with its ghost vertices: the previous and next chain points that
/// decide which contact normals the segment may produce at its ends.
struct ChainSegment {
  Vec2 ghost_prev{Real(0)};  ///< the chain point before `a` (meaningful when has_prev)
  Vec2 a{Real(0)};           ///< start of the segment
  Vec2 b{Real(0)};           ///< end of the segment
  Vec2 ghost_next{Real(0)};  ///< the chain point after `b` (meaningful when has_next)
  bool has_prev = false;     ///< false at the first segment of an open chain
  bool has_next = false;     ///< false at the last segment of an open chain

  /// Outward unit normal: the right side of a -> b.
  Vec2 normal() const;
  /// The segment as a two-sided core (2 vertices, radius 0).
  ConvexCore core() const;
};

/// A chain of segments through `points`; closed (a loop) or open.
class Chain {
 public:
  /// Validated construction: every point finite within kMaxCoordinate (field "points[i]"),
  /// at least 2 points (3 for a loop; field "points": TooFew), consecutive points distinct
  /// (field "points[i]": Degenerate; for a loop the last and the first too).
  static Result<Chain> create(std::span<const Vec2> points, bool loop);

  /// The chain points, local frame.
  const std::vector<Vec2>& points() const { return points_; }
  /// True for a closed loop (last point joined to the first).
  bool loop() const { return loop_; }
  /// Number of segments: points - 1 (open) or points (loop).
  int segment_count() const { return static_cast<int>(loop_ ? points_.size() : points_.size() - 1); }
  /// Segment i (0 <= i < segment_count()) with its ghost vertices.
  ChainSegment segment(int i) const;
  /// Rectangle of every point, local frame.
  Aabb local_aabb() const { return local_aabb_; }
  /// Tight rectangle of the chain under `pose` (O(points)).
  Aabb world_aabb(const Pose& pose) const;

 private:
  Chain() = default;
  std::vector<Vec2> points_;
  bool loop_ = false;
  Aabb local_aabb_;
};

}  // namespace proxima::d2
