// Mesh against mesh: boolean, every contact and distance between the triangles of two placed
// meshes by a simultaneous descent of both hierarchies.
//
// Steps (Gottschalk, Lin, Manocha, "OBBTree: a hierarchical structure for rapid interference
// detection", SIGGRAPH 1996; Larsen, Gottschalk, Lin, Manocha, "Fast proximity queries with
// swept sphere volumes", 1999, for the distance descent; Ericson, Real-Time Collision
// Detection 4.4.1, 5.1.9, 5.1.10 and 6.3):
//  1. Work in A's local frame: B's points map by the relative transform x_a = R x_b + t,
//     computed once per query.
//  2. Node bounds: by default each mesh's oriented boxes (TriangleMesh::oriented_tree, one
//     per Bvh node, built on the mesh's first such query); the node whose split is decided
//     is mapped into the other mesh's frame once for both children of the other side, then
//     the 15-axis separating-axis test (bounds/box_separation.hpp, shared with the Obb
//     overlap). The reference path (MeshMeshNodes::Aabb) tests A's axis-aligned Bvh boxes
//     against B's as oriented boxes in A's frame.
//  3. Overlap (boolean, all contacts): boxes within the contact distance plus a rounding
//     margin; descend the node with the larger size (a leaf never), fixed stack of pairs
//     (spatial/bvh_pair_descent.hpp, shared with compound against compound).
//  4. Leaves: B's leaf triangles moved into A's frame once per leaf pair, every triangle pair
//     tested (geometry::triangles_intersect, or the exact distance with a contact distance).
//     The boolean stops at the first hit; collide_all runs the narrow phase's triangle pair
//     on every hit.
//  5. Distance: first the overlap descent (a touching pair gives distance 0 at once); else
//     depth-first, nearer child pair first, a node pair pruned when its lower bound (the
//     largest gap over the separating axes and the centre axis, stopping once it exceeds
//     the best distance so far) is not below the best triangle distance. At the leaves:
//     a centroid-sphere and projection bound per triangle pair, then, the triangles being
//     known apart, only the six vertex-face and nine edge-edge candidates (no crossing
//     search; geometry::closest_points_triangle_triangle where coordinates need rescaling).
//
// The stack bound: every pop that pushes two pairs goes one level deeper on one side, so at
// most depth(A) + depth(B) + 1 pairs are ever pending.
//
// Penetration: two meshes are surfaces here, so intersecting meshes get signed distance 0
// (status Touching) with witnesses at a common point of a crossing triangle pair and the
// normal of A's triangle turned towards B's; no penetration depth is computed.
//
// Node type, by measurement on W4 (icosphere 20,480 against torus knot 50,000 triangles,
// 1,000 poses, callgrind instructions per query): oriented boxes against the axis-aligned
// ones cut the distance descent from 4,020 to 1,380 inner node pairs and 1,250 to 334 leaf
// pairs a query; boolean 51k instructions a query. Building the oriented boxes of both
// meshes (70,480 triangles) takes about 2.2e8 instructions (about 19 ms), once per mesh.
#include "mesh_mesh.hpp"

#include <proxima/core/tolerance.hpp>
#include <proxima/geometry/closest_points.hpp>
#include <proxima/narrowphase/narrowphase.hpp>
#include <proxima/shapes/triangle.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>

#include "geometry/box_separation.hpp"
#include "pair_support.hpp"
#include "shapes/oriented_tree.hpp"
#include "spatial/bvh_pair_descent.hpp"

namespace proxima::narrow {
namespace {

constexpr std::uint32_t kMaxLeafTriangles = 255;

/// B's frame seen from A's: x_a = r * x_b + t; rows of r kept row-major for the SAT.
struct RelativeFrame {
  Real r[3][3];      ///< r[i][j]: component i (A axis) of B's axis j
  Real abs_r[3][3];  ///< |r| + epsilon (parallel edge pairs)
  Vec3 t;            ///< B's origin in A's frame
  Mat3 rotation;     ///< r as a matrix
};

RelativeFrame make_frame(const Transform& pose_a, const Transform& pose_b) {
  const Transform rel = relative(pose_a, pose_b);
  RelativeFrame f;
  f.rotation = rel.rotation_matrix();
  f.t = rel.position;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      f.r[i][j] = f.rotation[j][i];
      f.abs_r[i][j] = std::abs(f.r[i][j]) + Real(8) * kEpsilon;
    }
  }
  return f;
}

struct NodeBox {
  Vec3 c;  ///< centre
  Vec3 h;  ///< half extents
};

inline NodeBox node_box(const BvhNode& n) { return {(n.min + n.max) * Real(0.5), (n.max - n.min) * Real(0.5)}; }

