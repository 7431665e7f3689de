#pragma once
/// @file oriented_tree.hpp
/// Oriented bounding boxes over the topology of a mesh's Bvh (internal to the midphase):
/// one OBB per Bvh node, bounding every triangle of the node's subtree, for the mesh-mesh
/// descent (tighter than the axis-aligned nodes: fewer node pairs for the boolean and a
/// better distance lower bound). Built by TriangleMesh::oriented_tree() on first use.

#include <proxima/shapes/triangle_mesh.hpp>

#include <span>
#include <vector>

namespace proxima::detail {

/// One oriented box (mesh frame): {center + sum_i s_i axis[i] : |s_i| <= half[i]}.
struct OrientedNode {
  Vec3 axis[3];    ///< unit, mutually orthogonal, right-handed axes
  Vec3 center{0};  ///< centre
  Vec3 half{0};    ///< half extents along the axes (>= 0)
};

/// The oriented boxes of one mesh: nodes[i] bounds the subtree of bvh().nodes()[i].
struct OrientedTree {
  std::vector<OrientedNode> nodes;  ///< same indexing as the Bvh's nodes (empty for an empty Bvh)
};

/// Builds the oriented boxes of `bvh` over `triangles` of `vertices`: axes = eigenvectors of
/// the covariance of the subtree's triangle corners (moments summed bottom-up, so each
/// node costs O(1) for them), extents = the range of the subtree's corners projected on
/// the axes (O(n) per tree level, O(n log n) in all). No rounding margin is added: the
/// box holds every corner up to the rounding of the projections.
OrientedTree build_oriented_tree(const Bvh& bvh, std::span<const Vec3> vertices,
                                 std::span<const TriangleIndices> triangles);

}  // namespace proxima::detail
