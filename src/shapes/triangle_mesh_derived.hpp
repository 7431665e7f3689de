#pragma once
/// @file triangle_mesh_derived.hpp
/// Internal: what a TriangleMesh derives from its triangles and hierarchy for the library's
/// own queries, kept out of the public header: the triangles in BVH leaf order and the
/// 4-wide ray hierarchy (built by create and deformed), and the caches built on first use
/// (oriented node bounds for mesh against mesh, the containment structure).

#include <proxima/core/math.hpp>

#include <array>
#include <memory>
#include <vector>

#include "shapes/lazy_slot.hpp"
#include "shapes/mesh_point_queries.hpp"
#include "shapes/oriented_tree.hpp"
#include "shapes/ray_bvh.hpp"

namespace proxima::detail {

/// The derived data of one TriangleMesh (shared by its copies; a deformed mesh builds its own).
struct MeshDerived {
  /// Corners of triangle bvh.primitives()[i] at index i (BVH leaf order, so a leaf's
  /// triangles are contiguous for the ray casts).
  std::vector<std::array<Vec3, 3>> leaf_triangles;
  /// 4-wide hierarchy for ray casts over the same leaves (RayTraversal::Wide); empty when
  /// the mesh's bounds do not fit its float layout.
  RayBvh ray_bvh;
  /// Oriented node bounds for mesh-mesh queries, built by oriented_tree() on first use.
  LazySlot<OrientedTree> oriented;
  /// Built by the first contains(): the BSP tree of a closed mesh, the far-field winding
  /// data of an open one.
  LazySlot<MeshPointCacheState> point_cache;
};

}  // namespace proxima::detail