/// True when A's box and B's box (B-local, mapped by f) may be within `margin`: false only
/// when one of the 15 axes separates them by more than margin (Ericson 4.4.1).
bool boxes_overlap(const RelativeFrame& f, const NodeBox& a, const NodeBox& bl, Real margin) {
  const Vec3 d = f.rotation * bl.c + f.t - a.c;
  const Real t[3] = {d.x, d.y, d.z};
  return proxima::detail::boxes_within(f.r, f.abs_r, t, a.h, bl.h, margin);
}

/// A lower bound of the squared distance between A's box and B's box: the larger of the
/// squared distances between each box and the axis-aligned box enclosing the other in its
/// frame.
Real box_distance_lower_bound_squared(const RelativeFrame& f, const NodeBox& a, const NodeBox& bl,
                                      Real prune2 = std::numeric_limits<Real>::infinity()) {
  const Vec3 bc = f.rotation * bl.c + f.t;
  const Vec3 d = bc - a.c;  // A's frame
  const Real t[3] = {d.x, d.y, d.z};
  const Real ea[3] = {a.h.x, a.h.y, a.h.z};
  const Real eb[3] = {bl.h.x, bl.h.y, bl.h.z};
  const auto& r = f.r;
  const auto& ar = f.abs_r;
  Real in_a = Real(0);
  Real in_b = Real(0);
  for (int i = 0; i < 3; ++i) {
    const Real rb = ar[i][0] * eb[0] + ar[i][1] * eb[1] + ar[i][2] * eb[2];
    const Real gap = std::abs(t[i]) - ea[i] - rb;
    if (gap > Real(0)) in_a += gap * gap;
  }
  for (int j = 0; j < 3; ++j) {
    const Real ra = ar[0][j] * ea[0] + ar[1][j] * ea[1] + ar[2][j] * ea[2];
    const Real tj = t[0] * r[0][j] + t[1] * r[1][j] + t[2] * r[2][j];
    const Real gap = std::abs(tj) - ra - eb[j];
    if (gap > Real(0)) in_b += gap * gap;
  }
  Real lb2 = std::max(in_a, in_b);
  if (lb2 >= prune2) return lb2;  // pruned already: the finer bound is not needed
  // The axis through the two centres: nearly tight for boxes far apart for their size.
  const Real dd = glm::dot(d, d);
  if (dd > Real(0)) {
    const Real len = std::sqrt(dd);
    const Vec3 u = d / len;
    const Real ra = ea[0] * std::abs(u.x) + ea[1] * std::abs(u.y) + ea[2] * std::abs(u.z);
    Real rb = Real(0);
    for (int j = 0; j < 3; ++j) rb += eb[j] * std::abs(u.x * r[0][j] + u.y * r[1][j] + u.z * r[2][j]);
    const Real gap = len - ra - rb;
    if (gap > Real(0)) lb2 = std::max(lb2, gap * gap);
  }
  return lb2;
}

inline Real extent_sum(const BvhNode& n) {
  const Vec3 e = n.max - n.min;
  return e.x + e.y + e.z;
}

/// The axis-aligned node test (the reference path): A's boxes in A's frame against B's boxes
/// as oriented boxes mapped by f. A node test offers, for a pair (A node, B node): the
/// overlap within a margin and a squared distance lower bound, each with one side fixed
/// (fix_a / fix_b prepare that side once for both children of the other).
struct AabbNodes {
  const BvhNode* na;
  const BvhNode* nb;
  const RelativeFrame* f;

  NodeBox fix_a(std::uint32_t ia) const { return node_box(na[ia]); }
  NodeBox fix_b(std::uint32_t ib) const { return node_box(nb[ib]); }
  bool overlap(std::uint32_t ia, const NodeBox& b, Real margin) const {
    return boxes_overlap(*f, node_box(na[ia]), b, margin);
  }
  bool overlap(const NodeBox& a, std::uint32_t ib, Real margin) const {
    return boxes_overlap(*f, a, node_box(nb[ib]), margin);
  }
  Real lower_bound2(std::uint32_t ia, const NodeBox& b, Real prune2) const {
    return box_distance_lower_bound_squared(*f, node_box(na[ia]), b, prune2);
  }
  Real lower_bound2(const NodeBox& a, std::uint32_t ib, Real prune2) const {
    return box_distance_lower_bound_squared(*f, a, node_box(nb[ib]), prune2);
  }
  Real size_a(std::uint32_t ia) const { return extent_sum(na[ia]); }
  Real size_b(std::uint32_t ib) const { return extent_sum(nb[ib]); }
};

/// The oriented node test: both meshes' OrientedTree boxes and the shared separating-axis
/// test. The fixed side is mapped into the other mesh's frame once (A's box into B's frame
/// by the inverse of f, B's into A's by f).
struct OrientedNodes {
  const proxima::detail::OrientedNode* oa;
  const proxima::detail::OrientedNode* ob;
  const RelativeFrame* f;

