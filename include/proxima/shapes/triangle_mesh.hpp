#pragma once
/// @file triangle_mesh.hpp
/// TriangleMesh: an immutable, shared triangle mesh shape with its BVH, triangle adjacency
/// and active-edge flags (for internal-edge handling). Copies are cheap (shared data), so
/// one mesh can be used by many objects.

#include <proxima/core/result.hpp>
#include <proxima/core/sub_shape_id.hpp>
#include <proxima/core/transform.hpp>
#include <proxima/geometry/aabb.hpp>
#include <proxima/geometry/ray.hpp>
#include <proxima/shapes/indexed_mesh.hpp>
#include <proxima/shapes/mass_properties.hpp>
#include <proxima/shapes/surface_point.hpp>
#include <proxima/spatial/bvh.hpp>

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <vector>

namespace proxima {

namespace detail {
struct OrientedTree;  // oriented node bounds for mesh-mesh queries (internal)
struct MeshDerived;   // leaf-order triangles, ray hierarchy and lazily built caches (internal)
}  // namespace detail

/// Which triangle sides a ray may hit. The front side is the one the normal
/// (b - a) x (c - a) points to.
enum class FaceCulling : std::uint8_t {
  None,   ///< both sides
  Back,   ///< only hits from the front side (the ray direction opposes the normal)
  Front,  ///< only hits from the back side
};

/// Which hierarchy a mesh ray cast traverses. Both give the same answers (same triangles,
/// same t, bit for bit): only the exact watertight triangle test decides a hit.
enum class RayTraversal : std::uint8_t {
  Wide,    ///< the 4-wide hierarchy collapsed from bvh() (four child boxes per SSE slab test,
           ///< float boxes rounded outward), falling back to Binary for rays it cannot bound
  Binary,  ///< the binary bvh(), one box at a time: the scalar reference of Wide
};

/// How TriangleMesh::create treats its input.
struct MeshCreateOptions {
  bool repair = true;                ///< run repair_mesh first (else only analyse)
  MeshRepairOptions repair_options;  ///< what repair may change
  BvhBuildOptions bvh;               ///< BVH build parameters
  /// An edge whose two triangles meet at a dihedral angle within this many radians of flat
  /// is inactive (internal-edge handling ignores contacts on it). Concave edges are always
  /// inactive, boundary and non-manifold edges always active.
  Real flat_edge_angle = Real(0.01);
};

/// An immutable triangle mesh with its BVH (local frame, length units).
class TriangleMesh {
 public:
  /// Validated construction. Errors: those of analyse_mesh (no triangle, index out of range,
  /// non-finite vertex), and TooFew when repair leaves no triangle. Open, non-manifold and
  /// inconsistently oriented meshes are accepted (see report()); queries that need a closed
  /// mesh say so. O(n log n).
  static Result<TriangleMesh> create(IndexedMesh mesh, const MeshCreateOptions& options = {});

  /// The same mesh with moved vertices (same count; same topology): the BVH is refitted,
  /// not rebuilt. Errors: InvalidArgument for a wrong count, NotFinite / OutOfRange. O(n).
  Result<TriangleMesh> deformed(std::span<const Vec3> vertices) const;

  /// Vertex positions (local frame).
  std::span<const Vec3> vertices() const { return data_->mesh.vertices; }
  /// Triangles (after repair).
  std::span<const TriangleIndices> triangles() const { return data_->mesh.triangles; }
  /// Number of triangles.
  std::uint32_t triangle_count() const { return static_cast<std::uint32_t>(data_->mesh.triangles.size()); }
  /// The three corners of triangle `index` (local frame).
  std::array<Vec3, 3> triangle(std::uint32_t index) const {
    const TriangleIndices& t = data_->mesh.triangles[index];
    return {data_->mesh.vertices[t[0]], data_->mesh.vertices[t[1]], data_->mesh.vertices[t[2]]};
  }
  /// Triangle across edge e (vertex e to vertex e+1 mod 3) of triangle `index`, or kNoIndex
  /// for a boundary or non-manifold edge.
  std::array<std::uint32_t, 3> neighbors(std::uint32_t index) const { return data_->neighbors[index]; }
  /// Bit e set: edge e of triangle `index` is active (convex or boundary), so contacts on it
  /// are real; clear: flat or concave, so a contact normal through it is a ghost.
  std::uint8_t active_edges(std::uint32_t index) const { return data_->active_edges[index]; }
  /// The analysis (and repair) report.
  const MeshReport& report() const { return data_->report; }
  /// True when closed and consistently oriented outward: contains(), signed distances and
  /// mass_properties() are then meaningful.
  bool is_closed() const { return data_->report.closed && data_->report.oriented && data_->report.volume > Real(0); }
  /// The BVH over the triangles (local frame).
  const Bvh& bvh() const { return data_->bvh; }

