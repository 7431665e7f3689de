#pragma once
/// @file broadphase_queries.hpp
/// BroadPhaseQueries<Derived>: the CRTP base that states once the members every tree and
/// cell structure offers alike (the serial find_pairs, the box query over the structure's
/// box walk, the point query as the box query of the point, the last find_pairs' counters).
/// Everything is resolved at compile time: no virtual call, no type erasure.

#include <proxima/broadphase/broadphase.hpp>
#include <proxima/broadphase/detail/query_support.hpp>
#include <proxima/core/executor.hpp>

#include <vector>

namespace proxima {

/// CRTP base of a broad-phase structure `Derived` (BroadPhaseStructure, broadphase.hpp).
/// `Derived` derives publicly from BroadPhaseQueries<Derived>, befriends it when the members
/// below are private, and provides:
/// - `void find_pairs(std::vector<ProxyPair>& out, Executor& executor)`, with
///   `using BroadPhaseQueries<Derived>::find_pairs;` so that the serial form stays visible;
/// - `BroadPhaseStats stats_`: the counters of its last find_pairs;
/// - for the box query below, `template <class Visit> void visit_box(const Aabb& box,
///   BroadPhaseStats& st, Visit&& visit) const`, its box walk: calls `visit(id)` for every
///   proxy whose box overlaps `box` (closed), counts nodes_visited and pairs_tested in `st`,
///   and stops when `visit` returns false. A structure whose box query works otherwise
///   declares its own query_aabb, which hides this one (query_point then uses it).
template <class Derived>
class BroadPhaseQueries {
 public:
  /// Every pair (see broadphase.hpp), sorted; `out` is cleared first. Runs
  /// find_pairs(out, serial_executor()) on the calling thread.
  void find_pairs(std::vector<ProxyPair>& out) { self().find_pairs(out, serial_executor()); }

  /// Calls `on_overlap` for every proxy whose box overlaps `box` (world frame, closed); stops
  /// when it returns false. A non-finite, inverted or too large box (check_box) reports
  /// nothing. Returns the query's counters.
  template <OverlapCallback OnOverlap>
  BroadPhaseStats query_aabb(const Aabb& box, OnOverlap&& on_overlap) const {
    BroadPhaseStats st;
    if (check_box(box) != BroadPhaseStatus::Ok) return st;
    self().visit_box(box, st, [&](ProxyId id) {
      ++st.pairs_found;
      return on_overlap(id);
    });
    return st;
  }
  /// Calls `on_overlap` for every proxy whose box contains `point` (world frame, boundary
  /// included): the box query of the point's box. Returns the query's counters.
  template <OverlapCallback OnOverlap>
  BroadPhaseStats query_point(const Vec3& point, OnOverlap&& on_overlap) const {
    return self().query_aabb(Aabb::from_point(point), on_overlap);
  }
  /// Counters of the last find_pairs.
  BroadPhaseStats stats() const { return self().stats_; }

 protected:
  BroadPhaseQueries() = default;

 private:
  Derived& self() { return static_cast<Derived&>(*this); }
  const Derived& self() const { return static_cast<const Derived&>(*this); }
};

}  // namespace proxima
