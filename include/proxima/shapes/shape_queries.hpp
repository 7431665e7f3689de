#pragma once
/// @file shape_queries.hpp
/// The single-shape queries over any shape (ShapeRef): bounds and ray casts. Pair queries
/// (intersect, distance, collide, collide_all) are the narrow phase's
/// (narrowphase/narrowphase.hpp). For the concrete types, placed.hpp has the same queries
/// without the dispatch.
#include <proxima/core/transform.hpp>
#include <proxima/geometry/aabb.hpp>
#include <proxima/geometry/ray.hpp>
#include <proxima/shapes/shape_ref.hpp>

#include <optional>

namespace proxima {

/// Box of `shape` under `pose` (world frame): exact for the convex shapes, from the
/// transformed vertices for a mesh, the union of the children's boxes for a compound.
Aabb world_aabb(ShapeRef shape, const Transform& pose);

/// Closest hit of a world-frame `ray` within [0, max_t] against `shape` placed at `pose`.
/// Convex shapes are solid (origin inside: t = 0); meshes are surfaces (see TriangleMesh).
/// The hit's `sub` names the triangle of a mesh and the top-level child of a compound.
std::optional<RayHit> raycast(ShapeRef shape, const Transform& pose, const Ray& ray, Real max_t);

}  // namespace proxima
