// Triangle-triangle: separating axes, exact distance and clipped manifold (two-sided
// triangles without thickness).
//
// Steps (Ericson, Real-Time Collision Detection 5.2.1 and 4.4; Gregorius' SAT):
//  1. SAT over both normals, the in-plane edge normals of both (which separate coplanar
//     pairs) and the 9 edge-pair cross products (small_polytope_sat.hpp); the largest
//     separation <= 0 is minus the exact penetration depth.
//  2. Separated: the exact closest points (geometry::closest_points_triangle_triangle).
//  3. Witnesses of a penetration: the closest points of A and of B moved out by the depth
//     along the normal (they touch there; polytope_pair_common.hpp), right for face,
//     edge-edge and in-plane axes alike.
//  4. Manifold: supporting faces (the triangles) along the normal, clipped, reduced to 4
//     points.
#include <proxima/geometry/closest_points.hpp>

#include <cmath>

#include "pairs_polyhedral.hpp"
#include "polytope_pair_common.hpp"
#include "small_polytope_sat.hpp"

namespace proxima::narrow {
namespace {

const Real kParallelSine = Real(4) * kSqrtEpsilon;

void triangle_polytope(const Triangle& t, const Transform& pose, SmallPolytope& p) {
  p.vertex_count = 3;
  for (int i = 0; i < 3; ++i) p.vertices[i] = pose.apply(t.vertex(i));
  const Vec3 n = pose.apply_vector(t.normal());
  p.face_count = 4;
  p.faces[0] = n;
  p.edge_count = 3;
  for (int i = 0; i < 3; ++i) {
    p.edges[i] = p.vertices[(i + 1) % 3] - p.vertices[i];
    p.faces[1 + i] = glm::cross(n, p.edges[i]);
  }
}

}  // namespace

DistanceResult pair_distance(const Triangle& a, const Transform& pose_a, const Triangle& b, const Transform& pose_b,
                             const PairRequest& request, PairCache* cache) {
  if (!finite_poses(pose_a, pose_b)) return invalid_distance();
  SmallPolytope pa;
  SmallPolytope pb;
  triangle_polytope(a, pose_a, pa);
  triangle_polytope(b, pose_b, pb);
  const SmallSat s = small_polytope_sat(pa, pb, nullptr, 0, kParallelSine);
  Real scale = Real(0);
  for (int i = 0; i < 3; ++i) {
    scale = std::max({scale, max_abs_component(pa.vertices[i]), max_abs_component(pb.vertices[i])});
  }
  const Real tol = resolve_tolerance(request, scale);
  DistanceResult r;
  r.method = PairMethod::Sat;
  r.normal = s.normal;
  if (cache != nullptr) {
    cache->axis = pose_a.inverse_apply_vector(s.normal);
    cache->valid = true;
  }
  if (s.separation > Real(0)) {
    const geometry::ClosestPair cp = geometry::closest_points_triangle_triangle(
        pa.vertices[0], pa.vertices[1], pa.vertices[2], pb.vertices[0], pb.vertices[1], pb.vertices[2]);
    r.point_a = cp.on_a;
    r.point_b = cp.on_b;
    const Real dist = std::sqrt(cp.distance_squared);
    Vec3 unit;
    Real len = Real(0);
    if (dist > tol * Real(1e-3) && unit_and_length(r.point_b - r.point_a, unit, len)) r.normal = unit;
    r.signed_distance = std::max(dist, s.separation);
  } else {
    r.signed_distance = s.separation;
    penetration_witness(r, [&](const Vec3& shift, Vec3& on_a, Vec3& on_b) {
      const geometry::ClosestPair cp = geometry::closest_points_triangle_triangle(
          pa.vertices[0], pa.vertices[1], pa.vertices[2], pb.vertices[0] + shift, pb.vertices[1] + shift,
          pb.vertices[2] + shift);
      on_a = cp.on_a;
      on_b = cp.on_b;
    });
  }
  r.status = status_from_distance(r.signed_distance, tol);
  return r;
}

bool pair_intersect(const Triangle& a, const Transform& pose_a, const Triangle& b, const Transform& pose_b,
                    const PairRequest& request, PairCache* cache) {
  if (!finite_poses(pose_a, pose_b)) return false;
  return pair_distance(a, pose_a, b, pose_b, request, cache).signed_distance <=
         std::max(request.contact_distance, Real(0));
}

ContactManifold pair_collide(const Triangle& a, const Transform& pose_a, const Triangle& b, const Transform& pose_b,
                             const PairRequest& request, PairCache* cache) {
  if (!finite_poses(pose_a, pose_b)) return invalid_manifold();
  const DistanceResult d = pair_distance(a, pose_a, b, pose_b, request, cache);
  ContactManifold m = manifold_of(a, pose_a, b, pose_b, d, request);
  m.method = PairMethod::Sat;
  return m;
}

}  // namespace proxima::narrow