  /// A box's axes and centre mapped into the other mesh's frame.
  struct Mapped {
    Vec3 axis[3];
    Vec3 center;
    Vec3 half;
  };
  Mapped fix_a(std::uint32_t ia) const {
    const proxima::detail::OrientedNode& a = oa[ia];
    const Mat3 inv = glm::transpose(f->rotation);
    return {{inv * a.axis[0], inv * a.axis[1], inv * a.axis[2]}, inv * (a.center - f->t), a.half};
  }
  Mapped fix_b(std::uint32_t ib) const {
    const proxima::detail::OrientedNode& b = ob[ib];
    const Mat3& r = f->rotation;
    return {{r * b.axis[0], r * b.axis[1], r * b.axis[2]}, r * b.center + f->t, b.half};
  }
  static constexpr Real kParallel = Real(8) * kEpsilon;
  proxima::detail::BoxPairFrame pair(std::uint32_t ia, const Mapped& b) const {
    return proxima::detail::box_pair_frame(oa[ia].axis, oa[ia].center, b.axis, b.center, kParallel);
  }
  proxima::detail::BoxPairFrame pair(const Mapped& a, std::uint32_t ib) const {
    return proxima::detail::box_pair_frame(a.axis, a.center, ob[ib].axis, ob[ib].center, kParallel);
  }
  bool overlap(std::uint32_t ia, const Mapped& b, Real margin) const {
    return proxima::detail::boxes_within(pair(ia, b), oa[ia].half, b.half, margin);
  }
  bool overlap(const Mapped& a, std::uint32_t ib, Real margin) const {
    return proxima::detail::boxes_within(pair(a, ib), a.half, ob[ib].half, margin);
  }
  static Real squared_gap(const proxima::detail::BoxPairFrame& p, const Vec3& ea, const Vec3& eb, Real prune2) {
    const Real g = proxima::detail::boxes_gap(p, ea, eb, std::sqrt(prune2));
    return g * g;
  }
  Real lower_bound2(std::uint32_t ia, const Mapped& b, Real prune2) const {
    return squared_gap(pair(ia, b), oa[ia].half, b.half, prune2);
  }
  Real lower_bound2(const Mapped& a, std::uint32_t ib, Real prune2) const {
    return squared_gap(pair(a, ib), a.half, ob[ib].half, prune2);
  }
  Real size_a(std::uint32_t ia) const { return oa[ia].half.x + oa[ia].half.y + oa[ia].half.z; }
  Real size_b(std::uint32_t ib) const { return ob[ib].half.x + ob[ib].half.y + ob[ib].half.z; }
};

/// Calls `run(nodes)` with the node test of `kind` for the pair (a, b).
template <class Run>
auto with_nodes(MeshMeshNodes kind, const TriangleMesh& a, const TriangleMesh& b, const RelativeFrame& f, Run&& run) {
  if (kind == MeshMeshNodes::Oriented && !a.bvh().empty() && !b.bvh().empty()) {
    return run(OrientedNodes{a.oriented_tree().nodes.data(), b.oriented_tree().nodes.data(), &f});
  }
  return run(AabbNodes{a.bvh().nodes().data(), b.bvh().nodes().data(), &f});
}

/// Largest |coordinate| of both meshes' boxes in A's frame: the scale of rounding errors.
Real pair_scale(const TriangleMesh& a, const TriangleMesh& b, const RelativeFrame& f) {
  const Aabb ba = a.local_aabb();
  const NodeBox bb{b.local_aabb().center(), b.local_aabb().half_extents()};
  const Vec3 c = f.rotation * bb.c + f.t;
  const Real rb = glm::length(bb.h);
  Real s = Real(0);
  for (int i = 0; i < 3; ++i) {
    s = std::max({s, std::abs(ba.min[i]), std::abs(ba.max[i]), std::abs(c[i]) + rb});
  }
  return s;
}

/// Rounding margin of the node tests: a few times the tolerance of triangles_intersect.
inline Real node_margin(Real scale, Real contact_distance) {
  return contact_distance + Real(4) * kRelativeTolerance * std::max(Real(1), scale);
}

/// The triangles of one B leaf moved into A's frame.
struct LeafTriangles {
  std::array<std::array<Vec3, 3>, kMaxLeafTriangles> v;
  std::uint32_t index[kMaxLeafTriangles];
  Vec3 center[kMaxLeafTriangles];  ///< centroid (distance bound)
  Real radius[kMaxLeafTriangles];  ///< largest centroid-to-vertex distance
  Aabb box[kMaxLeafTriangles];     ///< box in A's frame
  Vec3 normal[kMaxLeafTriangles];  ///< unit normal in A's frame (zero when degenerate)
  std::uint32_t count = 0;
};