  /// Oriented bounds (OBB) of every bvh() node's subtree for mesh-mesh queries (internal
  /// type, src/shapes/oriented_tree.hpp): built on the first call, O(n log n), then shared
  /// by the copies of this mesh; thread-safe.
  const detail::OrientedTree& oriented_tree() const;

  /// Box of the vertices (local frame).
  Aabb local_aabb() const { return data_->bvh.bounds(); }
  /// Box in the world frame under `pose`, from the transformed vertices. O(V).
  Aabb world_aabb(const Transform& pose) const;

  /// Closest hit of `ray` (local frame) within [0, max_t]: watertight (a ray through a
  /// shared edge or vertex never slips through), ties broken by the lower triangle index.
  /// The hit's normal faces the ray origin; `sub.triangle` is the triangle index in
  /// triangles(). `traversal` picks the hierarchy (same answer either way). O(log n) typical.
  std::optional<RayHit> raycast(const Ray& ray, Real max_t, FaceCulling culling = FaceCulling::None,
                                RayTraversal traversal = RayTraversal::Wide) const;
  /// True when the ray hits any triangle within [0, max_t] (stops at the first found).
  bool raycast_any(const Ray& ray, Real max_t, FaceCulling culling = FaceCulling::None,
                   RayTraversal traversal = RayTraversal::Wide) const;
  /// Appends every hit within [0, max_t] to `hits`, sorted by t then triangle index.
  void raycast_all(const Ray& ray, Real max_t, std::vector<RayHit>& hits, FaceCulling culling = FaceCulling::None,
                   RayTraversal traversal = RayTraversal::Wide) const;

  /// For a closed mesh: true when `point` (local) is inside, or within
  /// linear_tolerance(largest box extent) of the surface (so every point of a face, edge or
  /// vertex is contained); answered by a BSP tree (BspPolyhedron) built on the first call
  /// (thread-safe; O(n log n) once, then O(depth)), which hands points near its planes to
  /// the pseudo-normal test at the nearest surface point. For an open mesh: true when its
  /// generalised winding number is at least 1/2, computed over the BVH with a far-field
  /// expansion and an error bound; only points whose bound does not settle the comparison
  /// with 1/2 take the exact sum over every triangle. Non-finite point: false.
  bool contains(const Vec3& point) const;
  /// Nearest surface point to `point` (local frame); the distance is negative inside a
  /// closed mesh (unsigned for an open one, the normal then faces `point`). O(log n) typical.
  SurfacePoint closest_point(const Vec3& point) const;
  /// Mass properties of the enclosed solid at `density` (divergence theorem); zero volume and
  /// mass for a mesh that is not closed.
  MassProperties mass_properties(Real density = Real(1)) const;

 private:
  /// The immutable data shared between copies.
  struct Data {
    IndexedMesh mesh;                                     ///< vertices and triangles after repair
    MeshReport report;                                    ///< analysis and repair report
    Bvh bvh;                                              ///< hierarchy over the triangles
    std::vector<std::array<std::uint32_t, 3>> neighbors;  ///< triangle across each edge
    std::vector<std::uint8_t> active_edges;               ///< 3 bits per triangle
    Real flat_edge_angle = Real(0.01);             ///< MeshCreateOptions::flat_edge_angle used (deformed() reuses it)
    std::shared_ptr<detail::MeshDerived> derived;  ///< internal derived data and caches (never null)
  };
  explicit TriangleMesh(std::shared_ptr<const Data> data) : data_(std::move(data)) {}
  std::shared_ptr<const Data> data_;
};

}  // namespace proxima
