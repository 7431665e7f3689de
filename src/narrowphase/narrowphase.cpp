/// @file narrowphase.cpp
/// The public narrow-phase queries: one lookup in the dispatch table (dispatch.cpp), then
/// the pair's routine.
#include <proxima/narrowphase/narrowphase.hpp>

#include <limits>

#include "dispatch.hpp"

namespace proxima {

bool intersect(ShapeRef a, const Transform& pose_a, ShapeRef b, const Transform& pose_b, const PairRequest& request,
               PairCache* cache) {
  return narrow::pair_functions(a.type(), b.type()).intersect(a.data(), pose_a, b.data(), pose_b, request, cache);
}

DistanceResult distance(ShapeRef a, const Transform& pose_a, ShapeRef b, const Transform& pose_b,
                        const PairRequest& request, PairCache* cache) {
  constexpr Real inf = std::numeric_limits<Real>::infinity();
  DistanceResult d =
      narrow::pair_functions(a.type(), b.type()).distance(a.data(), pose_a, b.data(), pose_b, request, cache, inf);
  if (!(d.signed_distance < inf) && d.status != PairStatus::InvalidInput) {
    d = DistanceResult{};  // no part answered: "separated, +infinity"
    d.signed_distance = inf;
  }
  return d;
}

ContactManifold collide(ShapeRef a, const Transform& pose_a, ShapeRef b, const Transform& pose_b,
                        const PairRequest& request, PairCache* cache) {
  return narrow::pair_functions(a.type(), b.type()).collide(a.data(), pose_a, b.data(), pose_b, request, cache);
}

void collide_all(ShapeRef a, const Transform& pose_a, ShapeRef b, const Transform& pose_b, const PairRequest& request,
                 ContactCollector& collector) {
  narrow::pair_functions(a.type(), b.type()).collide_all(a.data(), pose_a, b.data(), pose_b, request, collector);
}

}  // namespace proxima