/// Squared lower bound of the distance between triangles a and b: the gap between their
/// projections on the unit axis u (A towards B) and on each face normal.
inline Real triangle_gap_squared(const std::array<Vec3, 3>& a, const Vec3& na, const std::array<Vec3, 3>& b,
                                 const Vec3& nb, const Vec3& u) {
  Real gap = std::min({glm::dot(u, b[0]), glm::dot(u, b[1]), glm::dot(u, b[2])}) -
             std::max({glm::dot(u, a[0]), glm::dot(u, a[1]), glm::dot(u, a[2])});
  // n: unit normal of `face` (or zero for a degenerate one).
  const auto side_gap = [](const std::array<Vec3, 3>& face, const Vec3& n, const std::array<Vec3, 3>& other) {
    const Real d0 = glm::dot(n, other[0] - face[0]);
    const Real d1 = glm::dot(n, other[1] - face[0]);
    const Real d2 = glm::dot(n, other[2] - face[0]);
    const Real lo = std::min({d0, d1, d2});
    const Real hi = std::max({d0, d1, d2});
    return lo > Real(0) ? lo : (hi < Real(0) ? -hi : Real(0));
  };
  gap = std::max({gap, side_gap(a, na, b), side_gap(b, nb, a)});
  return gap > Real(0) ? gap * gap : Real(0);
}

/// Keeps in `best` the nearer of it and the closest points of segments p0p1 (on A) and q0q1
/// (on B): the clamped parameters of Ericson 5.1.9. For nearly parallel segments the
/// parameter is ill-conditioned, but the distance then varies by at most sin^2 of their
/// angle times the squared length over it, so the distance stays within rounding.
inline void nearer_segment_pair(const Vec3& p0, const Vec3& p1, const Vec3& q0, const Vec3& q1,
                                geometry::ClosestPair& best) {
  const Vec3 d1 = p1 - p0;
  const Vec3 d2 = q1 - q0;
  const Vec3 r = p0 - q0;
  const Real a = glm::dot(d1, d1);
  const Real e = glm::dot(d2, d2);
  const Real f = glm::dot(d2, r);
  Real s = Real(0);
  Real t = Real(0);
  if (!(a > Real(0))) {
    if (e > Real(0)) t = std::clamp(f / e, Real(0), Real(1));
  } else {
    const Real c = glm::dot(d1, r);
    if (!(e > Real(0))) {
      s = std::clamp(-c / a, Real(0), Real(1));
    } else {
      const Real b = glm::dot(d1, d2);
      const Real denom = a * e - b * b;
      s = denom > Real(0) ? std::clamp((b * f - c * e) / denom, Real(0), Real(1)) : Real(0);
      const Real tn = b * s + f;
      if (tn < Real(0)) {
        s = std::clamp(-c / a, Real(0), Real(1));
      } else if (tn > e) {
        t = Real(1);
        s = std::clamp((b - c) / a, Real(0), Real(1));
      } else {
        t = tn / e;
      }
    }
  }
  const Vec3 on_a = p0 + d1 * s;
  const Vec3 on_b = q0 + d2 * t;
  const Vec3 d = on_b - on_a;
  const Real d2_ab = glm::dot(d, d);
  if (d2_ab < best.distance_squared) best = {on_a, on_b, d2_ab};
}

/// Keeps in `best` the nearer of it and the vertex-face pair of point p and triangle t
/// (unit normal n, zero when degenerate) when p projects inside t (else an edge pair is
/// nearer). `p_on_a`: p belongs to A (the pair is stored as (p, foot)), else to B.
inline void nearer_vertex_face(const Vec3& p, const std::array<Vec3, 3>& t, const Vec3& n, bool p_on_a,
                               geometry::ClosestPair& best) {
  const Real h = glm::dot(n, p - t[0]);
  if (!(h * h < best.distance_squared) || glm::dot(n, n) == Real(0)) return;
  const Vec3 foot = p - h * n;
  for (int k = 0; k < 3; ++k) {
    const Vec3& u = t[k];
    const Vec3& v = t[(k + 1) % 3];
    if (glm::dot(glm::cross(v - u, foot - u), n) < Real(0)) return;
  }
  best = p_on_a ? geometry::ClosestPair{p, foot, h * h} : geometry::ClosestPair{foot, p, h * h};
}

/// Closest points of two triangles known to be apart (the overlap descent found no pair
/// within tolerance, so the nearest features are a vertex and a face or two edges: Ericson
/// 5.1.10): the six vertex-face and nine edge-edge candidates, no crossing search. Unit
/// normals na, nb (zero when degenerate). Coordinates in the range where no rescaling is
/// needed (geometry::detail::rescale_exponent == 0).
inline geometry::ClosestPair separated_triangles(const std::array<Vec3, 3>& ta, const Vec3& na,
                                                 const std::array<Vec3, 3>& tb, const Vec3& nb) {
  geometry::ClosestPair best{ta[0], tb[0], std::numeric_limits<Real>::infinity()};
  for (int k = 0; k < 3; ++k) {
    for (int l = 0; l < 3; ++l) nearer_segment_pair(ta[k], ta[(k + 1) % 3], tb[l], tb[(l + 1) % 3], best);
  }
  for (int k = 0; k < 3; ++k) {
    nearer_vertex_face(ta[k], tb, nb, true, best);
    nearer_vertex_face(tb[k], ta, na, false, best);
  }
  return best;
}

