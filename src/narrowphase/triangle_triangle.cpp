// Triangle-triangle: separating axes, exact distance and clipped manifold (two-sided
// triangles without thickness).
//
// Steps (Ericson, Real-Time Collision Detection 5.2.1 and 4.4; Gregorius' SAT):
//  1. SAT over both normals, the in-plane edge normals of both (which separate coplanar
//     pairs) and the 9 edge-pair cross products (small_polytope_sat.hpp); the largest
//     separation <= 0 is minus the exact penetration depth.
//  2. Separated: the exact closest points (geometry::closest_points_triangle_triangle); the
//     normal is the SAT axis or their direction, whichever the triangles are farther apart
//     along, and the distance that gap (polytope_pair_common.hpp).
//  3. Witnesses of a penetration: the closest points of A and of B moved out by the depth
//     along the normal (they touch there; polytope_pair_common.hpp), right for face,
//     edge-edge and in-plane axes alike.
//  4. Manifold: supporting faces (the triangles) along the normal, clipped, reduced to 4
//     points.
#include <proxima/geometry/closest_points.hpp>

#include <array>
#include <cmath>

#include "polytope_pair_common.hpp"

namespace proxima::narrow {

DistanceResult pair_distance(const Triangle& a, const Transform& pose_a, const Triangle& b, const Transform& pose_b,
                             const PairRequest& request, PairCache* cache) {
  if (!poses_in_range(pose_a, pose_b)) return invalid_distance();
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
  return sat_distance_result(s, pa, pb, pose_a, tol, cache, [&](const Vec3* shift, Vec3& on_a, Vec3& on_b) {
    std::array<Vec3, 3> q{pb.vertices[0], pb.vertices[1], pb.vertices[2]};
    if (shift != nullptr) {
      for (Vec3& v : q) v += *shift;
    }
    const geometry::ClosestPair cp =
        geometry::closest_points_triangle_triangle(pa.vertices[0], pa.vertices[1], pa.vertices[2], q[0], q[1], q[2]);
    on_a = cp.on_a;
    on_b = cp.on_b;
  });
}

bool pair_intersect(const Triangle& a, const Transform& pose_a, const Triangle& b, const Transform& pose_b,
                    const PairRequest& request, PairCache* cache) {
  return sat_pair_intersect(a, pose_a, b, pose_b, request, cache);
}

ContactManifold pair_collide(const Triangle& a, const Transform& pose_a, const Triangle& b, const Transform& pose_b,
                             const PairRequest& request, PairCache* cache) {
  return sat_pair_collide(a, pose_a, b, pose_b, request, cache);
}

}  // namespace proxima::narrow
