/// @file dispatch.cpp
/// The N x N dispatch table of the narrow phase, built at compile time over ShapeType.
/// Cell (A, B) with A not after B calls narrow::pair_intersect / pair_distance / pair_collide
/// on the concrete types: overload resolution picks a pair's closed-form routine when its
/// group header declares one (kAnalyticPair<A, B>), else the generic GJK / EPA / SAT
/// templates. Cell (A, B) with A after B calls the (B, A) routine and mirrors its answer
/// (witnesses swapped, normal negated; intersect unchanged).
#include <proxima/narrowphase/narrowphase.hpp>
#include <proxima/shapes/placed.hpp>

#include <array>
#include <cstddef>
#include <limits>
#include <utility>

// Closed-form routines first, so that the generic templates below see them.
#include "pairs_halfspace.hpp"
#include "pairs_polyhedral.hpp"
#include "pairs_rounded.hpp"
// Generic routines.
#include "generic_distance.hpp"
// The generic manifold calls pair_distance: it must come after every declaration of it.
#include "generic_collide.hpp"

namespace proxima {

namespace {

template <class A, class B>
inline constexpr bool kHalfSpaceInvolved = std::is_same_v<A, HalfSpace> || std::is_same_v<B, HalfSpace>;

// Support-mapping answer for a half-space pair that has no closed-form routine (yet):
// B = {n . x <= d}; signed distance = n_w . s_A(-n_w) - d_w, normal -n_w (A to B).
template <class A>
DistanceResult support_halfspace_distance(const A& a, const Transform& pose_a, const HalfSpace& b,
                                          const Transform& pose_b, const PairRequest& request) {
  if (!narrow::finite_poses(pose_a, pose_b)) return narrow::invalid_distance();
  const Vec3 n = pose_b.apply_vector(b.normal());
  const Real d = b.offset() + glm::dot(n, pose_b.position);
  const Vec3 p = support(a, pose_a, -n);
  DistanceResult r;
  r.signed_distance = glm::dot(n, p) - d;
  r.normal = -n;
  r.point_a = p;
  r.point_b = p - r.signed_distance * n;
  r.method = PairMethod::Support;
  const Real scale = std::max({std::abs(d), glm::length(pose_a.position), Real(1)});
  r.status = status_from_distance(r.signed_distance, narrow::resolve_tolerance(request, scale));
  return r;
}

template <class A, class B>
DistanceResult cell_distance_direct(const void* a, const Transform& pose_a, const void* b, const Transform& pose_b,
                                    const PairRequest& request, PairCache* cache) {
  const A& sa = *static_cast<const A*>(a);
  const B& sb = *static_cast<const B*>(b);
  if constexpr (kHalfSpaceInvolved<A, B> && !narrow::kAnalyticPair<A, B>) {
    (void)cache;
    return support_halfspace_distance(sa, pose_a, sb, pose_b, request);
  } else {
    return narrow::pair_distance(sa, pose_a, sb, pose_b, request, cache);
  }
}

template <class A, class B>
bool cell_intersect_direct(const void* a, const Transform& pose_a, const void* b, const Transform& pose_b,
                           const PairRequest& request, PairCache* cache) {
  if constexpr (kHalfSpaceInvolved<A, B> && !narrow::kAnalyticPair<A, B>) {
    const DistanceResult d = cell_distance_direct<A, B>(a, pose_a, b, pose_b, request, cache);
    return d.status != PairStatus::InvalidInput && d.signed_distance <= request.contact_distance;
  } else {
    return narrow::pair_intersect(*static_cast<const A*>(a), pose_a, *static_cast<const B*>(b), pose_b, request, cache);
  }
}

template <class A, class B>
ContactManifold cell_collide_direct(const void* a, const Transform& pose_a, const void* b, const Transform& pose_b,
                                    const PairRequest& request, PairCache* cache) {
  if constexpr (kHalfSpaceInvolved<A, B> && !narrow::kAnalyticPair<A, B>) {
    if (!narrow::finite_poses(pose_a, pose_b)) return narrow::invalid_manifold();
    return narrow::manifold_from_distance(cell_distance_direct<A, B>(a, pose_a, b, pose_b, request, cache), request);
  } else {
    return narrow::pair_collide(*static_cast<const A*>(a), pose_a, *static_cast<const B*>(b), pose_b, request, cache);
  }
}

// Mirrored cells: (A, B) with A after B runs (B, A) and swaps.
template <class A, class B>
bool cell_intersect_mirrored(const void* a, const Transform& pose_a, const void* b, const Transform& pose_b,
                             const PairRequest& request, PairCache* cache) {
  return cell_intersect_direct<B, A>(b, pose_b, a, pose_a, request, cache);
}

template <class A, class B>
DistanceResult cell_distance_mirrored(const void* a, const Transform& pose_a, const void* b, const Transform& pose_b,
                                      const PairRequest& request, PairCache* cache) {
  return mirrored(cell_distance_direct<B, A>(b, pose_b, a, pose_a, request, cache));
}

template <class A, class B>
ContactManifold cell_collide_mirrored(const void* a, const Transform& pose_a, const void* b, const Transform& pose_b,
                                      const PairRequest& request, PairCache* cache) {
  return mirrored(cell_collide_direct<B, A>(b, pose_b, a, pose_a, request, cache));
}

template <std::size_t I>
constexpr PairFunctions make_cell() {
  constexpr auto ta = static_cast<ShapeType>(I / kShapeTypeCount);
  constexpr auto tb = static_cast<ShapeType>(I % kShapeTypeCount);
  using A = ShapeTypeAt<ta>;
  using B = ShapeTypeAt<tb>;
  if constexpr (ta <= tb) {
    return PairFunctions{&cell_intersect_direct<A, B>, &cell_distance_direct<A, B>, &cell_collide_direct<A, B>,
                         narrow::kAnalyticPair<A, B>, false};
  } else {
    return PairFunctions{&cell_intersect_mirrored<A, B>, &cell_distance_mirrored<A, B>, &cell_collide_mirrored<A, B>,
                         narrow::kAnalyticPair<B, A>, true};
  }
}

template <std::size_t... I>
constexpr std::array<PairFunctions, sizeof...(I)> make_table(std::index_sequence<I...>) {
  return {make_cell<I>()...};
}

constexpr std::size_t kCells = static_cast<std::size_t>(kShapeTypeCount) * static_cast<std::size_t>(kShapeTypeCount);
constexpr std::array<PairFunctions, kCells> kTable = make_table(std::make_index_sequence<kCells>{});

}  // namespace

const PairFunctions& pair_functions(ShapeType a, ShapeType b) {
  const auto ia = static_cast<std::size_t>(a);
  const auto ib = static_cast<std::size_t>(b);
  PROXIMA_ASSERT(ia < static_cast<std::size_t>(kShapeTypeCount) && ib < static_cast<std::size_t>(kShapeTypeCount));
  return kTable[ia * static_cast<std::size_t>(kShapeTypeCount) + ib];
}

}  // namespace proxima
