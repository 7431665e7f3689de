// Triangle (two-sided, no thickness) against sphere (Ericson, Real-Time Collision Detection,
// 5.1.5 and 5.2.7).
//
// Steps (in the triangle's frame):
//  1. the sphere centre c; the closest point q of the triangle to it (Voronoi regions);
//  2. normal = (c - q) / |c - q| (A to B), signed distance |c - q| - r (exact also when the
//     sphere overlaps: the triangle is convex, so the depth is r - |c - q|);
//  3. a centre on the triangle (within the pair's tolerance, where the direction of c - q is
//     rounding noise) takes the triangle's normal (b - a) x (c - a) turned to the centre's side
//     (+normal when exactly in the plane), depth r.
// Manifold: that single point; feature id: triangle vertex / edge / face against the sphere
// surface.
#include <proxima/geometry/closest_points.hpp>

#include "narrowphase/pairs_rounded.hpp"
#include "narrowphase/rounded_common.hpp"

namespace proxima::narrow {

namespace {

struct TriangleSphere {
  DistanceResult result;
  std::uint32_t feature = 0;
};

TriangleSphere triangle_sphere(const Triangle& a, const Transform& pose_a, const Sphere& b, const Transform& pose_b,
                               const PairRequest& request) {
  const Vec3 c = pose_a.inverse_apply(pose_b.position);
  const geometry::TrianglePoint q = geometry::closest_point_triangle(c, a.a(), a.b(), a.c());
  const Real size = geometry::detail::magnitude({a.a(), a.b(), a.c()});
  const Real tol = resolve_tolerance(request, detail::pair_scale(pose_a, pose_b, size + b.radius()));
  Real length = Real(0);
  Vec3 n = detail::unit_or(c - q.point, a.normal(), length);
  if (!(length > tol)) {
    // Centre on the triangle (within tolerance): the normal, turned to the centre's side.
    n = glm::dot(c - a.a(), a.normal()) < Real(0) ? -a.normal() : a.normal();
    length = Real(0);
  }
  TriangleSphere ts;
  ts.result = detail::rounded_result(pose_a.apply(q.point), pose_b.position, pose_a.apply_vector(n), length, Real(0),
                                     b.radius(), tol);
  FeatureKind kind{};
  std::uint32_t index = 0;
  detail::triangle_feature(q.feature, kind, index);
  ts.feature = make_feature_id(kind, index, FeatureKind::Surface, 0);
  return ts;
}

}  // namespace

DistanceResult pair_distance(const Triangle& a, const Transform& pose_a, const Sphere& b, const Transform& pose_b,
                             const PairRequest& request, PairCache* /*cache*/) {
  if (!finite_poses(pose_a, pose_b)) return invalid_distance();
  return triangle_sphere(a, pose_a, b, pose_b, request).result;
}

bool pair_intersect(const Triangle& a, const Transform& pose_a, const Sphere& b, const Transform& pose_b,
                    const PairRequest& request, PairCache* cache) {
  if (!finite_poses(pose_a, pose_b)) return false;
  return pair_distance(a, pose_a, b, pose_b, request, cache).signed_distance <= request.contact_distance;
}

ContactManifold pair_collide(const Triangle& a, const Transform& pose_a, const Sphere& b, const Transform& pose_b,
                             const PairRequest& request, PairCache* /*cache*/) {
  if (!finite_poses(pose_a, pose_b)) return invalid_manifold();
  const TriangleSphere ts = triangle_sphere(a, pose_a, b, pose_b, request);
  return manifold_from_distance(ts.result, request, ts.feature);
}

}  // namespace proxima::narrow
