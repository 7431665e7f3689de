// Sphere against box (Ericson, Real-Time Collision Detection, 5.1.3 and 5.2.5).
//
// Steps:
//  1. the sphere centre c in the box frame, clamped to the box: q;
//  2. c outside: normal = (q - c) / |q - c| (A to B, turned to world), signed distance
//     |q - c| - r;
//  3. c inside (or on the surface): the deepest face, the one nearest to c (ties go to x, then
//     y, then z; the + face when the coordinate is 0): normal = -(face normal), signed
//     distance -(h_i - |c_i|) - r, box witness c projected on that face;
//  4. sphere witness c + r normal.
// Manifold: that single point; feature id: the box vertex, edge or face holding q. intersect
// compares the squared distance of the centre to the box with (contact reach + r)^2, and asks
// pair_distance when rounding could decide (decide_contact_squared).
#include "narrowphase/pairs_rounded.hpp"
#include "narrowphase/rounded_common.hpp"

namespace proxima::narrow {

namespace {

struct SphereBox {
  DistanceResult result;
  std::uint32_t feature = 0;
};

SphereBox sphere_box(const Sphere& a, const Transform& pose_a, const Box& b, const Transform& pose_b,
                     const PairRequest& request) {
  const Vec3& h = b.half_extents();
  const Vec3 c = pose_b.inverse_apply(pose_a.position);
  Vec3 q = glm::clamp(c, -h, h);
  Vec3 n_local;
  Real core = Real(0);
  if (!unit_and_length(q - c, n_local, core)) {
    // Inside: the face nearest to c.
    int axis = 0;
    Real best = h.x - std::abs(c.x);
    for (int i = 1; i < 3; ++i) {
      const Real depth = h[i] - std::abs(c[i]);
      if (depth < best) {
        best = depth;
        axis = i;
      }
    }
    const Real side = c[axis] >= Real(0) ? Real(1) : Real(-1);
    q = c;
    q[axis] = side * h[axis];
    n_local = Vec3(Real(0));
    n_local[axis] = -side;
    core = -best;
  }
  SphereBox sb;
  FeatureKind kind{};
  detail::box_feature(q, h, kind, sb.feature);
  sb.feature = make_feature_id(FeatureKind::Surface, 0, kind, sb.feature);
  const Real tol = resolve_tolerance(request, detail::pair_scale(pose_a, pose_b, a.radius() + max_abs_component(h)));
  const Vec3 n = pose_b.apply_vector(n_local);
  sb.result = detail::rounded_result(pose_a.position, pose_b.apply(q), n, core, a.radius(), Real(0), tol);
  return sb;
}

}  // namespace

DistanceResult pair_distance(const Sphere& a, const Transform& pose_a, const Box& b, const Transform& pose_b,
                             const PairRequest& request, PairCache* /*cache*/) {
  if (!poses_in_range(pose_a, pose_b)) return invalid_distance();
  return sphere_box(a, pose_a, b, pose_b, request).result;
}

bool pair_intersect(const Sphere& a, const Transform& pose_a, const Box& b, const Transform& pose_b,
                    const PairRequest& request, PairCache* /*cache*/) {
  if (!poses_in_range(pose_a, pose_b)) return false;
  // Squared distance of the centre to the solid box (box frame) against (contact reach +
  // r)^2; a centre inside is at depth r + (distance to the nearest face) >= r: a hit.
  const Vec3& h = b.half_extents();
  const Vec3 c = pose_b.inverse_apply(pose_a.position);
  const Vec3 e = c - glm::clamp(c, -h, h);
  const Real d2 = length_squared(e);
  if (!(d2 > Real(0))) return true;
  const Real tol = resolve_tolerance(request, detail::pair_scale(pose_a, pose_b, a.radius() + max_abs_component(h)));
  return decide_contact_squared(d2, a.radius(), contact_reach(request.contact_distance, tol), Real(0.25) * tol, [&] {
    return in_contact(pair_distance(a, pose_a, b, pose_b, request, nullptr), request);
  });
}

ContactManifold pair_collide(const Sphere& a, const Transform& pose_a, const Box& b, const Transform& pose_b,
                             const PairRequest& request, PairCache* /*cache*/) {
  if (!poses_in_range(pose_a, pose_b)) return invalid_manifold();
  const SphereBox sb = sphere_box(a, pose_a, b, pose_b, request);
  return manifold_from_distance(sb.result, request, sb.feature);
}

}  // namespace proxima::narrow
