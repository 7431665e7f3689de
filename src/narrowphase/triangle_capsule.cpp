// Triangle (two-sided, no thickness) against capsule (Ericson, Real-Time Collision Detection,
// 5.1.10 and 5.2.1).
//
// Steps (in the triangle's frame):
//  1. the capsule's core segment p0p1; its closest points to the triangle
//     (geometry::closest_points_segment_triangle);
//  2. core apart: normal = (on_segment - on_triangle) / distance (A to B), signed distance =
//     distance - r;
//  3. core touching the triangle (within the tolerance, where the direction of on_segment -
//     on_triangle is rounding noise): separating-axis test over the face normals of the
//     Minkowski difference of segment and triangle: the triangle normal N, d x e_k and the
//     in-plane edge normals N x e_k (the normal wins ties within tolerance); the minimum
//     overlap is the exact core penetration; witnesses: the closest points of the triangle and
//     of the core moved out along the normal by the overlap (they touch there), the core's
//     point moved back;
//  4. manifold: when the normal is within kFaceCosine of +-N, the core is clipped to the
//     triangle's prism (its three side planes); each clipped end whose gap (height over the
//     plane minus r) is within contact_distance + tolerance is a contact with normal +-N. Two
//     distinct ends give the two-point manifold of a capsule lying along the triangle;
//     otherwise the single closest pair.
#include <proxima/geometry/closest_points.hpp>

#include "narrowphase/pairs_rounded.hpp"
#include "narrowphase/rounded_common.hpp"

