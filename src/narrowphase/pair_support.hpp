#pragma once
/// @file pair_support.hpp
/// Private helpers shared by every pair routine of the narrow phase: tolerance resolution,
/// the defined answer for poses out of range, and the one-point manifold of a distance result.
///
/// Contract of a pair routine (one header per group of pairs, declared in namespace
/// proxima::narrow, defined in one .cpp per pair): for each pair (A, B) it serves, with A
/// not after B in ShapeType order, it provides all three of
///   bool            pair_intersect(const A&, const Transform&, const B&, const Transform&,
///                                  const PairRequest&, PairCache*);
///   DistanceResult  pair_distance (same parameters);
///   ContactManifold pair_collide  (same parameters);
/// The dispatch table (dispatch.cpp) picks these non-template overloads over the generic
/// templates (GJK/EPA/SAT) and mirrors them for the (B, A) cell.

#include <proxima/core/tolerance.hpp>
#include <proxima/core/transform.hpp>
#include <proxima/narrowphase/contact.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace proxima::narrow {

/// The absolute tolerance to use: the request's when set, else linear_tolerance(scale), where
/// scale is the size of the pair (largest extent or coordinate involved).
inline Real resolve_tolerance(const PairRequest& request, Real scale) {
  return request.tolerance > Real(0) ? request.tolerance : linear_tolerance(scale);
}

/// True when both poses lie in the stated range: finite rotations, positions finite and
/// within kMaxPlacedCoordinate (core/tolerance.hpp), where every answer is right.
inline bool poses_in_range(const Transform& pose_a, const Transform& pose_b) {
  // islessequal: quiet on NaN (an ordered comparison would raise the invalid flag).
  const auto in_range = [](const Transform& t) {
    const auto near = [](Real x) { return std::islessequal(std::abs(x), kMaxPlacedCoordinate); };
    return near(t.position.x) && near(t.position.y) && near(t.position.z) && std::isfinite(t.rotation.w) &&
           std::isfinite(t.rotation.x) && std::isfinite(t.rotation.y) && std::isfinite(t.rotation.z);
  };
  return in_range(pose_a) && in_range(pose_b);
}

/// The defined answer for poses out of range: separated by +infinity, status InvalidInput.
inline DistanceResult invalid_distance() {
  DistanceResult r;
  r.signed_distance = std::numeric_limits<Real>::infinity();
  r.status = PairStatus::InvalidInput;
  return r;
}

/// The defined answer for poses out of range: no contact, status InvalidInput.
inline ContactManifold invalid_manifold() {
  ContactManifold m;
  m.status = PairStatus::InvalidInput;
  return m;
}

/// Separated polytopes: the closest points' offset `d` (A to B) or that offset taken across
/// one of the `edges` directions, whichever the shapes are farther apart along by `gap`
/// (gap(unit direction) -> the gap along it, a lower bound of the distance), replaces
/// `normal` and `distance` when it beats them (the caller starts them at the SAT's axis and
/// separation). Any direction's gap bounds the distance from below, so the largest is the
/// best; across an edge the direction is exact where a vertex meets the edge's inside.
template <class GapFn, class Edges>
void widest_gap_direction(const Vec3& d, const Edges& edges, GapFn gap, Vec3& normal, Real& distance) {
  const auto consider = [&](const Vec3& direction) {
    Vec3 unit;
    Real len = Real(0);
    if (!unit_and_length(direction, unit, len)) return;
    const Real g = gap(unit);
    if (g > distance) {
      distance = g;
      normal = unit;
    }
  };
  consider(d);
  for (const Vec3& e : edges) consider(across_direction(d, e));
}

/// A one-point manifold from a distance result: empty when the pair is not in contact
/// (in_contact: the gap exceeds max(request.contact_distance, d.tolerance)), else the two
/// witnesses with depth = -signed_distance.
inline ContactManifold manifold_from_distance(const DistanceResult& d, const PairRequest& request,
                                              std::uint32_t feature_id = 0) {
  ContactManifold m;
  m.normal = d.normal;
  m.status = d.status;
  m.method = d.method;
  if (!in_contact(d, request) || request.max_contacts < 1) return m;
  m.count = 1;
  m.points[0] = ContactPoint{d.point_a, d.point_b, d.normal, -d.signed_distance, feature_id};
  return m;
}

/// The request with its contact distance raised to the pair's reach (contact_reach of the
/// request and `tolerance`): what clipping and point filters compare gaps with, so that a
/// touching pair keeps its contacts.
inline PairRequest request_within_reach(const PairRequest& request, Real tolerance) {
  PairRequest r = request;
  r.contact_distance = contact_reach(request.contact_distance, tolerance);
  return r;
}

/// The contact reach of a request whose tolerance is set (a composite query sets it once for
/// all its parts): max(contact_distance, tolerance).
inline Real request_reach(const PairRequest& request) {
  return contact_reach(request.contact_distance, request.tolerance);
}

/// How far a composite query inflates boxes to find the parts that may be in contact: twice
/// the reach, so that rounding of the boxes never drops a part within the reach.
inline Real cull_margin(const PairRequest& request) { return Real(2) * request_reach(request); }

/// intersect's decision (the touching rule of contact.hpp) from a cheap estimate: `core_d2`
/// the squared distance of the cores, `radii` their radii, `reach` the contact reach, and
/// `error` a bound on how far the estimate's gap may differ from pair_distance's signed
/// distance (rounding). Conclusive outside that band; inside it `exact()` (the pair's
/// in_contact of pair_distance) decides, so intersect and distance always agree.
template <class Exact>
bool decide_contact_squared(Real core_d2, Real radii, Real reach, Real error, Exact&& exact) {
  const Real hi = radii + reach + error;
  if (!(core_d2 <= hi * hi)) return false;
  const Real lo = radii + reach - error;
  if (lo > Real(0) && core_d2 < lo * lo) return true;
  return exact();
}

/// The same decision from an estimate `gap` of the signed distance (see
/// decide_contact_squared).
template <class Exact>
bool decide_contact(Real gap, Real reach, Real error, Exact&& exact) {
  if (gap > reach + error) return false;
  if (gap < reach - error) return true;
  return exact();
}

}  // namespace proxima::narrow

namespace proxima::narrow {

/// True for the pairs (A, B) served by a closed-form routine; each pair header specialises it
/// next to the pair's declarations. The dispatch table sends every other pair to the generic
/// GJK / EPA / SAT routines.
template <class A, class B>
inline constexpr bool kAnalyticPair = false;

}  // namespace proxima::narrow

/// Declares the three routines of the closed-form pair (A, B) under the contract above and
/// marks it analytic (kAnalyticPair); used inside namespace proxima::narrow by the group
/// headers, one line per pair.
#define PROXIMA_ANALYTIC_PAIR(A, B)                                                                      \
  bool pair_intersect(const A& a, const Transform& pose_a, const B& b, const Transform& pose_b,          \
                      const PairRequest& request, PairCache* cache);                                     \
  DistanceResult pair_distance(const A& a, const Transform& pose_a, const B& b, const Transform& pose_b, \
                               const PairRequest& request, PairCache* cache);                            \
  ContactManifold pair_collide(const A& a, const Transform& pose_a, const B& b, const Transform& pose_b, \
                               const PairRequest& request, PairCache* cache);                            \
  template <>                                                                                            \
  inline constexpr bool kAnalyticPair<A, B> = true;