/// Unit normal of a triangle, zero when degenerate.
inline Vec3 unit_normal(const std::array<Vec3, 3>& t) {
  const Vec3 n = glm::cross(t[1] - t[0], t[2] - t[0]);
  const Real len2 = glm::dot(n, n);
  return len2 > Real(0) ? n / std::sqrt(len2) : Vec3(Real(0));
}

/// Centroid and bounding radius of a triangle.
inline void triangle_sphere(const std::array<Vec3, 3>& t, Vec3& c, Real& r) {
  c = (t[0] + t[1] + t[2]) * (Real(1) / Real(3));
  r = std::sqrt(std::max({glm::dot(t[0] - c, t[0] - c), glm::dot(t[1] - c, t[1] - c), glm::dot(t[2] - c, t[2] - c)}));
}

/// Triangle `t` of B in A's frame.
std::array<Vec3, 3> b_in_a(const TriangleMesh& b, const RelativeFrame& f, std::uint32_t t) {
  const std::array<Vec3, 3> v = b.triangle(t);
  return {f.rotation * v[0] + f.t, f.rotation * v[1] + f.t, f.rotation * v[2] + f.t};
}

void load_leaf(const TriangleMesh& b, const RelativeFrame& f, const BvhNode& leaf, LeafTriangles& out) {
  const auto prims = b.bvh().primitives();
  out.count = std::min(leaf.count, kMaxLeafTriangles);
  for (std::uint32_t k = 0; k < out.count; ++k) {
    const std::uint32_t ti = prims[leaf.first + k];
    out.index[k] = ti;
    out.v[k] = b_in_a(b, f, ti);
    triangle_sphere(out.v[k], out.center[k], out.radius[k]);
    out.normal[k] = unit_normal(out.v[k]);
    out.box[k] = {glm::min(glm::min(out.v[k][0], out.v[k][1]), out.v[k][2]),
                  glm::max(glm::max(out.v[k][0], out.v[k][1]), out.v[k][2])};
  }
}

/// Closest points of two triangles apart, as the distance descent computes them: the short
/// vertex-face and edge-edge search in the plain coordinate range (`plain_range`), the
/// general routine beyond it. Unit normals na, nb as unit_normal gives them.
inline geometry::ClosestPair apart_triangles(const std::array<Vec3, 3>& ta, const Vec3& na,
                                             const std::array<Vec3, 3>& tb, const Vec3& nb, bool plain_range) {
  return plain_range ? separated_triangles(ta, na, tb, nb)
                     : geometry::closest_points_triangle_triangle(ta[0], ta[1], ta[2], tb[0], tb[1], tb[2]);
}

/// The pair test shared by the boolean and all contacts (A's frame); `nb` is B's unit
/// normal as unit_normal gives it (a leaf holds it). Within a positive contact distance it
/// compares the same number the distance query does (apart_triangles, then the square
/// root), so that the two agree to the last bit at the threshold.
inline bool triangles_within(const std::array<Vec3, 3>& a, const std::array<Vec3, 3>& b, const Vec3& nb,
                             Real contact_distance, bool plain_range) {
  if (geometry::triangles_intersect(a[0], a[1], a[2], b[0], b[1], b[2])) return true;
  if (contact_distance <= Real(0)) return false;
  return std::sqrt(apart_triangles(a, unit_normal(a), b, nb, plain_range).distance_squared) <= contact_distance;
}

/// True when a pair of meshes at this scale needs no rescaling (apart_triangles).
inline bool in_plain_range(Real scale) { return geometry::detail::rescale_exponent(scale) == 0; }

/// True when `hint` names a triangle of A and a triangle of B.
bool valid_pair(const TriangleMesh& a, const TriangleMesh& b, const PartHint* hint) {
  return hint != nullptr && hint->a < a.triangle_count() && hint->b < b.triangle_count();
}

/// World-frame unit normal of A's triangle turned towards `towards` (A frame), +z when flat.
Vec3 facing_normal(const std::array<Vec3, 3>& ta, const Vec3& towards, const Transform& pose_a) {
  Vec3 n = glm::cross(ta[1] - ta[0], ta[2] - ta[0]);
  const Real len = glm::length(n);
  if (!(len > Real(0))) return pose_a.apply_vector(Vec3(Real(0), Real(0), Real(1)));
  n /= len;
  if (glm::dot(n, towards - ta[0]) < Real(0)) n = -n;
  return pose_a.apply_vector(n);
}

