#pragma once
/// @file dispatch.hpp
/// Internal: the cell type of the narrow phase's dispatch table over every ShapeType
/// (dispatch.cpp) and the lookup the public queries use. Shapes are passed as pointers to
/// the concrete types named by the cell's row (A) and column (B).
#include <proxima/core/transform.hpp>
#include <proxima/narrowphase/contact.hpp>
#include <proxima/narrowphase/contact_collector.hpp>
#include <proxima/shapes/shape_type.hpp>

namespace proxima::narrow {

/// See PairFunctions.
using IntersectFunction = bool (*)(const void* a, const Transform& pose_a, const void* b, const Transform& pose_b,
                                   const PairRequest& request, PairCache* cache);
/// `cutoff`: a composite pair (mesh, compound) searches only for answers below it (branch
/// and bound across parts); a convex pair ignores it.
using DistanceFunction = DistanceResult (*)(const void* a, const Transform& pose_a, const void* b,
                                            const Transform& pose_b, const PairRequest& request, PairCache* cache,
                                            Real cutoff);
/// See PairFunctions.
using CollideFunction = ContactManifold (*)(const void* a, const Transform& pose_a, const void* b,
                                            const Transform& pose_b, const PairRequest& request, PairCache* cache);
/// See PairFunctions.
using CollideAllFunction = void (*)(const void* a, const Transform& pose_a, const void* b, const Transform& pose_b,
                                    const PairRequest& request, ContactCollector& collector);

/// One cell of the N x N dispatch table: the four queries for one ordered pair of types.
struct PairFunctions {
  IntersectFunction intersect;
  DistanceFunction distance;
  CollideFunction collide;
  CollideAllFunction collide_all;
  bool analytic;  ///< a closed-form routine serves this (convex) pair, else GJK/EPA/SAT or a hierarchy
  bool mirrored;  ///< the cell calls the (B, A) routine and mirrors its answer
};

/// The dispatch table's cell for (a, b). Never null: every cell is filled.
const PairFunctions& pair_functions(ShapeType a, ShapeType b) noexcept;

}  // namespace proxima::narrow
