#pragma once
/// @file draw_shapes_2d.hpp
/// Emitters of 2D geometry (proxima/d2/) into a DebugDraw sink, in the plane z = 0 of the
/// world frame (x, y as the 2D world's): the outline of a rounded convex core, every shape
/// kind filled and outlined, a chain's segments with the normals of their solid sides, and a
/// shape's bounds. A 2D picture is then drawn by any 3D viewer looking down -z.
///
///   DrawBuffer buffer;
///   debug::draw_shape_2d(buffer, d2::Shape(d2::Circle::create(1).value()), pose, Rgba{70, 130, 230, 255});
#include <proxima/core/debug_draw.hpp>
#include <proxima/core/transform.hpp>
#include <proxima/d2/shape.hpp>
#include <proxima/debug/tessellate.hpp>

#include <span>
#include <vector>

namespace proxima::debug {

/// How 2D shapes are drawn.
struct Shape2DDrawOptions {
  /// Segments around a full turn of a rounded outline (a circle has this many; a capsule's
  /// two half-turns half as many each). Clamped to [3, 256].
  int segments = 32;
  bool fill = true;     ///< shapes with area as triangles (the given colour)
  bool outline = true;  ///< the boundary as lines (the colour darkened)
  /// The layer of fills, outlines, segments and markers (level 0); sweeps draw on theirs.
  DrawLayer layer = DrawLayer::Shapes;
  /// Length of the normal drawn from the middle of each chain segment towards its solid
  /// side's outside (its right, d2::ChainSegment::normal; {Normals, 0}), length units; 0: none.
  Real chain_normal_length = Real(0.2);
  Real point_size = Real(6);  ///< marker diameter of a point shape, pixels
};

/// The point (x, y) of the 2D world at z = 0.
inline Vec3 plane_point(const Vec2& p) { return Vec3(p.x, p.y, Real(0)); }

/// A 2D pose as the 3D transform that places its frame in the plane z = 0: position
/// (x, y, 0), rotation the pose's turn about +z (the half-angle quaternion, from the
/// rotation's cosine and sine without an arctangent).
Transform plane_pose(const d2::Pose& pose);

/// The colour of outlines drawn over a fill of `color`: each channel at 55 %, same opacity.
Rgba outline_color(Rgba color);

/// The boundary of `core` (local frame) counter-clockwise, every point on it: the vertices
/// pushed out by the radius, with an arc of ceil(segments * turn / 2 pi) chords around each
/// vertex (a circle: `segments` points; radius 0: the vertices alone). Chords lie inside the
/// boundary by at most radius * (1 - cos(pi / segments)). Empty for an empty core.
std::vector<Vec2> core_outline(const d2::ConvexCore& core, int segments);

/// The fill of `shape` as a mesh in its local frame at z = 0 (what a capture stores per 2D
/// object): the core_outline fanned from the mean of the core's vertices, counter-clockwise
/// seen from +z. Empty for a shape without area (a point, a segment of radius 0) and for a
/// chain (which bounds no area of its own; draw_chain draws it as lines).
DrawMesh tessellate_2d(const d2::Shape& shape, int segments);

/// Draws a convex shape at `pose`, tagged {options.layer, 0}: with area (circle, capsule,
/// polygon, rounded segment or point) its outline fanned into triangles from the vertices'
/// mean and its outline as lines; a segment as one line (full colour); a point as a marker.
void draw_convex_2d(DebugDraw& sink, const d2::ConvexCore& core, const d2::Pose& pose, Rgba color,
                    const Shape2DDrawOptions& options = {});

/// Draws a chain at `pose`: one line per segment ({options.layer, 0}) and, when
/// options.chain_normal_length > 0, each segment's normal from its middle ({Normals, 0}).
void draw_chain(DebugDraw& sink, const d2::Chain& chain, const d2::Pose& pose, Rgba color,
                const Shape2DDrawOptions& options = {});

/// Draws any 2D shape at `pose` (draw_convex_2d or draw_chain).
void draw_shape_2d(DebugDraw& sink, const d2::Shape& shape, const d2::Pose& pose, Rgba color,
                   const Shape2DDrawOptions& options = {});

/// Draws the chains of a sprite (d2::sprite_chains) placed at `pose`, as draw_chain.
void draw_sprite_chains(DebugDraw& sink, std::span<const d2::Chain> chains, const d2::Pose& pose, Rgba color,
                        const Shape2DDrawOptions& options = {});

/// Draws the world rectangle of `shape` at `pose` (Shape::world_aabb) as a flat box (z half
/// extent 0), tagged {Bounds, 0}.
void draw_bounds_2d(DebugDraw& sink, const d2::Shape& shape, const d2::Pose& pose, Rgba color);

}  // namespace proxima::debug