/// The first triangle pair (A, B) within the contact distance found by the overlap descent,
/// or false when there is none.
template <class Nodes>
bool find_pair_within(const TriangleMesh& a, const TriangleMesh& b, const RelativeFrame& f, const Nodes& nodes,
                      Real margin, Real cd, bool plain_range, std::uint32_t& found_a, std::uint32_t& found_b) {
  const auto prims_a = a.bvh().primitives();
  LeafTriangles leaf_b;
  std::uint32_t loaded = kNoIndex;
  const BvhNode* nodes_b = b.bvh().nodes().data();
  return !spatial::descend_bvh_pairs(a.bvh(), b.bvh(), nodes, margin, [&](const BvhNode& la, const BvhNode& lb) {
    const auto id_b = static_cast<std::uint32_t>(&lb - nodes_b);
    if (id_b != loaded) {
      load_leaf(b, f, lb, leaf_b);
      loaded = id_b;
    }
    for (std::uint32_t i = la.first; i != la.first + la.count; ++i) {
      const std::array<Vec3, 3> ta = a.triangle(prims_a[i]);
      const Aabb box_a =
          Aabb{glm::min(glm::min(ta[0], ta[1]), ta[2]), glm::max(glm::max(ta[0], ta[1]), ta[2])}.inflated(margin);
      for (std::uint32_t k = 0; k < leaf_b.count; ++k) {
        if (!box_a.overlaps(leaf_b.box[k])) continue;
        if (triangles_within(ta, leaf_b.v[k], leaf_b.normal[k], cd, plain_range)) {
          found_a = prims_a[i];
          found_b = leaf_b.index[k];
          return false;
        }
      }
    }
    return true;
  });
}

}  // namespace

bool mesh_mesh_intersect(const TriangleMesh& a, const Transform& pose_a, const TriangleMesh& b, const Transform& pose_b,
                         const PairRequest& request, MeshMeshNodes node_kind, PartHint* hint) {
  const RelativeFrame f = make_frame(pose_a, pose_b);
  const Real cd = request_reach(request);  // the touching rule (contact.hpp)
  const Real scale = pair_scale(a, b, f);
  const bool plain = in_plain_range(scale);
  if (valid_pair(a, b, hint)) {
    const std::array<Vec3, 3> tb = b_in_a(b, f, hint->b);
    if (triangles_within(a.triangle(hint->a), tb, unit_normal(tb), cd, plain)) return true;
  }
  const Real margin = node_margin(scale, cd);
  std::uint32_t ta = kNoIndex;
  std::uint32_t tb = kNoIndex;
  const bool hit = with_nodes(node_kind, a, b, f, [&](const auto& nodes) {
    return find_pair_within(a, b, f, nodes, margin, cd, plain, ta, tb);
  });
  if (hit && hint != nullptr) *hint = {ta, tb};
  return hit;
}

void mesh_mesh_collide_all(const TriangleMesh& a, const Transform& pose_a, const TriangleMesh& b,
                           const Transform& pose_b, const PairRequest& request, ContactCollector& collector,
                           MeshMeshNodes node_kind) {
  const RelativeFrame f = make_frame(pose_a, pose_b);
  const Real cd = request_reach(request);  // the touching rule (contact.hpp)
  const Real scale = pair_scale(a, b, f);
  const Real margin = node_margin(scale, cd);
  const bool plain = in_plain_range(scale);
  const auto prims_a = a.bvh().primitives();
  LeafTriangles leaf_b;
  std::uint32_t loaded = kNoIndex;
  const BvhNode* nodes_b = b.bvh().nodes().data();
  const auto visit = [&](const BvhNode& la, const BvhNode& lb) {
    const auto id_b = static_cast<std::uint32_t>(&lb - nodes_b);
    if (id_b != loaded) {
      load_leaf(b, f, lb, leaf_b);
      loaded = id_b;
    }
    for (std::uint32_t i = la.first; i != la.first + la.count; ++i) {
      const std::uint32_t tri_a = prims_a[i];
      const std::array<Vec3, 3> ta = a.triangle(tri_a);
      const Aabb box_a =
          Aabb{glm::min(glm::min(ta[0], ta[1]), ta[2]), glm::max(glm::max(ta[0], ta[1]), ta[2])}.inflated(margin);
      for (std::uint32_t k = 0; k < leaf_b.count; ++k) {
        if (!box_a.overlaps(leaf_b.box[k])) continue;
        if (!triangles_within(ta, leaf_b.v[k], leaf_b.normal[k], cd, plain)) continue;
        const std::uint32_t tri_b = leaf_b.index[k];
        const SubShapeId sub_a{kNoIndex, tri_a};
        const SubShapeId sub_b{kNoIndex, tri_b};
        const std::array<Vec3, 3> tb = b.triangle(tri_b);
        const Result<Triangle> shape_a = Triangle::create(ta[0], ta[1], ta[2]);
        const Result<Triangle> shape_b = Triangle::create(tb[0], tb[1], tb[2]);
        int added = 0;
        if (shape_a && shape_b) {
          const ContactManifold m = collide(ShapeRef(*shape_a), pose_a, ShapeRef(*shape_b), pose_b, request);
          for (int p = 0; p < m.count; ++p) {
            ContactPoint c = m.points[p];
            c.sub_a = sub_a;
            c.sub_b = sub_b;
            collector.add(c);
          }
          added = m.count;
        }
        if (added == 0) {
          // Degenerate triangle, or the pair touches within rounding where the narrow phase
          // finds no point: one contact at the closest points (A's frame, then world).
          const std::array<Vec3, 3>& tbl = leaf_b.v[k];
          const geometry::ClosestPair cp =
              geometry::closest_points_triangle_triangle(ta[0], ta[1], ta[2], tbl[0], tbl[1], tbl[2]);
          const Real d = std::sqrt(cp.distance_squared);
          ContactPoint c;
          c.point_a = pose_a.apply(cp.on_a);
          c.point_b = pose_a.apply(cp.on_b);
          c.normal = d > kRelativeTolerance * std::max(Real(1), scale)
                         ? pose_a.apply_vector((cp.on_b - cp.on_a) / d)
                         : facing_normal(ta, (tbl[0] + tbl[1] + tbl[2]) / Real(3), pose_a);
          c.depth = -d;
          c.feature_id = make_feature_id(FeatureKind::Face, tri_a, FeatureKind::Face, tri_b);
          c.sub_a = sub_a;
          c.sub_b = sub_b;
          collector.add(c);
        }
        if (collector.done()) return false;
      }
    }
    return true;
  };
  with_nodes(node_kind, a, b, f,
             [&](const auto& nodes) { return spatial::descend_bvh_pairs(a.bvh(), b.bvh(), nodes, margin, visit); });
}

