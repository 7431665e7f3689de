// Triangle-box: separating axes, exact distance and clipped manifold.
//
// Steps (Akenine-Moller, "Fast 3D Triangle-Box Overlap Testing", 2001, for the 13 axes;
// Ericson, Real-Time Collision Detection 5.2.9):
//  1. SAT over the triangle normal, its in-plane edge normals, the box's 3 face normals and
//     the 9 cross products of triangle edges with box axes (small_polytope_sat.hpp); the
//     largest separation <= 0 is minus the exact penetration depth.
//  2. Separated: the exact distance is the smallest over the 12 box edges against the
//     triangle and the 3 triangle vertices against the box (every closest feature pair of a
//     box and a triangle involves one of them). The normal is the SAT axis or the closest
//     points' direction, whichever the two are farther apart along, and the distance that
//     gap (sat_distance_result): a short gap's direction is mostly rounding.
//  3. Witnesses of a penetration: the closest features of the triangle and the box moved
//     out by the depth along the normal (they touch there; polytope_pair_common.hpp), right
//     for face, edge-edge and in-plane axes alike.
//  4. Manifold: supporting faces along the normal, clipped, reduced to 4 points; a
//     penetration whose clipped points reach the SAT depth skips step 3 (the witness would
//     not enter the manifold: sat_collide_result).
// intersect stops after step 1 when the separation exceeds the contact distance (a lower
// bound of the distance); triangle_box_separated_beyond is step 1 alone, which a mesh's
// collide_all asks first for each box-triangle pair.
#include <proxima/geometry/closest_points.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "polytope_pair_common.hpp"

namespace proxima::narrow {
namespace {

void box_polytope(const Box& b, const Transform& pose, SmallPolytope& p) {
  const Vec3 h = b.half_extents();
  p.vertex_count = 8;
  for (int c = 0; c < 8; ++c) {
    p.vertices[c] = pose.apply(Vec3((c & 1) ? h.x : -h.x, (c & 2) ? h.y : -h.y, (c & 4) ? h.z : -h.z));
  }
  const Mat3 m = pose.rotation_matrix();
  p.face_count = 3;
  p.edge_count = 3;
  for (int i = 0; i < 3; ++i) p.faces[i] = p.edges[i] = m[i];
}

// Exact closest points of a triangle (world vertices t) and a box (corners c, pose with
// position `centre` and axes m): every closest pair involves a box edge against the
// triangle or a triangle vertex against the box.
void closest_triangle_box(const std::array<Vec3, 8>& c, const Vec3* t, const Vec3& centre, const Mat3& m,
                          const Vec3& half_extents, Vec3& on_tri, Vec3& on_box) {
  Real best = std::numeric_limits<Real>::infinity();
  for (int k = 0; k < 8; ++k) {
    for (int bit = 1; bit < 8; bit <<= 1) {
      if (k & bit) continue;
      const geometry::ClosestPair cp = geometry::closest_points_segment_triangle(
          c[static_cast<std::size_t>(k)], c[static_cast<std::size_t>(k | bit)], t[0], t[1], t[2]);
      if (cp.distance_squared < best) {
        best = cp.distance_squared;
        on_tri = cp.on_b;
        on_box = cp.on_a;
      }
    }
  }
  for (int i = 0; i < 3; ++i) {
    const Vec3 q = geometry::closest_point_obb(t[i], centre, m, half_extents);
    const Real d2 = length_squared(q - t[i]);
    if (d2 < best) {
      best = d2;
      on_tri = t[i];
      on_box = q;
    }
  }
}

// The pair's polytopes, SAT, tolerance and closest-features function (shared by
// pair_distance and pair_collide).
struct TriangleBoxSat {
  SmallPolytope pa;
  SmallPolytope pb;
  SmallSat s;
  Real tol = Real(0);

