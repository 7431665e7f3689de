#pragma once
/// @file convex_hull.hpp
/// ConvexHull: the convex hull of a point set, built once with qhull and stored as a
/// polygonal boundary (merged coplanar faces, not triangulated) with vertex adjacency for
/// hill-climbing support queries.

#include <proxima/shapes/unrounded_core.hpp>

#include <cstdint>
#include <memory>
#include <span>
#include <utility>
#include <vector>

namespace proxima {

namespace detail {
struct HullData;  // the hull's full data (internal, src/shapes/convex_hull_data.hpp)
}  // namespace detail

/// A planar polygonal face of a ConvexHull.
///
/// Its vertex indices are `face_indices()[first_index .. first_index + index_count)`, in
/// counter-clockwise order seen from outside the hull. Its plane is `normal . x = offset`
/// (local frame) with `normal` unit and pointing out of the hull.
struct HullFace {
  std::uint32_t first_index = 0;           ///< first entry of the face's loop in face_indices()
  std::uint32_t index_count = 0;           ///< number of vertices of the loop (>= 3)
  Vec3 normal{Real(0), Real(0), Real(1)};  ///< unit outward plane normal, local frame
  Real offset = Real(0);                   ///< plane offset: normal . x = offset (length)
};

/// An edge of a ConvexHull, listed once, with the two faces that share it.
///
/// Seen from outside, the edge runs v0 -> v1 in the loop of `face0` and v1 -> v0 in the
/// loop of `face1` (face0 != face1).
struct HullEdge {
  std::uint32_t v0 = 0;     ///< first vertex index (into vertices())
  std::uint32_t v1 = 0;     ///< second vertex index
  std::uint32_t face0 = 0;  ///< face whose CCW loop traverses v0 -> v1
  std::uint32_t face1 = 0;  ///< face whose CCW loop traverses v1 -> v0
};

/// Solid convex polyhedron: the convex hull of a set of points, in its local frame.
///
/// Built by `create` with qhull (Barber, Dobkin, Huhdanpaa, "The Quickhull Algorithm for
/// Convex Hulls", ACM TOMS 1996) in double precision; coplanar facets are merged into
/// polygonal faces. Interior and duplicate input points are dropped. The hull data is
/// immutable and shared: copies are cheap (one reference count).
///
/// Members as every shape (see Sphere): support, core_support + core_radius (the core is
/// the hull itself, core_radius is 0), local_aabb, world_aabb, raycast, contains,
/// closest_point, mass_properties — all in the local frame unless the name says world.
class ConvexHull : public UnroundedCore<ConvexHull> {
 public:
  /// Dispatch tag.
  static constexpr ShapeType kType = ShapeType::ConvexHull;

  /// Hulls with at most this many vertices answer support_index by a linear scan (four
  /// vertices per step with SSE2 in float); larger ones hill-climb from the start vertex.
  /// Measured (callgrind, random directions, warm-started climb): at 32 vertices the scan
  /// takes about 330 instructions against 460 for the climb, at 64 about 600 against 620,
  /// and the scan's straight-line code runs at a much higher rate than the climb's
  /// data-dependent branches and loads.
  static constexpr std::uint32_t kLinearScanMaxVertices = 64;

  /// Validated construction from a point cloud (local frame).
  ///
  /// Errors: TooFew (fewer than 4 points, field "points"); NotFinite / OutOfRange
  /// ("points[i].x" etc.); Degenerate (all points coincident, collinear or coplanar within
  /// tolerance, field "points"); Internal (qhull failed, message says so). O(n log n)
  /// expected; qhull's merging dominates for large clouds (100k points take seconds), so
  /// build hulls once, offline or at load time.
  static Result<ConvexHull> create(std::span<const Vec3> points);

  /// Hull vertices (local frame), each one an input point; interior and duplicate input
  /// points are dropped.
  std::span<const Vec3> vertices() const { return data_->vertices; }
  /// The faces: convex polygons, planar within tolerance(); facets coplanar within the
  /// resolution of the input are merged into one face (a facet that merging left bent
  /// comes as several convex pieces sharing its plane).
  std::span<const HullFace> faces() const { return data_->faces; }
  /// Concatenated CCW vertex loops of every face (indices into vertices()).
  std::span<const std::uint32_t> face_indices() const { return data_->face_indices; }
  /// The vertex loop of face `face` (indices into vertices()), CCW seen from outside.
  std::span<const std::uint32_t> face_vertices(std::uint32_t face) const {
    const HullFace& f = data_->faces[face];
    return std::span<const std::uint32_t>(data_->face_indices).subspan(f.first_index, f.index_count);
  }
  /// Every edge once, with the faces on its two sides. V - E + F = 2.
  std::span<const HullEdge> edges() const { return data_->edges; }
  /// Vertices joined to `vertex` by a hull edge (compressed sparse rows). Use
  /// support_index rather than climbing these edges: it also moves across faces.
  std::span<const std::uint32_t> vertex_neighbors(std::uint32_t vertex) const {
    const std::uint32_t b = data_->neighbor_offsets[vertex];
    const std::uint32_t e = data_->neighbor_offsets[vertex + 1];
    return std::span<const std::uint32_t>(data_->neighbors).subspan(b, e - b);
  }

