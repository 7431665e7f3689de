#pragma once
/// @file draw_shapes.hpp
/// Emitters of the geometry layers into a DebugDraw sink: a shape's surface at a pose, its
/// bounds, the nodes of a hierarchy (a mesh's or a compound's Bvh) by level, and the nodes
/// of the dynamic AABB tree broad phase (or any structure's proxy boxes). Every emitter
/// makes one call per primitive kind. Everything drawn is in the world frame.
#include <proxima/broadphase/dynamic_aabb_tree.hpp>
#include <proxima/core/debug_draw.hpp>
#include <proxima/core/transform.hpp>
#include <proxima/debug/tessellate.hpp>
#include <proxima/geometry/aabb.hpp>
#include <proxima/shapes/shape_ref.hpp>
#include <proxima/spatial/bvh.hpp>

#include <span>

namespace proxima::debug {

/// A colour for level `level` of a hierarchy (a fixed palette of 8, cycling).
Rgba level_color(int level);

/// The box `box` (world frame) as a DrawBox with no rotation.
DrawBox box_of(const Aabb& box, Rgba color, DrawTag tag);

/// Draws the surface of `shape` placed at `pose` (local -> world) as triangles of
/// tessellate(shape, options), tagged {Shapes, 0}.
void draw_shape(DebugDraw& sink, ShapeRef shape, const Transform& pose, Rgba color,
                const TessellationOptions& options = {});

/// Draws the triangles of `mesh` (local frame) placed at `pose`, tagged `tag`.
void draw_mesh(DebugDraw& sink, const DrawMesh& mesh, const Transform& pose, Rgba color, DrawTag tag);

/// Draws the world box of `shape` at `pose` (world_aabb), tagged {Bounds, 0}.
void draw_bounds(DebugDraw& sink, ShapeRef shape, const Transform& pose, Rgba color);

/// Draws the nodes of `bvh` (boxes in the frame of its primitives) placed at `pose` as
/// oriented boxes, node at depth k (the root at 0) tagged {Bvh, k} and coloured
/// level_color(k); only depths in [min_level, max_level]. O(nodes).
void draw_bvh(DebugDraw& sink, const Bvh& bvh, const Transform& pose, int min_level = 0, int max_level = 64);

/// The hierarchy of a shape that has one (triangle mesh: over its triangles; compound:
/// over its children), drawn as draw_bvh at `pose`; nothing for the other kinds.
void draw_shape_bvh(DebugDraw& sink, ShapeRef shape, const Transform& pose, int min_level = 0, int max_level = 64);

/// Draws every node of `tree` (both trees, leaves with their fat boxes) tagged
/// {BroadPhase, depth}, coloured level_color(depth); only depths in [min_level, max_level].
void draw_broadphase(DebugDraw& sink, const DynamicAabbTree& tree, int min_level = 0, int max_level = 64);

/// Draws proxy boxes (world frame) of a broad-phase structure that exposes no nodes, tagged
/// {BroadPhase, 0}.
void draw_proxy_boxes(DebugDraw& sink, std::span<const Aabb> boxes, Rgba color);

}  // namespace proxima::debug
