// Capsule against capsule (Ericson, Real-Time Collision Detection, 4.5.1 and 5.1.9).
//
// Steps:
//  1. both core segments in world; their closest points (geometry::closest_points_segment_
//     segment, robust for parallel and zero-length segments);
//  2. cores apart: normal = (on_b - on_a) / |on_b - on_a|, signed distance = |on_b - on_a| -
//     both radii;
//  3. cores crossing (apart by at most the tolerance, where the direction of on_b - on_a is
//     rounding noise): the Minkowski difference of two segments is flat, so the exact
//     penetration of the capsules is ra + rb along the common normal dA x dB (turned towards
//     B's centre); parallel or zero-length cores take A's local +x axis (B's when A is a
//     point), turned the same way;
//  4. manifold: when both cores have length and are parallel within kParallelSine, the
//     overlap of B's projection on A's axis gives two points (its ends), each kept when its gap
//     is within contact_distance + tolerance; else the single closest pair.
#include <proxima/geometry/closest_points.hpp>

#include "narrowphase/pairs_rounded.hpp"
#include "narrowphase/rounded_common.hpp"

namespace proxima::narrow {

namespace {

/// Axes within this sine of parallel give a two-point manifold.
constexpr Real kParallelSine = Real(0.02);

struct CapsuleCapsule {
  DistanceResult result;
  Vec3 a0, a1, b0, b1;
  Real s = Real(0);
  Real t = Real(0);
  Real tolerance = Real(0);
};

CapsuleCapsule capsule_capsule(const Capsule& a, const Transform& pose_a, const Capsule& b, const Transform& pose_b,
                               const PairRequest& request) {
  CapsuleCapsule cc;
  cc.a0 = pose_a.apply(a.bottom());
  cc.a1 = pose_a.apply(a.top());
  cc.b0 = pose_b.apply(b.bottom());
  cc.b1 = pose_b.apply(b.top());
  cc.tolerance = resolve_tolerance(
      request, detail::pair_scale(pose_a, pose_b, a.radius() + b.radius() + a.half_length() + b.half_length()));
  const geometry::SegmentPair sp = geometry::closest_points_segment_segment(cc.a0, cc.a1, cc.b0, cc.b1);
  cc.s = sp.s;
  cc.t = sp.t;
  Vec3 n;
  Real length = Real(0);
  if (!(unit_and_length(sp.on_b - sp.on_a, n, length) && length > cc.tolerance)) {
    length = Real(0);
    const Vec3 da = cc.a1 - cc.a0;
    const Vec3 db = cc.b1 - cc.b0;
    const Vec3 c = glm::cross(da, db);
    Real lc = Real(0);
    const Real la = glm::length(da);
    const Real lb = glm::length(db);
    if (!(unit_and_length(c, n, lc) && lc > kSqrtEpsilon * la * lb)) {
      n = pose_a.apply_vector(Vec3(Real(1), Real(0), Real(0)));
      if (!(la > Real(0)) && lb > Real(0)) n = pose_b.apply_vector(Vec3(Real(1), Real(0), Real(0)));
    }
    if (glm::dot(n, pose_b.position - pose_a.position) < Real(0)) n = -n;
  }
  cc.result = detail::rounded_result(sp.on_a, sp.on_b, n, length, a.radius(), b.radius(), cc.tolerance);
  return cc;
}

}  // namespace

DistanceResult pair_distance(const Capsule& a, const Transform& pose_a, const Capsule& b, const Transform& pose_b,
                             const PairRequest& request, PairCache* /*cache*/) {
  if (!finite_poses(pose_a, pose_b)) return invalid_distance();
  return capsule_capsule(a, pose_a, b, pose_b, request).result;
}

bool pair_intersect(const Capsule& a, const Transform& pose_a, const Capsule& b, const Transform& pose_b,
                    const PairRequest& request, PairCache* cache) {
  if (!finite_poses(pose_a, pose_b)) return false;
  return pair_distance(a, pose_a, b, pose_b, request, cache).signed_distance <= request.contact_distance;
}

ContactManifold pair_collide(const Capsule& a, const Transform& pose_a, const Capsule& b, const Transform& pose_b,
                             const PairRequest& request, PairCache* /*cache*/) {
  if (!finite_poses(pose_a, pose_b)) return invalid_manifold();
  const CapsuleCapsule cc = capsule_capsule(a, pose_a, b, pose_b, request);
  const DistanceResult& d = cc.result;
  FeatureKind ka{};
  FeatureKind kb{};
  std::uint32_t ia = 0;
  std::uint32_t ib = 0;
  detail::capsule_feature(cc.s, ka, ia);
  detail::capsule_feature(cc.t, kb, ib);
  ContactManifold m = manifold_from_distance(d, request, make_feature_id(ka, ia, kb, ib));
  if (m.count == 0 || request.max_contacts < 2) return m;

  // Parallel cores: the ends of the overlap of B's projection on A's axis.
  Vec3 ua;
  Vec3 ub;
  Real la = Real(0);
  Real lb = Real(0);
  if (!unit_and_length(cc.a1 - cc.a0, ua, la) || !unit_and_length(cc.b1 - cc.b0, ub, lb)) return m;
  if (!(length_squared(glm::cross(ua, ub)) <= kParallelSine * kParallelSine)) return m;
  const Real s0 = glm::dot(cc.b0 - cc.a0, ua);
  const Real s1 = glm::dot(cc.b1 - cc.a0, ua);
  const bool b0_low = s0 <= s1;
  const Real lo = std::max(Real(0), std::min(s0, s1));
  const Real hi = std::min(la, std::max(s0, s1));
  if (!(hi - lo > cc.tolerance)) return m;

  const Vec3 n = d.normal;
  const Real rab = a.radius() + b.radius();
  ContactManifold two;
  two.normal = n;
  two.status = d.status;
  two.method = d.method;
  for (int k = 0; k < 2; ++k) {
    const Real s = k == 0 ? lo : hi;
    const Vec3 pa = cc.a0 + s * ua;
    const Vec3 pb = geometry::closest_point_segment(pa, cc.b0, cc.b1).point;
    const Real gap = glm::dot(pb - pa, n) - rab;
    if (!(gap <= request.contact_distance + cc.tolerance)) continue;
    // The overlap end comes from A's end (vertex 0 / 1) or from B's end (vertex j).
    const bool from_a = k == 0 ? lo == Real(0) : hi == la;
    const std::uint32_t b_end = (k == 0) == b0_low ? 0u : 1u;
    const std::uint32_t id =
        from_a ? make_feature_id(FeatureKind::Vertex, static_cast<std::uint32_t>(k), FeatureKind::Edge, 0)
               : make_feature_id(FeatureKind::Edge, 0, FeatureKind::Vertex, b_end);
    ContactPoint& c = two.points[static_cast<std::size_t>(two.count++)];
    c.point_a = pa + a.radius() * n;
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
  return two;
}

}  // namespace proxima::narrow
