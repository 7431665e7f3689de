#pragma once
/// @file dispatch_cells.hpp
/// Internal: the cells of the narrow phase's dispatch table, one per ordered pair of
/// ShapeTypes; included only by the generated row files (dispatch_row.cpp.in), each of which
/// builds one row with pair_table.hpp's make_pair_row.
///
/// Convex cells: cell (A, B) with A not after B calls pair_intersect /
/// pair_distance / pair_collide on the concrete types: overload resolution picks a pair's
/// closed-form routine when its group header declares one (kAnalyticPair<A, B>), else the
/// generic GJK / EPA / SAT templates; every half-space pair has its routine
/// (pairs_halfspace.hpp). collide_all gives the manifold's points.
/// Composite cells (a mesh or a compound on either side): a compound side runs
/// compound_pairs.cpp, else a mesh against a convex shape runs mesh_convex.cpp and two
/// meshes mesh_mesh.cpp; their collide reduces collide_all to one manifold.
/// Cell (A, B) with A after B (in ShapeType order; a compound side always goes first, a mesh
/// side before a convex one) calls the (B, A) routine and mirrors its answer (witnesses and
/// parts swapped, normal negated; intersect unchanged). A mirrored convex cell calls the
/// (B, A) cell through the table (cell_of), so each convex pair's templates are compiled once,
/// in the row of the type that comes first.
#include <proxima/narrowphase/narrowphase.hpp>
#include <proxima/shapes/placed.hpp>

#include <algorithm>
#include <array>
#include <cstddef>
#include <limits>
#include <type_traits>
#include <utility>

#include "dispatch.hpp"
#include "dispatch_rows.hpp"
#include "pair_table.hpp"
// Closed-form routines first, so that the generic templates below see them.
#include "pairs_curved.hpp"
#include "pairs_halfspace.hpp"
#include "pairs_polyhedral.hpp"
#include "pairs_rounded.hpp"
// Generic routines.
#include "generic_distance.hpp"
// The generic manifold calls pair_distance: it must come after every declaration of it.
#include "generic_collide.hpp"
// Meshes and compounds.
#include "collector_adapters.hpp"
#include "compound_pairs.hpp"
#include "mesh_convex.hpp"
#include "mesh_mesh.hpp"