  TriangleBoxSat(const Triangle& a, const Transform& pose_a, const Box& b, const Transform& pose_b,
                 const PairRequest& request) {
    triangle_polytope(a, pose_a, pa);
    box_polytope(b, pose_b, pb);
    s = small_polytope_sat(pa, pb, nullptr, 0, kParallelSine);
    Real scale = max_abs_component(b.half_extents());
    for (int i = 0; i < 8; ++i) scale = std::max(scale, max_abs_component(pb.vertices[i]));
    for (int i = 0; i < 3; ++i) scale = std::max(scale, max_abs_component(pa.vertices[i]));
    tol = resolve_tolerance(request, scale);
  }

  auto closest(const Box& b, const Transform& pose_b) const {
    return [this, &b, &pose_b](const Vec3* shift, Vec3& on_a, Vec3& on_b) {
      const Mat3 m = pose_b.rotation_matrix();
      if (shift == nullptr) {
        closest_triangle_box(pb.vertices, pa.vertices.data(), pose_b.position, m, b.half_extents(), on_a, on_b);
        return;
      }
      std::array<Vec3, 8> moved;
      for (std::size_t k = 0; k < 8; ++k) moved[k] = pb.vertices[k] + *shift;
      closest_triangle_box(moved, pa.vertices.data(), pose_b.position + *shift, m, b.half_extents(), on_a, on_b);
    };
  }
};

}  // namespace

DistanceResult pair_distance(const Triangle& a, const Transform& pose_a, const Box& b, const Transform& pose_b,
                             const PairRequest& request, PairCache* cache) {
  if (!poses_in_range(pose_a, pose_b)) return invalid_distance();
  const TriangleBoxSat sat(a, pose_a, b, pose_b, request);
  return sat_distance_result(sat.s, sat.pa, sat.pb, pose_a, sat.tol, cache, sat.closest(b, pose_b));
}

bool triangle_box_separated_beyond(const Triangle& a, const Transform& pose_a, const Box& b, const Transform& pose_b,
                                   Real beyond) {
  SmallPolytope pa;
  SmallPolytope pb;
  triangle_polytope(a, pose_a, pa);
  box_polytope(b, pose_b, pb);
  return small_polytope_sat(pa, pb, nullptr, 0, kParallelSine).separation > beyond;
}

Real triangle_box_directional_signed_distance(const Triangle& a, const Transform& pose_a, const Box& b,
                                              const Transform& pose_b, const Vec3& n) {
  SmallPolytope pa;
  SmallPolytope pb;
  triangle_polytope(a, pose_a, pa);
  box_polytope(b, pose_b, pb);
  const TranslationInterval t = small_polytope_translation_interval(pa, pb, n, kParallelSine);
  if (t.lo > t.hi || t.lo > Real(0)) return std::numeric_limits<Real>::infinity();
  return -t.hi;
}

bool pair_intersect(const Triangle& a, const Transform& pose_a, const Box& b, const Transform& pose_b,
                    const PairRequest& request, PairCache* cache) {
  if (!poses_in_range(pose_a, pose_b)) return false;
  // The separation along the best axis is a lower bound of the distance: beyond the
  // contact reach the answer is no without the exact closest features (the same answer
  // and cache as the full distance).
  const TriangleBoxSat sat(a, pose_a, b, pose_b, request);
  if (sat.s.separation > contact_reach(request.contact_distance, sat.tol)) {
    if (cache != nullptr) {
      cache->axis = pose_a.inverse_apply_vector(sat.s.normal);
      cache->valid = true;
    }
    return false;
  }
  return in_contact(sat_distance_result(sat.s, sat.pa, sat.pb, pose_a, sat.tol, cache, sat.closest(b, pose_b)),
                    request);
}

ContactManifold pair_collide(const Triangle& a, const Transform& pose_a, const Box& b, const Transform& pose_b,
                             const PairRequest& request, PairCache* cache) {
  if (!poses_in_range(pose_a, pose_b)) return invalid_manifold();
  const TriangleBoxSat sat(a, pose_a, b, pose_b, request);
  return sat_collide_result(a, pose_a, b, pose_b, sat.s, sat.pa, sat.pb, sat.tol, request, cache,
                            sat.closest(b, pose_b));
}

}  // namespace proxima::narrow
