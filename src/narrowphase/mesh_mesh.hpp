#pragma once
/// @file mesh_mesh.hpp
/// Mesh against mesh (internal; reached through the dispatch table of dispatch.cpp):
/// boolean, every contact and distance between the triangle sets of two placed meshes, by a
/// simultaneous descent of their hierarchies with the triangle pair routines of the narrow
/// phase at the leaves.

#include <proxima/narrowphase/contact.hpp>
#include <proxima/narrowphase/contact_collector.hpp>
#include <proxima/shapes/shape_ref.hpp>

#include <cstdint>
#include <vector>

#include "part_hint.hpp"

namespace proxima::narrow {

/// Which node bounds the descent tests (same answers either way, up to rounding ties).
enum class MeshMeshNodes : std::uint8_t {
  Oriented,  ///< TriangleMesh::oriented_tree() boxes (built on a mesh's first such query)
  Aabb,      ///< the axis-aligned bvh() boxes: the reference path
};

/// True when a triangle of A and a triangle of B are within request.contact_distance.
/// `hint` (optional): the triangle pair tried first, then the pair that touched.
bool mesh_mesh_intersect(const TriangleMesh& a, const Transform& pose_a, const TriangleMesh& b, const Transform& pose_b,
                         const PairRequest& request, MeshMeshNodes nodes = MeshMeshNodes::Oriented,
                         PartHint* hint = nullptr);

/// Minimum distance over all triangle pairs with its witnesses (sub.triangle set on both
/// sides; sub.child left at kNoIndex for the caller to fill); 0 (status Touching) when the
/// surfaces cross: meshes are surfaces here, no penetration depth is computed. `hint`
/// (optional): the triangle pair whose distance is the descent's first bound; then the
/// answer's pair.
DistanceResult mesh_mesh_distance(const TriangleMesh& a, const Transform& pose_a, const TriangleMesh& b,
                                  const Transform& pose_b, const PairRequest& request,
                                  MeshMeshNodes nodes = MeshMeshNodes::Oriented, PartHint* hint = nullptr);

/// Adds the contacts of every triangle pair within request.contact_distance to `collector`
/// (parts in sub_a / sub_b), stopping when it is done.
void mesh_mesh_collide_all(const TriangleMesh& a, const Transform& pose_a, const TriangleMesh& b,
                           const Transform& pose_b, const PairRequest& request, ContactCollector& collector,
                           MeshMeshNodes nodes = MeshMeshNodes::Oriented);

}  // namespace proxima::narrow