namespace proxima::narrow::cells {

// Every convex shape meets a half-space through the generic routine of generic_halfspace.hpp.
template <class A, class B>
inline constexpr bool kHalfSpaceCovered =
    !(std::is_same_v<A, HalfSpace> || std::is_same_v<B, HalfSpace>) || kAnalyticPair<A, B>;

template <class A, class B>
DistanceResult cell_distance_direct(const void* a, const Transform& pose_a, const void* b, const Transform& pose_b,
                                    const PairRequest& request, PairCache* cache, Real /*cutoff*/ = Real(0)) {
  static_assert(kHalfSpaceCovered<A, B>, "a convex shape without its half-space pair (shape_halfspace.cpp)");
  return pair_distance(*static_cast<const A*>(a), pose_a, *static_cast<const B*>(b), pose_b, request, cache);
}

template <class A, class B>
bool cell_intersect_direct(const void* a, const Transform& pose_a, const void* b, const Transform& pose_b,
                           const PairRequest& request, PairCache* cache) {
  return pair_intersect(*static_cast<const A*>(a), pose_a, *static_cast<const B*>(b), pose_b, request, cache);
}

template <class A, class B>
ContactManifold cell_collide_direct(const void* a, const Transform& pose_a, const void* b, const Transform& pose_b,
                                    const PairRequest& request, PairCache* cache) {
  return pair_collide(*static_cast<const A*>(a), pose_a, *static_cast<const B*>(b), pose_b, request, cache);
}

// Mirrored cells: (A, B) with A after B runs the cell (B, A) of row B and swaps.
template <class A, class B>
bool cell_intersect_mirrored(const void* a, const Transform& pose_a, const void* b, const Transform& pose_b,
                             const PairRequest& request, PairCache* cache) {
  return cell_of<B, A>().intersect(b, pose_b, a, pose_a, request, cache);
}

template <class A, class B>
DistanceResult cell_distance_mirrored(const void* a, const Transform& pose_a, const void* b, const Transform& pose_b,
                                      const PairRequest& request, PairCache* cache, Real cutoff) {
  return mirrored(cell_of<B, A>().distance(b, pose_b, a, pose_a, request, cache, cutoff));
}

template <class A, class B>
ContactManifold cell_collide_mirrored(const void* a, const Transform& pose_a, const void* b, const Transform& pose_b,
                                      const PairRequest& request, PairCache* cache) {
  return mirrored(cell_of<B, A>().collide(b, pose_b, a, pose_a, request, cache));
}

/// The points of the convex pair's manifold, given to the collector.
template <class A, class B>
void cell_collide_all_convex(const void* a, const Transform& pose_a, const void* b, const Transform& pose_b,
                             const PairRequest& request, ContactCollector& collector) {
  ContactManifold m;
  if constexpr (kShapeTypeOf<A> <= kShapeTypeOf<B>)
    m = cell_collide_direct<A, B>(a, pose_a, b, pose_b, request, nullptr);
  else
    m = cell_collide_mirrored<A, B>(a, pose_a, b, pose_b, request, nullptr);
  for (int i = 0; i < m.count && !collector.done(); ++i) collector.add(m.points[static_cast<std::size_t>(i)]);
}

template <class A, class B>
constexpr PairFunctions convex_cell() {
  if constexpr (kShapeTypeOf<A> <= kShapeTypeOf<B>) {
    return PairFunctions{&cell_intersect_direct<A, B>,   &cell_distance_direct<A, B>, &cell_collide_direct<A, B>,
                         &cell_collide_all_convex<A, B>, kAnalyticPair<A, B>,         false};
  } else {
    return PairFunctions{&cell_intersect_mirrored<A, B>, &cell_distance_mirrored<A, B>, &cell_collide_mirrored<A, B>,
                         &cell_collide_all_convex<A, B>, kAnalyticPair<B, A>,           true};
  }
}

// Composite cells. The routine for (A, B) with A the compound, or A the mesh against a
// convex B; the mirrored cells swap the arguments.

template <class A, class B>
bool composite_intersect(const A& a, const Transform& pa, const B& b, const Transform& pb, const PairRequest& r,
                         PartHint* hint) {
  if constexpr (std::is_same_v<A, Compound>)
    return compound_intersect(a, pa, b, pb, r, hint);
  else if constexpr (std::is_same_v<B, TriangleMesh>)
    return mesh_mesh_intersect(a, pa, b, pb, r, MeshMeshNodes::Oriented, hint);
  else
    return mesh_convex_intersect(a, pa, b, pb, r, hint);
}

template <class A, class B>
DistanceResult composite_distance(const A& a, const Transform& pa, const B& b, const Transform& pb,
                                  const PairRequest& r, Real cutoff, PartHint* hint) {
  if constexpr (std::is_same_v<A, Compound>)
    return compound_distance(a, pa, b, pb, r, cutoff, hint);
  else if constexpr (std::is_same_v<B, TriangleMesh>)
    return mesh_mesh_distance(a, pa, b, pb, r, MeshMeshNodes::Oriented, hint);
  else
    return mesh_convex_distance(a, pa, b, pb, r, cutoff, hint);
}

template <class A, class B>
void composite_collide_all(const A& a, const Transform& pa, const B& b, const Transform& pb, const PairRequest& r,
                           ContactCollector& collector) {
  if constexpr (std::is_same_v<A, Compound>)
    compound_collide_all(a, pa, b, pb, r, collector);
  else if constexpr (std::is_same_v<B, TriangleMesh>)
    mesh_mesh_collide_all(a, pa, b, pb, r, collector);
  else
    mesh_convex_collide_all(a, pa, b, pb, r, collector);
}

/// Whether the composite routine for (A, B) runs as written (else as (B, A), mirrored): a
/// compound side goes first, then a mesh side.
template <class A, class B>
inline constexpr bool kCompositeDirect = std::is_same_v<A, Compound> ||
                                         (std::is_same_v<A, TriangleMesh> && !std::is_same_v<B, Compound>);

template <class A, class B>
struct CompositeCell {
  static const A& sa(const void* p) { return *static_cast<const A*>(p); }
  static const B& sb(const void* p) { return *static_cast<const B*>(p); }

