#pragma once
/// @file core_segment_pair.hpp
/// Private building block of the capsule-capsule and segment-segment routines: two segment
/// cores with radii (0 for a segment), their closest points, the contact normal in the
/// degenerate cases and the two-point manifold of parallel overlapping cores.
///
/// Steps (Ericson, Real-Time Collision Detection, 5.1.9):
///  1. closest points of the two segments (geometry::closest_points_segment_segment, robust
///     for parallel and zero-length segments);
///  2. apart beyond rounding (offset_noise): the offset from A's closest point to B's from
///     the cores' geometry (core_offset: the common normal dA x dB when both points are
///     inside the cores, exactly across a core when one is), its length the core distance;
///  3. touching or crossing (where the direction of on_b - on_a is rounding noise): the
///     Minkowski difference of two segments is flat, so the exact core penetration is 0 along
///     the common normal dA x dB; parallel (collinear or coplanar) or zero-length cores take a
///     direction orthogonal to A's core (B's when A has no length): the fallback axis with
///     its component along the core removed, or a perpendicular from orthonormal_basis when
///     the fallback lies along the core; the normal is turned towards B's centre;
///  4. manifold: both cores with length and parallel within kParallelSine: the ends of the
///     overlap of B's projection on A's axis, each kept when its gap is within the contact
///     reach (contact.hpp); else the single closest pair.

#include <proxima/core/math.hpp>
#include <proxima/geometry/closest_points.hpp>

#include <algorithm>
#include <utility>

#include "pair_support.hpp"
#include "rounded_common.hpp"

