#pragma once
// Internal: point queries on a triangle mesh given as plain arrays plus its BVH (an empty Bvh
// means "scan every triangle"), shared by TriangleMesh::contains / closest_point /
// mass_properties and testable without a TriangleMesh.

#include <proxima/shapes/bsp_polyhedron.hpp>
#include <proxima/shapes/indexed_mesh.hpp>
#include <proxima/shapes/mass_properties.hpp>
#include <proxima/shapes/surface_point.hpp>
#include <proxima/spatial/bvh.hpp>

#include <array>
#include <cstdint>
#include <mutex>
#include <optional>
#include <span>
#include <vector>

namespace proxima::detail {

/// The arrays of a mesh the point queries read (all in the mesh's local frame).
struct MeshView {
  std::span<const Vec3> vertices;                           ///< positions
  std::span<const TriangleIndices> triangles;               ///< triangles
  std::span<const std::array<std::uint32_t, 3>> neighbors;  ///< triangle across edge e (e -> e+1), kNoIndex if none
  bool closed = false;   ///< closed and outward oriented: distances are signed, contains is exact
  Real scale = Real(1);  ///< largest extent of the mesh's box (tolerances)
};

/// Nearest triangle to `point` and the nearest point on it.
struct MeshClosest {
  std::uint32_t triangle = 0xffffffffu;  ///< triangle index (kNoIndex when none)
  Vec3 point{Real(0)};                   ///< nearest surface point
  Real distance_squared = Real(0);       ///< |point - query|^2
  Vec3 pseudo_normal{Real(0)};           ///< angle-weighted pseudo-normal of the nearest feature (not unit)
};

/// Nearest surface point by BVH descent pruned with the current best distance (a linear scan
/// when `bvh` is empty), with the pseudo-normal of the feature holding it (Baerentzen and
/// Aanaes 2005). Finite `point` only.
MeshClosest mesh_closest(const MeshView& mesh, const Bvh& bvh, const Vec3& point);

/// TriangleMesh::closest_point semantics over the arrays.
SurfacePoint mesh_closest_point(const MeshView& mesh, const Bvh& bvh, const Vec3& point);

/// TriangleMesh::contains semantics: closed meshes by the sign of the pseudo-normal at the
/// nearest feature (points within the tolerance of the surface count as inside), open ones by
/// the generalised winding number >= 1/2.
bool mesh_contains(const MeshView& mesh, const Bvh& bvh, const Vec3& point);

/// Generalised winding number of `point` (Jacobson et al. 2013): the sum of the signed solid
/// angles of the triangles over 4 pi, in double. O(n).
double mesh_winding_number(const MeshView& mesh, const Vec3& point);

/// Far-field data of one BVH node for the fast winding number (Barill, Dickson, Schmidt,
/// Levin, Jacobson, "Fast winding numbers for soups and clouds", SIGGRAPH 2018): the
/// first two terms of the Taylor expansion of the solid angle of the node's triangles about
/// their area-weighted centroid, in double.
struct WindingNode {
  std::array<double, 3> center{0, 0, 0};  ///< area-weighted centroid of the triangles
  std::array<double, 3> dipole{0, 0, 0};  ///< sum of area * unit normal
  std::array<double, 9> second{};         ///< sum of area * n_i (c_t - center)_j, row major
  double area = 0;                        ///< sum of the triangle areas
  double radius = 0;                      ///< bound on |vertex - center| below the node
};

/// The WindingNode of every node of `bvh` (same indices). O(n log n) at most.
std::vector<WindingNode> build_winding_nodes(const MeshView& mesh, const Bvh& bvh);

/// Winding number by BVH descent: leaves exactly, inner nodes farther than `beta` radii
/// (> 1) whose Taylor remainder bound is at most `node_error` by their expansion.
/// `error_bound` gets the sum of those bounds, a bound on |result - exact| (rounding aside).
/// Non-empty bvh and `nodes` only.
double mesh_fast_winding_number(const MeshView& mesh, const Bvh& bvh, std::span<const WindingNode> nodes,
                                const Vec3& point, double beta, double node_error, double& error_bound);

/// TriangleMesh::contains on an open mesh: the fast winding number compared with 1/2 when
/// its error bound settles it, else the exact sum (mesh_winding_number) compared with 1/2.
bool mesh_contains_open(const MeshView& mesh, const Bvh& bvh, std::span<const WindingNode> nodes, const Vec3& point);

/// TriangleMesh::contains on a closed mesh with its BSP tree: Inside / Outside answers of
/// the tree at a tolerance of at least twice the reference's, the reference mesh_contains for
/// OnBoundary ones, so the answer equals mesh_contains' (rounding aside).
bool mesh_contains_bsp(const MeshView& mesh, const Bvh& bvh, const BspPolyhedron& bsp, const Vec3& point);

/// What a TriangleMesh's containment cache (Data::point_cache) holds once built.
struct MeshPointCacheState {
  std::optional<BspPolyhedron> bsp;  ///< closed meshes whose BSP build succeeded
  std::vector<WindingNode> winding;  ///< open meshes (empty for closed ones)
};

/// Volume, centroid and inertia of the enclosed solid by the divergence theorem (zero for an
/// open mesh).
MassProperties mesh_mass_properties(const MeshView& mesh, Real density);

}  // namespace proxima::detail
