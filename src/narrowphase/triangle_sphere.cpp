// Triangle (two-sided, no thickness) against sphere (Ericson, Real-Time Collision Detection,
// 5.1.5 and 5.2.7).
//
// Steps (in the triangle's frame):
//  1. the sphere centre c; the closest point q of the triangle to it (Voronoi regions);
//  2. normal = (c - q) / |c - q| (A to B), signed distance |c - q| - r (exact also when the
//     sphere overlaps: the triangle is convex, so the depth is r - |c - q|); c - q comes
//     from the closest feature's geometry (feature_offset: height over the plane along the
//     unit normal, plus the offset beyond an edge along its in-plane normal), not from the
//     difference of the nearby points c and q, whose rounding tilts a short offset;
//  3. a centre on the triangle (to rounding, offset_noise, where the direction of c - q is
//     noise) takes the triangle's normal (b - a) x (c - a) turned to the centre's side
//     (+normal when exactly in the plane), depth r.
// Manifold: that single point; feature id: triangle vertex / edge / face against the sphere
// surface.
#include <proxima/geometry/closest_points.hpp>

#include "narrowphase/pairs_rounded.hpp"
#include "narrowphase/rounded_common.hpp"

namespace proxima::narrow {

namespace {

/// c minus its closest point on the triangle, from the closest feature's own geometry rather
/// than from the difference of the nearby points c and q (whose rounding would tilt a short
/// offset): over the face, the height over the plane times the unit normal; beyond an edge,
/// that plus the distance beyond the edge's line in the plane times the edge's outward
/// in-plane normal; at a vertex, c minus the vertex (exact input points).
Vec3 feature_offset(const Triangle& t, geometry::TriangleFeature f, const Vec3& c, const Vec3& q) {
  const Vec3& n = t.normal();
  int edge = -1;
  switch (f) {
    case geometry::TriangleFeature::VertexA: return c - t.a();
    case geometry::TriangleFeature::VertexB: return c - t.b();
    case geometry::TriangleFeature::VertexC: return c - t.c();
    case geometry::TriangleFeature::Face: return glm::dot(c - t.a(), n) * n;
    case geometry::TriangleFeature::EdgeAB: edge = 0; break;
    case geometry::TriangleFeature::EdgeBC: edge = 1; break;
    case geometry::TriangleFeature::EdgeCA: edge = 2; break;
  }
  if (edge < 0) return c - q;
  const Vec3& p0 = t.vertex(edge);
  const Vec3& p1 = t.vertex((edge + 1) % 3);
  Vec3 m;
  Real lm = Real(0);
  if (!unit_and_length(glm::cross(p1 - p0, n), m, lm)) return c - q;
  const Vec3 w = c - p0;
  return glm::dot(w, n) * n + std::max(glm::dot(w, m), Real(0)) * m;
}

struct TriangleSphere {
  DistanceResult result;
  std::uint32_t feature = 0;
};

TriangleSphere triangle_sphere(const Triangle& a, const Transform& pose_a, const Sphere& b, const Transform& pose_b,
                               const PairRequest& request) {
  const Vec3 c = pose_a.inverse_apply(pose_b.position);
  const geometry::TrianglePoint q = geometry::closest_point_triangle(c, a.a(), a.b(), a.c());
  const Real size = geometry::detail::magnitude({a.a(), a.b(), a.c()});
  const Real scale = detail::pair_scale(pose_a, pose_b, size + b.radius());
  const Real tol = resolve_tolerance(request, scale);
  Real length = Real(0);
  const Vec3 offset = feature_offset(a, q.feature, c, q.point);
  Vec3 n = detail::unit_or(offset, a.normal(), length);
  const Vec3 on_triangle = c - offset;
  if (!(length > detail::offset_noise(scale))) {
    // Centre on the triangle (to rounding): the normal, turned to the centre's side.
    n = glm::dot(c - a.a(), a.normal()) < Real(0) ? -a.normal() : a.normal();
    length = Real(0);
  }
  TriangleSphere ts;
  ts.result = detail::rounded_result(pose_a.apply(on_triangle), pose_b.position, pose_a.apply_vector(n), length,
                                     Real(0), b.radius(), tol);
  FeatureKind kind{};
  std::uint32_t index = 0;
  detail::triangle_feature(q.feature, kind, index);
  ts.feature = make_feature_id(kind, index, FeatureKind::Surface, 0);
  return ts;
}

}  // namespace

DistanceResult pair_distance(const Triangle& a, const Transform& pose_a, const Sphere& b, const Transform& pose_b,
                             const PairRequest& request, PairCache* /*cache*/) {
  if (!poses_in_range(pose_a, pose_b)) return invalid_distance();
  return triangle_sphere(a, pose_a, b, pose_b, request).result;
}

bool pair_intersect(const Triangle& a, const Transform& pose_a, const Sphere& b, const Transform& pose_b,
                    const PairRequest& request, PairCache* cache) {
  if (!poses_in_range(pose_a, pose_b)) return false;
  return in_contact(pair_distance(a, pose_a, b, pose_b, request, cache), request);
}

ContactManifold pair_collide(const Triangle& a, const Transform& pose_a, const Sphere& b, const Transform& pose_b,
                             const PairRequest& request, PairCache* /*cache*/) {
  if (!poses_in_range(pose_a, pose_b)) return invalid_manifold();
  const TriangleSphere ts = triangle_sphere(a, pose_a, b, pose_b, request);
  return manifold_from_distance(ts.result, request, ts.feature);
}

}  // namespace proxima::narrow
