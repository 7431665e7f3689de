#pragma once
/// @file halfspace_common.hpp
/// Private building blocks of the half-space pairs (pairs_halfspace.hpp): the world plane of
/// a half-space, the support-point distance of any shape to it, and the manifold of a few
/// candidate points (vertices, core ends, rim points) below the plane.

#include <proxima/core/math.hpp>
#include <proxima/core/transform.hpp>
#include <proxima/shapes/halfspace.hpp>

#include <algorithm>
#include <array>
#include <limits>

#include "manifold_reduction.hpp"
#include "pair_support.hpp"

namespace proxima::narrow::detail {

/// A half-space's boundary in the world frame: gap(x) = n . (x - origin) - offset, the signed
/// distance of a world point x above the plane (> 0 outside the solid).
struct WorldPlane {
  Vec3 n{Real(0), Real(0), Real(1)};  ///< unit outward normal, world frame
  Vec3 origin{Real(0)};               ///< the half-space's frame origin, world frame
  Real offset = Real(0);              ///< plane offset relative to origin

  /// Signed height of x above the plane (length units).
  Real gap(const Vec3& x) const { return glm::dot(n, x - origin) - offset; }
};

/// The world plane of half-space h placed at pose.
inline WorldPlane world_plane(const HalfSpace& h, const Transform& pose) {
  return {pose.apply_vector(h.normal()), pose.position, h.offset()};
}

/// Tolerance of a shape-halfspace pair: positions, the plane offset and the shape's size.
inline Real halfspace_tolerance(const PairRequest& request, const Transform& pose_a, const Transform& pose_b,
                                const HalfSpace& b, Real size) {
  return resolve_tolerance(request, std::max({max_abs_component(pose_a.position), max_abs_component(pose_b.position),
                                              std::abs(b.offset()), size}));
}

/// Distance result of a point x of A's core with radius r against the plane: normal -n (A to
/// B), point_a = x - r n, point_b its projection on the plane.
inline DistanceResult halfspace_result(const WorldPlane& plane, const Vec3& x, Real r, Real tolerance) {
  DistanceResult d;
  d.signed_distance = plane.gap(x) - r;
  d.normal = -plane.n;
  d.point_a = x - r * plane.n;
  d.point_b = d.point_a - d.signed_distance * plane.n;
  d.status = status_from_distance(d.signed_distance, tolerance);
  d.method = PairMethod::Analytic;
  return d;
}

/// Distance of any shape with core_support / core_radius to the half-space: the core's
/// support point in the direction -n plus the radius. O(cost of one support query).
template <class Shape>
DistanceResult halfspace_distance(const Shape& a, const Transform& pose_a, const HalfSpace& b, const Transform& pose_b,
                                  Real tolerance) {
  const WorldPlane plane = world_plane(b, pose_b);
  const Vec3 x = pose_a.apply(a.core_support(pose_a.inverse_apply_vector(-plane.n)));
  return halfspace_result(plane, x, a.core_radius(), tolerance);
}

/// Up to 8 candidate contact points of A's core (world frame) with their feature indices.
struct Candidates {
  std::array<Vec3, 8> points{};
  std::array<std::uint32_t, 8> index{};
  int count = 0;

  /// Appends a point with its feature index on A.
  void add(const Vec3& p, std::uint32_t i) {
    points[static_cast<std::size_t>(count)] = p;
    index[static_cast<std::size_t>(count)] = i;
    ++count;
  }
};

/// Manifold of candidate points (A's core, radius r) against the plane, with `d` the pair's
/// distance result (its normal and status). Empty when d's gap exceeds contact_distance;
/// else every candidate whose gap is within contact_distance + tolerance, the 4 deepest when
/// more, reduced to max_contacts by select_contacts. Deepest first. Feature ids (Vertex, index,
/// Face, 0).
inline ContactManifold candidate_manifold(const WorldPlane& plane, const Candidates& c, Real r, const DistanceResult& d,
                                          const PairRequest& request, Real tolerance) {
  ContactManifold m;
  m.normal = d.normal;
  m.status = d.status;
  m.method = d.method;
  if (!(d.signed_distance <= request.contact_distance) || request.max_contacts < 1) return m;
  // Gaps, and the kept candidates ordered deepest first (insertion sort, at most 8).
  std::array<Real, 8> gap{};
  std::array<int, 8> order{};
  int kept = 0;
  const Real limit = request.contact_distance + tolerance;
  for (int i = 0; i < c.count; ++i) {
    const Real g = plane.gap(c.points[static_cast<std::size_t>(i)]) - r;
    gap[static_cast<std::size_t>(i)] = g;
    if (!(g <= limit)) continue;
    int j = kept++;
    for (; j > 0 && gap[static_cast<std::size_t>(order[static_cast<std::size_t>(j - 1)])] > g; --j) {
      order[static_cast<std::size_t>(j)] = order[static_cast<std::size_t>(j - 1)];
    }
    order[static_cast<std::size_t>(j)] = i;
  }
  if (kept == 0) return manifold_from_distance(d, request);  // rounding: the support point only
  kept = std::min(kept, kMaxContactPoints);
  std::array<ContactPoint, 8> all{};
  for (int k = 0; k < kept; ++k) {
    const int i = order[static_cast<std::size_t>(k)];
    ContactPoint& p = all[static_cast<std::size_t>(k)];
    p.point_a = c.points[static_cast<std::size_t>(i)] - r * plane.n;
    p.point_b = p.point_a - gap[static_cast<std::size_t>(i)] * plane.n;
    p.normal = d.normal;
    p.depth = -gap[static_cast<std::size_t>(i)];
    p.feature_id = make_feature_id(FeatureKind::Vertex, c.index[static_cast<std::size_t>(i)], FeatureKind::Face, 0);
  }
  if (kept <= request.max_contacts) {
    std::copy(all.begin(), all.begin() + kept, m.points.begin());
    m.count = kept;
    return m;
  }
  m.count = reduce_contacts(std::span<const ContactPoint>(all.data(), static_cast<std::size_t>(kept)), d.normal,
                            request.max_contacts, m.points);
  return m;
}

}  // namespace proxima::narrow::detail
