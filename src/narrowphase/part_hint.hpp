#pragma once
/// @file part_hint.hpp
/// Internal: the warm start of a composite pair (a compound or mesh side). The PairCache
/// keeps the parts (top-level compound child, mesh triangle) that answered the pair's last
/// query; the composite routines try that pair of parts first:
///   - intersect: a hit on the remembered parts answers at once, without a descent;
///   - distance: the remembered parts' distance becomes the bound of the branch and bound
///     from the start, so the descent prunes most nodes at once (a pair that moved little
///     has the same closest parts).
/// An index out of range (a cache used with another pair) is ignored. The answers equal the
/// cold ones (intersect exactly; distance up to the rounding of the part's own routine when
/// two parts tie).

#include <proxima/core/sub_shape_id.hpp>
#include <proxima/narrowphase/contact.hpp>

#include <cstdint>

namespace proxima::narrow {

/// The parts of A and B to try first (kNoIndex: none), updated with the parts that answer.
struct PartHint {
  std::uint32_t a = kNoIndex;  ///< A's compound child or mesh triangle
  std::uint32_t b = kNoIndex;  ///< B's compound child or mesh triangle
};

/// The hint stored in `cache` for the routine that runs the pair as (A, B) (`swap`: the
/// routine runs it as (B, A)).
inline PartHint load_hint(const PairCache& cache, bool swap) {
  return swap ? PartHint{cache.part_b, cache.part_a} : PartHint{cache.part_a, cache.part_b};
}

/// Writes the routine's hint back into `cache` (see load_hint).
inline void store_hint(PairCache& cache, const PartHint& hint, bool swap) {
  cache.part_a = swap ? hint.b : hint.a;
  cache.part_b = swap ? hint.a : hint.b;
}

}  // namespace proxima::narrow
