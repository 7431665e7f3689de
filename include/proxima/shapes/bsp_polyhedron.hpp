#pragma once
/// @file bsp_polyhedron.hpp
/// BspPolyhedron: a solid-leaf BSP tree of a closed, consistently oriented triangle mesh.
/// Splitting planes are face planes (autopartition) or axis-aligned planes through the
/// polygons' centroids, whichever scores best, so convex solids give a balanced tree rather
/// than a chain. Classifies points as inside / outside / on the boundary and segments or
/// rays into their inside intervals.
///
/// Build: Naylor, "Constructing good partitioning trees" (Graphics Interface 1993); Ericson,
/// Real-Time Collision Detection, ch. 8 (solid-leaf trees, thick planes, split cost).

#include <proxima/core/math.hpp>
#include <proxima/core/result.hpp>
#include <proxima/geometry/aabb.hpp>
#include <proxima/geometry/ray.hpp>
#include <proxima/shapes/indexed_mesh.hpp>

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

namespace proxima {

/// Where a point lies relative to a closed polyhedron.
enum class PointClass : std::uint8_t {
  Inside,      ///< strictly inside (farther than the tolerance from the boundary)
  Outside,     ///< strictly outside
  OnBoundary,  ///< within about the tolerance of the boundary
};

/// How BspPolyhedron::create builds the tree.
struct BspBuildOptions {
  /// Half thickness of the splitting planes (length): a vertex within it of a plane counts as
  /// on the plane (no split, no sliver fragment). Negative (default): 4 kRelativeTolerance
  /// times the largest extent of the mesh's box.
  Real plane_thickness = Real(-1);
  /// Weight of the number of split polygons against the front/back imbalance in the plane
  /// cost k * splits + (1 - k) * |front - back| - consumed (Ericson 8.3.2 suggests 0.8; consumed:
  /// polygons coplanar with a face plane and facing its way), in [0, 1].
  Real split_weight = Real(0.8);
  /// At most this many candidate face planes (faces spread evenly over the node's polygons)
  /// are scored per node, each against at most 64 of the node's polygons, so choosing a
  /// plane costs O(max_candidates) per node (>= 1).
  std::uint32_t max_candidates = 16;
  /// Also score six axis-aligned planes per node of at least 8 polygons (on each axis the
  /// median and the middle of the sampled polygon centroids). Such a plane is taken only when
  /// it leaves polygons on both sides (a face-free plane cannot tell an empty side's inside
  /// from its outside). False: pure autopartition (a convex solid of n face planes then gives
  /// a chain of depth n).
  bool axis_planes = true;
};

/// One node of the compact tree: a plane `normal . (x - reference) = offset` and two children.
/// A child index >= kBspInside is a leaf: kBspInside (solid) or kBspOutside (empty).
struct BspNode {
  Vec3 normal{Real(0), Real(0), Real(1)};  ///< unit plane normal (outward normal of a face, or an axis)
  Real offset = Real(0);                   ///< plane offset relative to BspPolyhedron::reference()
  std::uint32_t front = 0;                 ///< child on the side the normal points to
  std::uint32_t back = 0;                  ///< child on the other side
};

/// Child index of an inside (solid) leaf.
inline constexpr std::uint32_t kBspInside = 0xfffffffeu;
/// Child index of an outside (empty) leaf.
inline constexpr std::uint32_t kBspOutside = 0xffffffffu;

/// A parameter interval [t_enter, t_exit] of a ray (or segment) inside the solid.
struct BspInterval {
  Real t_enter = Real(0);  ///< where the ray enters the solid (0 when it starts inside)
  Real t_exit = Real(0);   ///< where it leaves (max_t when it ends inside)
};

/// Statistics of a built tree.
struct BspStats {
  std::uint32_t node_count = 0;      ///< inner nodes (planes)
  std::uint32_t depth = 0;           ///< longest root-to-leaf path in inner nodes
  std::uint32_t input_faces = 0;     ///< triangles of the mesh
  std::uint32_t split_faces = 0;     ///< polygons cut in two during the build
  std::uint32_t inside_leaves = 0;   ///< solid leaves
  std::uint32_t outside_leaves = 0;  ///< empty leaves
};

/// Solid-leaf BSP tree of a closed polyhedron (local frame of the mesh, length units).
/// Immutable after create; queries allocate nothing except classify_segment's output and a
/// work stack that outgrows its 64 in-place entries (a point near many planes, a segment
/// crossing many planes of a deep tree).
class BspPolyhedron {
 public:
  /// Builds the tree from the faces of `mesh`.
  ///
  /// Steps: validate with analyse_mesh (errors of analyse_mesh; InvalidArgument "mesh" when
  /// the mesh is not closed (boundary or non-manifold edges), not consistently oriented, has
  /// degenerate triangles, or encloses a non-positive volume (inward-facing triangles));
  /// then recursive partition: pick the candidate plane of least cost (face planes and, with
  /// options.axis_planes, axis-aligned planes through the polygon centroids); polygons
  /// coplanar with a face plane (within the plane thickness) and facing its way are the plane
  /// and go nowhere, coplanar ones facing the other way go to the front, the others to the
  /// side they lie on, straddling ones are split (Sutherland-Hodgman with thick planes); after
  /// a face plane an empty front list makes an outside leaf, an empty back list an inside
  /// leaf. O(n log n) typical, O(n^2) worst case.
  static Result<BspPolyhedron> create(const IndexedMesh& mesh, const BspBuildOptions& options = {});

