#pragma once
/// @file narrowphase.hpp
/// The narrow phase: exact queries between two placed convex shapes.
///
///   intersect  do they touch or overlap (within the request's contact_distance)? Early exit.
///   distance   signed distance, witness points on each surface, normal A to B, status.
///   collide    contact manifold: up to four points with depth and stable feature ids.
///
/// Shapes are given in their local frames with a world transform each; every output is in
/// the world frame and follows the convention of contact.hpp. Every pair of shape types
/// answers every query: pairs with a closed-form routine use it (one file per pair in
/// src/narrowphase/), every other pair runs GJK on the cores, EPA when the cores overlap, and
/// SAT when EPA cannot answer for polytopes. Half-spaces meet every shape through its support
/// mapping. The functions allocate nothing, throw nothing and never return NaN: a transform
/// that is not finite gives status InvalidInput with "separated, +infinity" answers.
///
/// Cost: one table lookup to reach the pair's routine; see bench/RESULTS.md for timings.

#include <proxima/core/transform.hpp>
#include <proxima/narrowphase/contact.hpp>
#include <proxima/shapes/shape_ref.hpp>

namespace proxima {

/// True when A and B touch or overlap, or are apart by at most request.contact_distance.
/// `cache` (optional) warm-starts the query and is updated; keep one per ordered pair.
bool intersect(ShapeRef a, const Transform& pose_a, ShapeRef b, const Transform& pose_b,
               const PairRequest& request = {}, PairCache* cache = nullptr);

/// Signed distance between A and B with witness points and the normal from A to B.
DistanceResult distance(ShapeRef a, const Transform& pose_a, ShapeRef b, const Transform& pose_b,
                        const PairRequest& request = {}, PairCache* cache = nullptr);

/// Contact manifold of A and B: empty (count 0) when they are apart by more than
/// request.contact_distance, else up to request.max_contacts points sharing one normal.
ContactManifold collide(ShapeRef a, const Transform& pose_a, ShapeRef b, const Transform& pose_b,
                        const PairRequest& request = {}, PairCache* cache = nullptr);

/// Signature of a cell of the dispatch table: shapes passed as pointers to the concrete types
/// named by the cell's row (A) and column (B).
using IntersectFunction = bool (*)(const void* a, const Transform& pose_a, const void* b, const Transform& pose_b,
                                   const PairRequest& request, PairCache* cache);
/// See IntersectFunction.
using DistanceFunction = DistanceResult (*)(const void* a, const Transform& pose_a, const void* b,
                                            const Transform& pose_b, const PairRequest& request, PairCache* cache);
/// See IntersectFunction.
using CollideFunction = ContactManifold (*)(const void* a, const Transform& pose_a, const void* b,
                                            const Transform& pose_b, const PairRequest& request, PairCache* cache);

/// One cell of the N x N dispatch table.
struct PairFunctions {
  IntersectFunction intersect;
  DistanceFunction distance;
  CollideFunction collide;
  bool analytic;  ///< true when a closed-form routine serves this pair (else GJK/EPA/SAT)
  bool mirrored;  ///< true when the cell calls the (B, A) routine and mirrors its answer
};

/// The dispatch table's cell for (a, b). Never null: every cell is filled.
const PairFunctions& pair_functions(ShapeType a, ShapeType b);

}  // namespace proxima