namespace proxima::narrow {

namespace {

/// A normal within this cosine of the triangle normal gives the clipped two-point manifold.
constexpr Real kFaceCosine = Real(0.999);

struct TriangleCapsule {
  DistanceResult result;
  Vec3 p0, p1;  ///< core ends, triangle frame
  Real tolerance = Real(0);
  std::uint32_t feature = 0;
};

TriangleCapsule triangle_capsule(const Triangle& a, const Transform& pose_a, const Capsule& b, const Transform& pose_b,
                                 const PairRequest& request) {
  TriangleCapsule tc;
  tc.p0 = pose_a.inverse_apply(pose_b.apply(b.bottom()));
  tc.p1 = pose_a.inverse_apply(pose_b.apply(b.top()));
  const Real size = geometry::detail::magnitude({a.a(), a.b(), a.c()});
  tc.tolerance = resolve_tolerance(request, detail::pair_scale(pose_a, pose_b, size + b.radius() + b.half_length()));
  const geometry::ClosestPair cp = geometry::closest_points_segment_triangle(tc.p0, tc.p1, a.a(), a.b(), a.c());
  Vec3 n;
  Real core = Real(0);
  Vec3 on_tri = cp.on_b;
  Vec3 on_seg = cp.on_a;
  if (!(unit_and_length(cp.on_a - cp.on_b, n, core) && core > tc.tolerance)) {
    // The core touches the triangle: SAT over the faces of the Minkowski difference.
    const Vec3 d = tc.p1 - tc.p0;
    const Vec3& nt = a.normal();
    const Vec3 e[3] = {a.b() - a.a(), a.c() - a.b(), a.a() - a.c()};
    const Real ld = glm::length(d);
    Real best = std::numeric_limits<Real>::infinity();
    Vec3 axis = nt;
    const auto consider = [&](const Vec3& u, Real bias) {
      const Real ta = glm::dot(u, a.a());
      const Real tb = glm::dot(u, a.b());
      const Real tcv = glm::dot(u, a.c());
      const Real tmin = std::min({ta, tb, tcv});
      const Real tmax = std::max({ta, tb, tcv});
      const Real s0 = glm::dot(u, tc.p0);
      const Real s1 = glm::dot(u, tc.p1);
      const Real up = tmax - std::min(s0, s1);    // push the capsule along +u
      const Real down = std::max(s0, s1) - tmin;  // push it along -u
      const Real overlap = std::min(up, down);
      if (overlap < best - bias) {
        best = overlap;
        axis = up <= down ? u : -u;
      }
    };
    consider(nt, Real(0));
    for (const Vec3& ek : e) {
      Vec3 u;
      Real lc = Real(0);
      if (unit_and_length(glm::cross(d, ek), u, lc) && lc > kSqrtEpsilon * ld * glm::length(ek)) {
        consider(u, tc.tolerance);
      }
      if (unit_and_length(glm::cross(nt, ek), u, lc)) consider(u, tc.tolerance);
    }
    n = axis;
    core = -best;
    // Witnesses: move the core out along n by the overlap; it then touches the triangle, and
    // the closest points of the moved core are the contact.
    const Vec3 shift = -core * n;
    const geometry::ClosestPair touch =
        geometry::closest_points_segment_triangle(tc.p0 + shift, tc.p1 + shift, a.a(), a.b(), a.c());
    on_seg = touch.on_a - shift;
    on_tri = touch.on_b;
  }
  tc.result = detail::rounded_result(pose_a.apply(on_tri), pose_a.apply(on_seg), pose_a.apply_vector(n), core, Real(0),
                                     b.radius(), tc.tolerance);
  FeatureKind kb{};
  std::uint32_t ib = 0;
  const Vec3 dd = tc.p1 - tc.p0;
  const Real l2 = length_squared(dd);
  const Real t = l2 > Real(0) ? glm::dot(on_seg - tc.p0, dd) / l2 : Real(0);
  detail::capsule_feature(t, kb, ib);
  FeatureKind ka{};
  std::uint32_t ia = 0;
  detail::triangle_feature(geometry::closest_point_triangle(on_tri, a.a(), a.b(), a.c()).feature, ka, ia);
  tc.feature = make_feature_id(ka, ia, kb, ib);
  return tc;
}

}  // namespace

DistanceResult pair_distance(const Triangle& a, const Transform& pose_a, const Capsule& b, const Transform& pose_b,
                             const PairRequest& request, PairCache* /*cache*/) {
  if (!poses_in_range(pose_a, pose_b)) return invalid_distance();
  return triangle_capsule(a, pose_a, b, pose_b, request).result;
}

bool pair_intersect(const Triangle& a, const Transform& pose_a, const Capsule& b, const Transform& pose_b,
                    const PairRequest& request, PairCache* cache) {
  if (!poses_in_range(pose_a, pose_b)) return false;
  return in_contact(pair_distance(a, pose_a, b, pose_b, request, cache), request);
}

ContactManifold pair_collide(const Triangle& a, const Transform& pose_a, const Capsule& b, const Transform& pose_b,
                             const PairRequest& request, PairCache* /*cache*/) {
  if (!poses_in_range(pose_a, pose_b)) return invalid_manifold();
  const TriangleCapsule tc = triangle_capsule(a, pose_a, b, pose_b, request);
  ContactManifold m = manifold_from_distance(tc.result, request, tc.feature);
  if (m.count == 0 || request.max_contacts < 2) return m;

  const Vec3& nt = a.normal();
  const Real cosine = glm::dot(pose_a.inverse_apply_vector(tc.result.normal), nt);
  if (!(std::abs(cosine) >= kFaceCosine)) return m;
  const Real side = cosine > Real(0) ? Real(1) : Real(-1);
  const Vec3 v[3] = {a.a(), a.b(), a.c()};
  Real t0 = Real(0);
  Real t1 = Real(1);
  int clipped_by[2] = {-1, -1};
  for (int k = 0; k < 3; ++k) {
    const Vec3& p = v[k];
    const Vec3& q = v[(k + 1) % 3];
    const Vec3 m_edge = glm::cross(q - p, nt);  // outward in the plane
    const Real old0 = t0;
    const Real old1 = t1;
    if (!detail::clip_segment(tc.p0, tc.p1, m_edge, glm::dot(m_edge, p), t0, t1)) return m;
    if (t0 != old0) clipped_by[0] = k;
    if (t1 != old1) clipped_by[1] = k;
  }
  const Vec3 d = tc.p1 - tc.p0;
  if (!((t1 - t0) * glm::length(d) > tc.tolerance)) return m;
  const Vec3 normal = pose_a.apply_vector(side * nt);
  ContactManifold two;
  two.normal = normal;
  two.status = tc.result.status;
  two.method = tc.result.method;
  for (int k = 0; k < 2; ++k) {
    const Real t = k == 0 ? t0 : t1;
    const Vec3 p = tc.p0 + t * d;
    const Real height = side * glm::dot(nt, p - a.a());
    const Real gap = height - b.radius();
    if (!(gap <= request.contact_distance + tc.tolerance)) continue;
    ContactPoint& c = two.points[static_cast<std::size_t>(two.count++)];
    c.point_a = pose_a.apply(p - (side * height) * nt);
    c.point_b = c.point_a + gap * normal;
    c.normal = normal;
    c.depth = -gap;
    const int by = clipped_by[k];
    c.feature_id = by < 0 ? make_feature_id(FeatureKind::Face, 0, FeatureKind::Vertex, static_cast<std::uint32_t>(k))
                          : make_feature_id(FeatureKind::Face, 0, FeatureKind::Edge, static_cast<std::uint32_t>(by));
  }
  if (two.count < 2) return m;
  if (two.points[1].depth > two.points[0].depth) std::swap(two.points[0], two.points[1]);
  // The pair's deepest point must be among them (else the closest points lie elsewhere, e.g.
  // near an edge): otherwise keep the exact single point.
  if (two.points[0].depth < -tc.result.signed_distance - tc.tolerance) return m;
  return two;
}

}  // namespace proxima::narrow