  /// Index of a vertex farthest in `direction` (local frame; any vector, zero gives a
  /// valid vertex). Up to kLinearScanMaxVertices it scans every vertex and returns the
  /// first (lowest index) of largest dot product, 0 when none compares larger than
  /// -infinity (a NaN direction). Above kLinearScanMaxVertices it hill-climbs from `start_vertex`
  /// (clamped to a valid index; pass the previous answer to warm-start), moving to a
  /// vertex sharing a face with a strictly larger dot product until none exists. That
  /// cannot cycle, and it is exact on a convex polyhedron; moving across faces rather
  /// than only along edges keeps it exact on faces that merging left slightly bent.
  /// O(V) worst case, O(1) amortised when coherent.
  std::uint32_t support_index(const Vec3& direction, std::uint32_t start_vertex = 0) const;
  /// The linear scan of support_index at any size: the first (lowest index) vertex of
  /// largest dot product with `direction` (local frame), 0 for a NaN direction. In float
  /// with SSE2, four vertices per step over the vertices stored in blocks of four
  /// (x x x x y y y y z z z z); exactly the index of scalar_support_index. O(V), no branch on the data but the last
  /// block.
  std::uint32_t scan_support_index(const Vec3& direction) const;
  /// The scalar reference of scan_support_index (one vertex per step, same answer).
  std::uint32_t scalar_support_index(const Vec3& direction) const;
  /// The hill-climb of support_index at any size, from `start_vertex` (clamped): a vertex
  /// of largest dot product, not necessarily the first one on ties. O(1) amortised when
  /// the start is the answer to a nearby direction, O(V) worst case.
  std::uint32_t climb_support_index(const Vec3& direction, std::uint32_t start_vertex) const;

  /// Farthest point of the hull in `direction` (local frame): a vertex. Dot products are
  /// taken relative to the centre of the box, so ties are resolved at the hull's own
  /// resolution even far from the local origin.
  Vec3 support(const Vec3& direction) const { return data_->vertices[support_index(direction)]; }

  /// Tight box of the vertices in the local frame.
  Aabb local_aabb() const { return data_->local_box; }
  /// Tight box in the world frame under `pose`: the box of the transformed vertices. O(V).
  Aabb world_aabb(const Transform& pose) const;

  /// First hit of `ray` (local frame) with the solid hull within [0, max_t], by
  /// Cyrus–Beck clipping against the face planes. Origin inside: t = 0, normal
  /// -direction/|direction|.
  std::optional<RayHit> raycast(const Ray& ray, Real max_t) const;
  /// True when `point` (local) is inside the hull or within tolerance() of it. O(F), or
  /// O(F + E) for points within tolerance in front of a face.
  bool contains(const Vec3& point) const;
  /// Nearest surface point to `point` (local) with signed distance: outside, the nearest
  /// point over all faces; inside, the projection on the nearest face plane (negative
  /// distance, normal = that face's normal).
  SurfacePoint closest_point(const Vec3& point) const;
  /// Volume, mass, centroid and inertia about the centroid for uniform `density`, by the
  /// divergence theorem over a tetrahedral decomposition (Tonon 2004; Eberly, "Polyhedral
  /// Mass Properties").
  MassProperties mass_properties(Real density = Real(1)) const;

  /// Length scale of the hull (largest extent of its box).
  Real scale() const { return data_->scale; }
  /// Absolute distance below which a point counts as on the surface: kRelativeTolerance *
  /// scale() plus how far the merged faces deviate from the input points (a few times the
  /// resolution of Real at the hull's size). Queries work relative to the centre of the
  /// box, so this does not grow with the distance from the local origin.
  Real tolerance() const { return data_->tolerance; }

 private:
  friend struct detail::HullData;  // derives from Boundary

  /// What the inline accessors above read: the hull's boundary, box and tolerance (local
  /// frame, length units). The rest of the hull's data (the support scan's blocks, the
  /// hill-climbing adjacency, the shifted copies the queries work on, the mass properties)
  /// is internal: detail::HullData (src/shapes/convex_hull_data.hpp), derived from this.
  struct Boundary {
    std::vector<Vec3> vertices;                   ///< hull vertices, local frame
    std::vector<HullFace> faces;                  ///< polygonal faces
    std::vector<std::uint32_t> face_indices;      ///< concatenated CCW face loops
    std::vector<HullEdge> edges;                  ///< every edge once
    std::vector<std::uint32_t> neighbor_offsets;  ///< CSR offsets, size vertices + 1
    std::vector<std::uint32_t> neighbors;         ///< CSR adjacency over edges
    Aabb local_box;                               ///< box of the vertices
    Real scale = Real(1);                         ///< largest box extent (length)
    Real tolerance = Real(0);                     ///< absolute tolerance of contains / on-surface tests (length)
  };

  /// Shares `data` (built by create).
  explicit ConvexHull(std::shared_ptr<const detail::HullData> data);
  /// The full data (defined in src/shapes/convex_hull_data.hpp, for the library's own code).
  const detail::HullData& data() const;

  std::shared_ptr<const Boundary> data_;  // a detail::HullData: immutable and shared, copies are cheap
};

}  // namespace proxima