  /// Classifies `point` (local frame). A point within `tolerance` (length; negative: the
  /// default tolerance()) of a splitting plane is sent down both sides: differing answers
  /// give OnBoundary. So points within `tolerance` of the surface are OnBoundary, and
  /// OnBoundary points are within a few `tolerance` of it. Non-finite point: Outside.
  /// O(depth), more near vertices and edges where several planes meet.
  PointClass classify(const Vec3& point, Real tolerance = Real(-1)) const;

  /// True when `point` is inside or on the boundary (classify() != Outside).
  bool contains(const Vec3& point) const { return classify(point) != PointClass::Outside; }

  /// Appends to `intervals` the parts of `ray` with t in [0, max_t] that lie inside the
  /// solid, in increasing t, adjacent pieces merged (a segment pq is the ray {p, q - p} with
  /// max_t = 1). Points on faces split the ray at the exact plane crossing; a ray lying in
  /// a face plane takes the front (outside) side of that face. Negative, NaN or infinite
  /// max_t is clamped to the mesh's box; a non-finite ray appends nothing.
  void classify_segment(const Ray& ray, Real max_t, std::vector<BspInterval>& intervals) const;

  /// The first inside interval of `ray` within [0, max_t] (entry 0 when it starts inside),
  /// or nothing when the ray never enters the solid. No allocation for trees whose
  /// traversal fits 64 pending nodes (all but pathological ones).
  std::optional<BspInterval> first_interval(const Ray& ray, Real max_t) const;

  /// The nodes (root first; empty only for an impossible empty tree).
  std::span<const BspNode> nodes() const { return nodes_; }
  /// Point the planes are expressed relative to (centre of the mesh's box).
  const Vec3& reference() const { return reference_; }
  /// Box of the mesh's vertices.
  const Aabb& bounds() const { return bounds_; }
  /// Default point tolerance (length): twice the plane thickness used at build, at least
  /// half of linear_tolerance(largest box extent).
  Real tolerance() const { return tolerance_; }
  /// Build statistics.
  const BspStats& stats() const { return stats_; }

 private:
  BspPolyhedron() = default;
  template <class Visit>
  void walk_segment(const Vec3& origin, const Vec3& direction, Real t0, Real t1, Visit&& visit) const;
  Real clamp_max_t(const Ray& ray, Real max_t) const;

  std::vector<BspNode> nodes_;
  Vec3 reference_{Real(0)};
  Aabb bounds_;
  Real tolerance_ = Real(0);
  BspStats stats_;
};

}  // namespace proxima