  /// Runs `query(hint)` with the cache's part hint in the routine's order (none without a
  /// cache) and stores the hint back.
  template <class Query>
  static auto with_hint(PairCache* cache, Query&& query) {
    constexpr bool swap = !kCompositeDirect<A, B>;
    if (cache == nullptr) return query(nullptr);
    PartHint hint = load_hint(*cache, swap);
    auto answer = query(&hint);
    store_hint(*cache, hint, swap);
    return answer;
  }
  /// The request with the pair's tolerance resolved once for every part.
  static PairRequest resolved(const void* a, const Transform& pa, const void* b, const Transform& pb,
                              const PairRequest& r) {
    return composite_request(ShapeRef(sa(a)), pa, ShapeRef(sb(b)), pb, r);
  }
  static bool intersect(const void* a, const Transform& pa, const void* b, const Transform& pb,
                        const PairRequest& request, PairCache* cache) {
    if (!poses_in_range(pa, pb)) return false;
    const PairRequest r = resolved(a, pa, b, pb, request);
    return with_hint(cache, [&](PartHint* hint) {
      if constexpr (kCompositeDirect<A, B>)
        return composite_intersect(sa(a), pa, sb(b), pb, r, hint);
      else
        return composite_intersect(sb(b), pb, sa(a), pa, r, hint);
    });
  }
  static DistanceResult distance(const void* a, const Transform& pa, const void* b, const Transform& pb,
                                 const PairRequest& request, PairCache* cache, Real cutoff) {
    if (!poses_in_range(pa, pb)) return invalid_distance();
    const PairRequest r = resolved(a, pa, b, pb, request);
    return with_hint(cache, [&](PartHint* hint) {
      if constexpr (kCompositeDirect<A, B>)
        return composite_distance(sa(a), pa, sb(b), pb, r, cutoff, hint);
      else
        return mirrored(composite_distance(sb(b), pb, sa(a), pa, r, cutoff, hint));
    });
  }
  static ContactManifold collide(const void* a, const Transform& pa, const void* b, const Transform& pb,
                                 const PairRequest& request, PairCache* /*cache*/) {
    if (!poses_in_range(pa, pb)) return invalid_manifold();
    return reduced_manifold(sa(a), pa, sb(b), pb, resolved(a, pa, b, pb, request));
  }
  static void collide_all(const void* a, const Transform& pa, const void* b, const Transform& pb,
                          const PairRequest& request, ContactCollector& collector) {
    if (!poses_in_range(pa, pb)) return;
    const PairRequest r = resolved(a, pa, b, pb, request);
    if constexpr (kCompositeDirect<A, B>) {
      composite_collide_all(sa(a), pa, sb(b), pb, r, collector);
    } else {
      MirroredCollector swapped(collector);
      composite_collide_all(sb(b), pb, sa(a), pa, r, swapped);
    }
  }
};

/// The cell for the ordered pair (A, B).
template <class A, class B>
struct Cell {
  static constexpr PairFunctions entry() {
    if constexpr (is_convex(kShapeTypeOf<A>) && is_convex(kShapeTypeOf<B>)) {
      return convex_cell<A, B>();
    } else {
      using C = CompositeCell<A, B>;
      return PairFunctions{&C::intersect, &C::distance, &C::collide, &C::collide_all, false, !kCompositeDirect<A, B>};
    }
  }
};

/// Row A of the dispatch table.
template <class A>
constexpr std::array<PairFunctions, Shapes3::size> row() {
  return make_pair_row<Shapes3, Cell, PairFunctions, A>();
}

}  // namespace proxima::narrow::cells