namespace proxima::narrow::detail {

/// Axes within this sine of parallel give a two-point manifold.
inline constexpr Real kCoreParallelSine = Real(0.02);

/// Two segment cores in world and their closest pair.
struct CoreSegmentPair {
  DistanceResult result;  ///< distance of the rounded cores
  Vec3 a0, a1, b0, b1;    ///< core ends, world
  Real s = Real(0);       ///< parameter of the closest point on A's core
  Real t = Real(0);       ///< parameter of the closest point on B's core
  Real tolerance = Real(0);
};

/// A unit direction orthogonal to the (non-zero) core direction d: `fallback` (unit) with its
/// component along d removed, or a perpendicular of d when the fallback lies along it.
inline Vec3 orthogonal_to_core(const Vec3& d, const Vec3& fallback) {
  Vec3 u;
  Real l = Real(0);
  if (!unit_and_length(d, u, l)) return fallback;
  Vec3 n;
  Real ln = Real(0);
  if (unit_and_length(fallback - glm::dot(fallback, u) * u, n, ln) && ln > Real(0.1)) return n;
  Vec3 t2;
  orthonormal_basis(u, n, t2);
  return n;
}

/// The offset from A's closest point to B's, from the cores' geometry rather than from the
/// difference of the two rounded points alone (whose direction, over a short offset, tilts
/// by their rounding over its length): both points inside their cores, the common normal
/// dA x dB with the offset's length along it, where the directions give it more precisely
/// (the sine of their angle times the longer core exceeds the offset); one inside, the
/// offset taken exactly across that core (across_direction); else the difference (two
/// ends: the gap is smooth in the direction there).
inline Vec3 core_offset(const Vec3& da, const Vec3& db, const geometry::SegmentPair& sp) {
  const Vec3 d = sp.on_b - sp.on_a;
  const bool inside_a = sp.s > Real(0) && sp.s < Real(1);
  const bool inside_b = sp.t > Real(0) && sp.t < Real(1);
  if (inside_a && inside_b) {
    // Squared: sine^2 la^2 lb^2 = |c|^2 against epsilon and against |d|^2 max(la^2, lb^2).
    const Vec3 c = glm::cross(da, db);
    const Real cc = glm::dot(c, c);
    const Real la2 = glm::dot(da, da);
    const Real lb2 = glm::dot(db, db);
    if (cc > kEpsilon * la2 * lb2 && cc > glm::dot(d, d) * std::max(la2, lb2)) return (glm::dot(c, d) / cc) * c;
    return across_direction(d, la2 >= lb2 ? da : db);
  }
  if (inside_a) return across_direction(d, da);
  if (inside_b) return across_direction(d, db);
  return d;
}

/// Closest pair of cores a0a1 (radius ra) and b0b1 (radius rb), all in world. When the
/// closest points coincide and the cores are parallel or zero-length, a normal orthogonal to
/// the cores is derived from A's or B's local +x axis in the world (rotated only then, by
/// `rotation_a`, `rotation_b`); B's centre minus A's (`towards`) orients it. Always inlined:
/// called out of line, it costs the capsule pairs about 100 instructions a query (measured
/// with callgrind on W7), more than its own work.
[[gnu::always_inline]] inline CoreSegmentPair core_segment_pair(const Vec3& a0, const Vec3& a1, const Vec3& b0,
                                                                const Vec3& b1, Real ra, Real rb,
                                                                const Quat& rotation_a, const Quat& rotation_b,
                                                                const Vec3& towards, Real tolerance) {
  CoreSegmentPair cc;
  cc.a0 = a0;
  cc.a1 = a1;
  cc.b0 = b0;
  cc.b1 = b1;
  cc.tolerance = tolerance;
  const geometry::SegmentPair sp = geometry::closest_points_segment_segment(a0, a1, b0, b1);
  cc.s = sp.s;
  cc.t = sp.t;
  const Vec3 da = a1 - a0;
  const Vec3 db = b1 - b0;
  Vec3 n;
  Real length = Real(0);
  // Beyond the tolerance the offset is far above the rounding; within it, its length is
  // compared with the coordinates' rounding (the ends' magnitudes, found only then).
  const bool apart =
      unit_and_length(core_offset(da, db, sp), n, length) &&
      (length > tolerance || length > offset_noise(std::max(std::max(max_abs_component(a0), max_abs_component(a1)),
                                                            std::max(max_abs_component(b0), max_abs_component(b1)))));
  if (!apart) {
    length = Real(0);
    const Vec3 c = glm::cross(da, db);
    Real lc = Real(0);
    const Real la = glm::length(da);
    const Real lb = glm::length(db);
    if (!(unit_and_length(c, n, lc) && lc > kSqrtEpsilon * la * lb)) {
      const Vec3 x(Real(1), Real(0), Real(0));
      if (la > Real(0)) {
        n = orthogonal_to_core(da, rotation_a * x);
      } else if (lb > Real(0)) {
        n = orthogonal_to_core(db, rotation_b * x);
      } else {
        n = rotation_a * x;
      }
    }
    if (glm::dot(n, towards) < Real(0)) n = -n;
  }
  cc.result = rounded_result(sp.on_a, sp.on_b, n, length, ra, rb, tolerance);
  return cc;
}

/// Whether two cores (radii ra, rb) are in contact under the touching rule (contact.hpp):
/// the squared core distance against (contact reach + radii)^2, `exact()` (in_contact of the
/// pair's distance) where rounding could decide, so intersect agrees with distance.
template <class Exact>
bool core_segments_within(const Vec3& a0, const Vec3& a1, const Vec3& b0, const Vec3& b1, Real ra, Real rb,
                          Real contact_distance, Real tolerance, Exact&& exact) {
  const geometry::SegmentPair sp = geometry::closest_points_segment_segment(a0, a1, b0, b1);
  if (sp.distance_squared <= tolerance * tolerance) return true;  // touching cores (core_segment_pair)
  return decide_contact_squared(sp.distance_squared, ra + rb, contact_reach(contact_distance, tolerance),
                                Real(0.25) * tolerance, exact);
}

/// Manifold of two cores from their closest pair: two points (the ends of the overlap of the
/// cores) when both have length and are parallel within kCoreParallelSine and both ends are
/// within the contact distance and the deeper one is as deep as the pair (within the
/// tolerance); else the single
/// closest pair. Feature ids: vertex 0 / 1 for the core ends (a0 / a1, b0 / b1), edge 0 for
/// the core's inside.
inline ContactManifold core_segment_manifold(const CoreSegmentPair& cc, Real ra, Real rb, const PairRequest& request) {
  const DistanceResult& d = cc.result;
  FeatureKind ka{};
  FeatureKind kb{};
  std::uint32_t ia = 0;
  std::uint32_t ib = 0;
  capsule_feature(cc.s, ka, ia);
  capsule_feature(cc.t, kb, ib);
  ContactManifold m = manifold_from_distance(d, request, make_feature_id(ka, ia, kb, ib));
  if (m.count == 0 || request.max_contacts < 2) return m;

  // Parallel cores: the ends of the overlap of B's projection on A's axis.
  Vec3 ua;
  Vec3 ub;
  Real la = Real(0);
  Real lb = Real(0);
  if (!unit_and_length(cc.a1 - cc.a0, ua, la) || !unit_and_length(cc.b1 - cc.b0, ub, lb)) return m;
  if (!(length_squared(glm::cross(ua, ub)) <= kCoreParallelSine * kCoreParallelSine)) return m;
  const Real s0 = glm::dot(cc.b0 - cc.a0, ua);
  const Real s1 = glm::dot(cc.b1 - cc.a0, ua);
  const bool b0_low = s0 <= s1;
  const Real lo = std::max(Real(0), std::min(s0, s1));
  const Real hi = std::min(la, std::max(s0, s1));
  if (!(hi - lo > cc.tolerance)) return m;

  const Vec3 n = d.normal;
  const Real rab = ra + rb;
  ContactManifold two;
  two.normal = n;
  two.status = d.status;
  two.method = d.method;
  for (int k = 0; k < 2; ++k) {
    const Real s = k == 0 ? lo : hi;
    const Vec3 pa = cc.a0 + s * ua;
    const Vec3 pb = geometry::closest_point_segment(pa, cc.b0, cc.b1).point;
    const Real gap = glm::dot(pb - pa, n) - rab;
    if (!(gap <= contact_reach(request.contact_distance, cc.tolerance))) continue;
    // The overlap end comes from A's end (vertex 0 / 1) or from B's end (vertex j).
    const bool from_a = k == 0 ? lo == Real(0) : hi == la;
    const std::uint32_t b_end = (k == 0) == b0_low ? 0u : 1u;
    const std::uint32_t id =
        from_a ? make_feature_id(FeatureKind::Vertex, static_cast<std::uint32_t>(k), FeatureKind::Edge, 0)
               : make_feature_id(FeatureKind::Edge, 0, FeatureKind::Vertex, b_end);
    ContactPoint& c = two.points[static_cast<std::size_t>(two.count++)];
    c.point_a = pa + ra * n;
    c.point_b = c.point_a + gap * n;
    c.normal = n;
    c.depth = -gap;
    c.feature_id = id;
  }
  if (two.count < 2) return m;  // one end only: the exact closest pair is the better point
  if (two.points[1].depth > two.points[0].depth) std::swap(two.points[0], two.points[1]);
  // The pair's deepest point must be among them (else the closest points lie elsewhere, e.g.
  // near an edge): otherwise keep the exact single point.
  if (two.points[0].depth < -d.signed_distance - cc.tolerance) return m;
  if (two.points[0].depth > -d.signed_distance + cc.tolerance) return m;
  return two;
}

}  // namespace proxima::narrow::detail