namespace {

/// The distance descent with node test `nodes` (see mesh_mesh_distance).
template <class Nodes>
DistanceResult distance_descent(const TriangleMesh& a, const Transform& pose_a, const TriangleMesh& b,
                                const PairRequest& request, const RelativeFrame& f, const Nodes& nodes,
                                PartHint* hint) {
  DistanceResult out;
  const Real scale = pair_scale(a, b, f);
  const Bvh& ba = a.bvh();
  const Bvh& bb = b.bvh();
  if (ba.empty() || bb.empty()) {
    out.signed_distance = std::numeric_limits<Real>::infinity();
    return out;
  }
  const auto na = ba.nodes();
  const auto nb = bb.nodes();
  const auto prims_a = ba.primitives();

  Real best2 = std::numeric_limits<Real>::infinity();
  geometry::ClosestPair best_pair;
  std::uint32_t best_a = kNoIndex;
  std::uint32_t best_b = kNoIndex;
  std::array<Vec3, 3> best_ta{};
  std::array<Vec3, 3> best_tb{};

  struct Entry {
    std::uint32_t a;
    std::uint32_t b;
    Real lb2;
  };
  Entry stack[spatial::kBvhPairStackSize];
  std::uint32_t top = 0;
  stack[top++] = {0, 0, nodes.lower_bound2(0, nodes.fix_b(0), std::numeric_limits<Real>::infinity())};
  LeafTriangles leaf_b;
  std::uint32_t loaded = kNoIndex;
  bool touching = false;
  // Intersecting meshes: the overlap descent finds a touching pair far sooner than the
  // distance descent would.
  {
    std::uint32_t hit_a = kNoIndex;
    std::uint32_t hit_b = kNoIndex;
    const bool hinted_touch = valid_pair(a, b, hint) && [&] {
      const std::array<Vec3, 3> ta = a.triangle(hint->a);
      const std::array<Vec3, 3> tb = b_in_a(b, f, hint->b);
      return geometry::triangles_intersect(ta[0], ta[1], ta[2], tb[0], tb[1], tb[2]);
    }();
    if (hinted_touch) {
      hit_a = hint->a;
      hit_b = hint->b;
    }
    if (hinted_touch || find_pair_within(a, b, f, nodes, node_margin(scale, Real(0)), Real(0), false, hit_a, hit_b)) {
      const std::array<Vec3, 3> ta = a.triangle(hit_a);
      const std::array<Vec3, 3> tb = b_in_a(b, f, hit_b);
      best_pair = geometry::closest_points_triangle_triangle(ta[0], ta[1], ta[2], tb[0], tb[1], tb[2]);
      best2 = Real(0);  // touching within the triangle test's tolerance
      best_a = hit_a;
      best_b = hit_b;
      best_ta = ta;
      best_tb = tb;
      touching = true;
    }
  }
  // Apart meshes in the plain coordinate range take the short triangle distance.
  const bool plain_range = in_plain_range(scale);
  const auto pair_distance = [&](const std::array<Vec3, 3>& ta, const Vec3& na_unit, const std::array<Vec3, 3>& tb,
                                 const Vec3& nb_unit) {
    return apart_triangles(ta, na_unit, tb, nb_unit, plain_range);
  };

  if (!touching && valid_pair(a, b, hint)) {
    // The remembered pair's distance, computed as the descent would, is the first bound.
    best_ta = a.triangle(hint->a);
    best_tb = b_in_a(b, f, hint->b);
    best_pair = pair_distance(best_ta, unit_normal(best_ta), best_tb, unit_normal(best_tb));
    best2 = best_pair.distance_squared;
    best_a = hint->a;
    best_b = hint->b;
    touching = best2 == Real(0);
  }
  while (top != 0 && !touching) {
    const Entry e = stack[--top];
    if (e.lb2 >= best2) continue;
    const BvhNode& nda = na[e.a];
    const BvhNode& ndb = nb[e.b];
    if (nda.is_leaf() && ndb.is_leaf()) {
      if (e.b != loaded) {
        load_leaf(b, f, ndb, leaf_b);
        loaded = e.b;
      }
      for (std::uint32_t i = nda.first; i != nda.first + nda.count && !touching; ++i) {
        const std::uint32_t tri_a = prims_a[i];
        const std::array<Vec3, 3> ta = a.triangle(tri_a);
        Vec3 ca;
        Real ra;
        triangle_sphere(ta, ca, ra);
        const Vec3 na_unit = unit_normal(ta);
        for (std::uint32_t k = 0; k < leaf_b.count; ++k) {
          const std::array<Vec3, 3>& tb = leaf_b.v[k];
          const Real reach = ra + leaf_b.radius[k];
          const Vec3 dc = leaf_b.center[k] - ca;
          const Real dc2 = glm::dot(dc, dc);
          if (dc2 > reach * reach) {
            const Real lb = std::sqrt(dc2) - reach;
            if (lb * lb >= best2) continue;
            // Projections on the centroid axis and on both face normals bound the distance
            // much more tightly than the spheres.
            if (triangle_gap_squared(ta, na_unit, tb, leaf_b.normal[k], dc / std::sqrt(dc2)) >= best2) continue;
          }
          const geometry::ClosestPair cp = pair_distance(ta, na_unit, tb, leaf_b.normal[k]);
          if (cp.distance_squared < best2) {
            best2 = cp.distance_squared;
            best_pair = cp;
            best_a = tri_a;
            best_b = leaf_b.index[k];
            best_ta = ta;
            best_tb = tb;
            if (best2 == Real(0)) {
              touching = true;
              break;
            }
          }
        }
      }
      continue;
    }
    const bool split_a = ndb.is_leaf() || (!nda.is_leaf() && nodes.size_a(e.a) >= nodes.size_b(e.b));
    Entry c0;
    Entry c1;
    if (split_a) {
      const auto fixed = nodes.fix_b(e.b);
      c0 = {nda.first, e.b, nodes.lower_bound2(nda.first, fixed, best2)};
      c1 = {nda.first + 1, e.b, nodes.lower_bound2(nda.first + 1, fixed, best2)};
    } else {
      const auto fixed = nodes.fix_a(e.a);
      c0 = {e.a, ndb.first, nodes.lower_bound2(fixed, ndb.first, best2)};
      c1 = {e.a, ndb.first + 1, nodes.lower_bound2(fixed, ndb.first + 1, best2)};
    }
    if (c1.lb2 < c0.lb2) std::swap(c0, c1);  // c0 nearer: pushed last, popped first
    if (c1.lb2 < best2) stack[top++] = c1;
    if (c0.lb2 < best2) stack[top++] = c0;
  }

  const Real d = std::sqrt(best2);
  const Real tol = request.tolerance > Real(0) ? request.tolerance : linear_tolerance(scale);
  DistanceResult& r = out;
  r.signed_distance = d;
  r.point_a = pose_a.apply(best_pair.on_a);
  r.point_b = pose_a.apply(best_pair.on_b);
  if (d > kRelativeTolerance * std::max(Real(1), scale)) {
    r.normal = pose_a.apply_vector((best_pair.on_b - best_pair.on_a) / d);
  } else {
    r.normal = facing_normal(best_ta, (best_tb[0] + best_tb[1] + best_tb[2]) / Real(3), pose_a);
  }
  r.status = status_from_distance(d, tol);
  r.method = PairMethod::Analytic;
  r.tolerance = tol;
  out.sub_a.triangle = best_a;
  out.sub_b.triangle = best_b;
  if (hint != nullptr) *hint = {best_a, best_b};
  return out;
}

}  // namespace

DistanceResult mesh_mesh_distance(const TriangleMesh& a, const Transform& pose_a, const TriangleMesh& b,
                                  const Transform& pose_b, const PairRequest& request, MeshMeshNodes node_kind,
                                  PartHint* hint) {
  const RelativeFrame f = make_frame(pose_a, pose_b);
  return with_nodes(node_kind, a, b, f,
                    [&](const auto& nodes) { return distance_descent(a, pose_a, b, request, f, nodes, hint); });
}

}  // namespace proxima::narrow
