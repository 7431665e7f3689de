/// @file narrowphase.cpp
/// The public narrow-phase queries: one lookup in the dispatch table (dispatch.cpp), then
/// the pair's routine.
#include <proxima/narrowphase/narrowphase.hpp>

namespace proxima {

bool intersect(ShapeRef a, const Transform& pose_a, ShapeRef b, const Transform& pose_b, const PairRequest& request,
               PairCache* cache) {
  return pair_functions(a.type(), b.type()).intersect(a.data(), pose_a, b.data(), pose_b, request, cache);
}

DistanceResult distance(ShapeRef a, const Transform& pose_a, ShapeRef b, const Transform& pose_b,
                        const PairRequest& request, PairCache* cache) {
  return pair_functions(a.type(), b.type()).distance(a.data(), pose_a, b.data(), pose_b, request, cache);
}

ContactManifold collide(ShapeRef a, const Transform& pose_a, ShapeRef b, const Transform& pose_b,
                        const PairRequest& request, PairCache* cache) {
  return pair_functions(a.type(), b.type()).collide(a.data(), pose_a, b.data(), pose_b, request, cache);
}

}  // namespace proxima
