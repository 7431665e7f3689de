#pragma once
/// @file pair_support.hpp
/// Private helpers shared by every pair routine of the narrow phase: tolerance resolution,
/// the defined answer for non-finite poses, and the one-point manifold of a distance result.
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

/// True when both poses are finite (rotation and position).
inline bool finite_poses(const Transform& pose_a, const Transform& pose_b) {
  const auto finite = [](const Transform& t) {
    return std::isfinite(t.position.x) && std::isfinite(t.position.y) && std::isfinite(t.position.z) &&
           std::isfinite(t.rotation.w) && std::isfinite(t.rotation.x) && std::isfinite(t.rotation.y) &&
           std::isfinite(t.rotation.z);
  };
  return finite(pose_a) && finite(pose_b);
}

/// The defined answer for non-finite poses: separated by +infinity, status InvalidInput.
inline DistanceResult invalid_distance() {
  DistanceResult r;
  r.signed_distance = std::numeric_limits<Real>::infinity();
  r.status = PairStatus::InvalidInput;
  return r;
}

/// The defined answer for non-finite poses: no contact, status InvalidInput.
inline ContactManifold invalid_manifold() {
  ContactManifold m;
  m.status = PairStatus::InvalidInput;
  return m;
}

/// A one-point manifold from a distance result: empty when the gap exceeds
/// request.contact_distance, else the two witnesses with depth = -signed_distance.
inline ContactManifold manifold_from_distance(const DistanceResult& d, const PairRequest& request,
                                              std::uint32_t feature_id = 0) {
  ContactManifold m;
  m.normal = d.normal;
  m.status = d.status;
  m.method = d.method;
  if (!(d.signed_distance <= request.contact_distance) || request.max_contacts < 1) return m;
  m.count = 1;
  m.points[0] = ContactPoint{d.point_a, d.point_b, d.normal, -d.signed_distance, feature_id};
  return m;
}

}  // namespace proxima::narrow

namespace proxima::narrow {

/// True for the pairs (A, B) served by a closed-form routine; each pair header specialises it
/// next to the pair's declarations. The dispatch table sends every other pair to the generic
/// GJK / EPA / SAT routines.
template <class A, class B>
inline constexpr bool kAnalyticPair = false;

}  // namespace proxima::narrow
