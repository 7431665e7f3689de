#pragma once
/// @file broadphase.hpp
/// The broad phase's shared vocabulary: proxy ids, kinds, filters, pairs, the status of an
/// update, statistics, the query callbacks, and the `BroadPhaseStructure` concept that every
/// structure (brute force, sweep-and-prune, grid, hash, octree, kd-tree, BSP, dynamic AABB
/// tree) satisfies, so code templated on it runs on any of them with no virtual call.
///
/// Semantics shared by every structure (the differential tests hold them to it):
/// - A proxy is a closed AABB in world coordinates with a caller-chosen id (dense small
///   integers work best: structures index arrays by id), a kind and a filter.
/// - Two proxies form a pair when their boxes overlap or touch (closed intervals on all three
///   axes), at least one of them is Moving, and their filters accept each other.
/// - find_pairs reports every pair exactly once as (lo, hi) with lo < hi, sorted by (lo, hi):
///   the order is deterministic and independent of insertion history and executor.
/// - A rejected call (non-finite or inverted box, unknown or duplicate id) changes nothing.
/// - Queries are const member templates on the callback (any callable satisfying
///   OverlapCallback or RayCallback, called directly: no type erasure per reported proxy)
///   and return their counters by value; they change nothing, so concurrent queries on one
///   structure are safe while nothing modifies it. stats() holds the last find_pairs' counters.
/// - Parallel pair finding is an optional overload `find_pairs(out, executor)` (Executor,
///   core/executor.hpp; the structures start no threads of their own) whose output is
///   identical to the serial one for every executor and thread count; structures offering it
///   satisfy ParallelBroadPhase (any_broadphase.hpp), and parallel_pairs.hpp has a helper
///   (parallel_pair_chunks: per-chunk outputs concatenated, then sort_pairs).
/// Shared pieces: pair_tracker.hpp (sort_pairs radix sort, begun/ended deltas), brute_force.hpp
/// (the reference), broadphase_queries.hpp (members stated once), detail/ (query helpers),
/// any_broadphase.hpp (type erasure: the one place where callbacks are type-erased;
/// make_broadphase by name).

#include <proxima/core/function_ref.hpp>
#include <proxima/geometry/aabb.hpp>
#include <proxima/geometry/ray.hpp>

#include <concepts>
#include <cstdint>
#include <span>
#include <type_traits>
#include <vector>

namespace proxima {

/// Caller-chosen identifier of a proxy (structures size their tables by the largest id).
using ProxyId = std::uint32_t;

/// Whether a proxy moves. Static-static pairs are never reported.
enum class ProxyKind : std::uint8_t {
  Static,  ///< rarely updated (level geometry); never paired with another Static proxy
  Moving,  ///< updated every frame
};

/// Collision filter: two proxies may pair when each one's layer bits meet the other's mask.
struct ProxyFilter {
  std::uint32_t layer = 1;   ///< bits this proxy belongs to
  std::uint32_t mask = ~0u;  ///< bits this proxy collides with

  /// True when a and b accept each other.
  friend constexpr bool can_pair(const ProxyFilter& a, const ProxyFilter& b) {
    return (a.layer & b.mask) != 0 && (b.layer & a.mask) != 0;
  }
};

/// A reported pair, lo < hi.
struct ProxyPair {
  ProxyId lo = 0;
  ProxyId hi = 0;
  friend constexpr bool operator==(const ProxyPair&, const ProxyPair&) = default;
  friend constexpr auto operator<=>(const ProxyPair&, const ProxyPair&) = default;
};

/// One entry of a batch update: the new box of an existing proxy.
struct ProxyUpdate {
  ProxyId id = 0;
  Aabb box;
};

/// Outcome of insert / remove / update. Anything but Ok leaves the structure unchanged.
enum class BroadPhaseStatus : std::uint8_t {
  Ok,
  NotFinite,    ///< a coordinate of the box is NaN or infinite
  InvalidBox,   ///< min > max on some axis, or |coordinate| > kMaxCoordinate
  UnknownId,    ///< no proxy with this id
  DuplicateId,  ///< insert of an id already present
};

/// Short name ("ok", "not_finite", ...).
const char* to_string(BroadPhaseStatus status);

/// Validates a box for insertion or update (finite, min <= max, within kMaxCoordinate).
BroadPhaseStatus check_box(const Aabb& box);

/// Counters of a find_pairs or query call, for tests and benchmarks (stats() keeps those of
/// the last find_pairs; each query returns its own).
struct BroadPhaseStats {
  std::uint64_t nodes_visited = 0;  ///< tree nodes, cells or sweep steps visited
  std::uint64_t pairs_tested = 0;   ///< box-box overlap tests run
  std::uint64_t pairs_found = 0;    ///< pairs reported
};

/// Pairs begun and ended between two successive find_pairs results (both sorted).
struct PairDelta {
  std::vector<ProxyPair> begun;  ///< in the new set, not in the old; sorted
  std::vector<ProxyPair> ended;  ///< in the old set, not in the new; sorted
};

/// A ray-query callback: called as on_ray(id, t) for a proxy whose box the ray enters at
/// fraction t (in units of the ray's direction length, t <= the current max fraction); it
/// returns the new max fraction: t' < current clips the ray, 0 stops the query, a negative
/// value ignores the proxy.
template <class F>
concept RayCallback = std::is_invocable_r_v<Real, F&, ProxyId, Real>;
/// An overlap-query callback (box or point): called as on_overlap(id); false stops the query.
template <class F>
concept OverlapCallback = std::is_invocable_r_v<bool, F&, ProxyId>;

/// Type-erased RayCallback (non-owning FunctionRef): AnyBroadPhase's virtual interface only.
using RayQueryCallback = FunctionRef<Real(ProxyId id, Real t)>;
/// Type-erased OverlapCallback (non-owning FunctionRef): AnyBroadPhase's virtual interface only.
using OverlapQueryCallback = FunctionRef<bool(ProxyId id)>;

/// What every broad-phase structure offers. Queries (templates on the callback; checked here
/// with the type-erased callbacks) report each matching proxy once, in no particular order,
/// and return their counters; find_pairs clears `out` and fills it sorted (file comment).
template <class T>
concept BroadPhaseStructure = requires(T& s, const T& cs, ProxyId id, const Aabb& box, ProxyKind kind,
                                       ProxyFilter filter, std::span<const ProxyUpdate> updates,
                                       std::vector<ProxyPair>& out, const Ray& ray, Real max_t, const Vec3& point,
                                       const RayQueryCallback& on_ray, const OverlapQueryCallback& on_overlap) {
  { s.insert(id, box, kind, filter) } -> std::same_as<BroadPhaseStatus>;
  { s.remove(id) } -> std::same_as<BroadPhaseStatus>;
  { s.update(id, box) } -> std::same_as<BroadPhaseStatus>;
  { s.update(updates) } -> std::same_as<BroadPhaseStatus>;  // all or nothing
  { s.rebuild() } -> std::same_as<void>;
  { s.find_pairs(out) } -> std::same_as<void>;
  { cs.query_aabb(box, on_overlap) } -> std::same_as<BroadPhaseStats>;
  { cs.query_point(point, on_overlap) } -> std::same_as<BroadPhaseStats>;
  { cs.query_ray(ray, max_t, on_ray) } -> std::same_as<BroadPhaseStats>;
  { cs.validate() } -> std::same_as<bool>;
  { cs.stats() } -> std::same_as<BroadPhaseStats>;
  { cs.size() } -> std::same_as<std::size_t>;
};

}  // namespace proxima
