#pragma once
/// @file narrowphase.hpp
/// The narrow phase: exact queries between two placed shapes of any kind.
///
///   intersect    do they touch or overlap (within the request's contact_distance)? Early exit.
///   distance     signed distance, witness points on each surface, normal A to B, status.
///   collide      contact manifold: up to four points with depth and stable feature ids.
///   collide_all  every contact between the parts of A and B, into a collector that may stop
///                the query early.
///
/// The single-shape verbs (world_aabb, raycast) come with this header (shape_queries.hpp).
///
/// Shapes are given in their local frames with a world transform each; every output is in
/// the world frame and follows the convention of contact.hpp, and names the parts it comes
/// from (mesh triangle, compound child) in sub_a / sub_b. One dispatch table over every
/// ShapeType reaches the pair's routine:
///   - two convex shapes: a closed-form routine where one exists (one file per pair in
///     src/narrowphase/), else GJK on the cores, EPA when the cores overlap, SAT when EPA
///     cannot answer for polytopes; half-spaces meet every shape through its support mapping.
///     These allocate nothing, throw nothing and never return NaN: a transform that is not
///     finite or whose position exceeds kMaxPlacedCoordinate (the stated range, core/tolerance.hpp)
///     gives status InvalidInput with "separated, +infinity" answers.
///   - a triangle mesh against a convex shape: the mesh's BVH walked with the shape's box,
///     the convex routine per triangle, internal-edge handling so that a shape sliding over
///     a flat mesh gets no ghost contacts; mesh against mesh: both hierarchies descended
///     together. Meshes are surfaces: crossing meshes have distance 0 (no penetration
///     depth), and a shape wholly inside a closed mesh does not touch it.
///   - a compound against anything: its BVH walked (two compounds: both together), each
///     child answered at its pose, nested compounds included.
/// The PairCache warm-starts every pair: convex pairs from the last separating axis and
/// support vertices; mesh and compound pairs by trying first the parts (compound child,
/// mesh triangle) that answered last, which makes intersect answer at once and gives
/// distance its branch-and-bound bound from the start.
/// The four entry points are not noexcept: mesh and compound pairs keep per-thread scratch
/// lists that may allocate (and the collector is the caller's code).
///
/// Cost: one table lookup to reach the pair's routine; see bench/RESULTS.md for timings.
#include <proxima/core/transform.hpp>
#include <proxima/narrowphase/contact.hpp>
#include <proxima/narrowphase/contact_collector.hpp>
#include <proxima/shapes/shape_queries.hpp>
#include <proxima/shapes/shape_ref.hpp>

namespace proxima {

/// True when A and B touch or overlap, or are apart by at most request.contact_distance;
/// stops at the first pair of parts that does. `cache` (optional) warm-starts the query and
/// is updated; keep one per ordered pair.
bool intersect(ShapeRef a, const Transform& pose_a, ShapeRef b, const Transform& pose_b,
               const PairRequest& request = {}, PairCache* cache = nullptr);

/// Signed distance between A and B with witness points and the normal from A to B: for
/// meshes and compounds, the minimum over all pairs of parts (pruned by the hierarchies;
/// ties go to the lower part index). When no part answers (a mesh of degenerate
/// triangles only), signed_distance is +infinity with status Separated.
DistanceResult distance(ShapeRef a, const Transform& pose_a, ShapeRef b, const Transform& pose_b,
                        const PairRequest& request = {}, PairCache* cache = nullptr);

/// Contact manifold of A and B: empty (count 0) when they are apart by more than
/// request.contact_distance, else up to request.max_contacts points sharing one normal. For
/// meshes and compounds: collide_all reduced along the deepest contact's normal (points
/// within about 26 degrees of it kept, then the deepest, the farthest, the largest area).
ContactManifold collide(ShapeRef a, const Transform& pose_a, ShapeRef b, const Transform& pose_b,
                        const PairRequest& request = {}, PairCache* cache = nullptr);

/// Every contact between the parts of A and B within request.contact_distance, given to
/// `collector` as found; returns as soon as the collector is done. For two convex shapes,
/// the points of their manifold.
void collide_all(ShapeRef a, const Transform& pose_a, ShapeRef b, const Transform& pose_b, const PairRequest& request,
                 ContactCollector& collector);

}  // namespace proxima
