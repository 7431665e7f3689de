/// @file mesh_convex.cpp
/// A triangle mesh against a convex shape: boolean, distance and every contact, with
/// internal-edge handling.
///
/// Steps:
///  1. Map the convex shape into the mesh frame (relative pose) and take its box there,
///     inflated by the contact distance; walk the mesh BVH for the triangles whose node
///     boxes overlap it. A zero-area triangle (Triangle::create refuses it) counts as the
///     set it covers: the segment between its farthest corners, or a point (FlatTriangle).
///  2. Per candidate, the narrow phase's Triangle-vs-shape routine (mesh = A), world frame
///     (collide_all first drops a triangle whose plane the shape lies wholly beyond, by two
///     support calls, and for a box asks the cheap separating-axis intersect).
///     Distance: the minimum over triangles, nodes visited nearer first and pruned when the
///     box gap is not below the best distance so far (branch and bound).
///  3. Internal edges (the "ghost contact" problem; ideas of Bullet's
///     btAdjustInternalEdgeContacts and Jolt's active edges / InternalEdgeRemovingCollector):
///     a manifold whose normal is not the triangle's face normal is checked point by point.
///     Each contact point on the triangle is classified (barycentric coordinates) as face,
///     edge or vertex. On an active (convex or boundary) edge, or a vertex with an active
///     edge anywhere in its fan, the contact is real and kept. On an inactive (flat or concave) edge or vertex,
///     the normal is replaced by the face normal and the signed distance recomputed along
///     it against the triangle itself (not its plane, which would count parts of the shape
///     hanging beyond the triangle's other edges): the translation along the face normal
///     that separates the shape from the triangle, found as the exit of the ray along the
///     normal from the Minkowski difference by conservative advancement (the signed
///     distance is 1-Lipschitz in the translation) and bisection, bracketed above by the
///     plane depth and by depth / cos(angle to the narrow phase's normal), one value per
///     triangle (a few narrow-phase distance calls, only on inactive features; for a box, exact
///     in closed form over the 13 separating axes); the corrected contact
///     is dropped when a neighbouring triangle sharing its feature's vertices already gave a
///     face contact (that triangle holds the same support), or when the corrected gap
///     exceeds the contact distance.
///  4. Half-spaces (unbounded, no useful box) are handled in closed form over the vertices:
///     each vertex within contact distance of the plane is one contact (point on the mesh,
///     normal -plane normal), reported once with the first triangle found that uses it.

#include "mesh_convex.hpp"

#include <proxima/core/tolerance.hpp>
#include <proxima/narrowphase/narrowphase.hpp>
#include <proxima/shapes/point.hpp>
#include <proxima/shapes/segment.hpp>
#include <proxima/shapes/triangle.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <utility>

#include "pairs_polyhedral.hpp"
#include "shapes/shape_visit.hpp"

namespace proxima::narrow {
namespace {

constexpr Real kInf = std::numeric_limits<Real>::infinity();

/// A half-space's plane in the mesh's frame: normal . x - offset is the signed distance.
struct LocalPlane {
  Vec3 normal;        ///< unit, mesh frame
  Real offset;        ///< plane offset, mesh frame
  Vec3 world_normal;  ///< unit, world frame
};

LocalPlane local_plane(const HalfSpace& h, const Transform& pose_h, const Transform& pose_mesh) {
  const Vec3 nw = pose_h.apply_vector(h.normal());
  const Real ow = h.offset() + glm::dot(nw, pose_h.position);
  return {pose_mesh.inverse_apply_vector(nw), ow - glm::dot(nw, pose_mesh.position), nw};
}

/// Smallest signed plane distance over a box (mesh frame).
Real box_plane_distance(const Aabb& box, const LocalPlane& p) {
  const Vec3 c = box.center(), h = box.half_extents();
  return glm::dot(p.normal, c) -
         (std::abs(p.normal.x) * h.x + std::abs(p.normal.y) * h.y + std::abs(p.normal.z) * h.z) - p.offset;
}

/// Depth-first walk over the mesh BVH with node filter `enter(node) -> bool` and
/// `leaf(triangle) -> bool` (false stops).
template <class Enter, class Leaf>
void walk(const TriangleMesh& mesh, Enter&& enter, Leaf&& leaf) {
  mesh.bvh().traverse(enter, leaf);
}

/// A zero-area triangle as the convex set it covers (mesh frame): the segment between its
/// two farthest corners, or a point where the corners coincide (Segment::create refuses
/// them too). Its queries run on that shape, so a degenerate triangle is never skipped.
class FlatTriangle {
 public:
  explicit FlatTriangle(const std::array<Vec3, 3>& v) {
    std::size_t i = 0;
    std::size_t j = 1;
    for (const auto& [p, q] : {std::pair<std::size_t, std::size_t>{1, 2}, {0, 2}}) {
      if (glm::dot(v[q] - v[p], v[q] - v[p]) > glm::dot(v[j] - v[i], v[j] - v[i])) {
        i = p;
        j = q;
      }
    }
    if (Result<Segment> s = Segment::create(v[i], v[j])) segment_ = *s;
    at_.position = v[0];
  }
  /// Calls f(shape, its world pose) for the mesh at `pose_mesh`.
  template <class F>
  decltype(auto) visit(const Transform& pose_mesh, F&& f) const {
    if (segment_) return f(ShapeRef(*segment_), pose_mesh);
    return f(ShapeRef(point_), pose_mesh * at_);
  }

 private:
  std::optional<Segment> segment_;
  Point point_ = *Point::create();
  Transform at_;  ///< the point's place (mesh frame)
};

/// Calls f(t, corners, triangle) for each triangle t whose BVH leaf box overlaps `box` (mesh
/// frame), and flat(t, FlatTriangle) for a zero-area one; either returns false to stop.
template <class F, class Flat>
void for_each_triangle_near(const TriangleMesh& mesh, const Aabb& box, F&& f, Flat&& flat) {
  walk(
      mesh, [&](const BvhNode& n) { return n.bounds().overlaps(box); },
      [&](std::uint32_t t) {
        const std::array<Vec3, 3> v = mesh.triangle(t);
        const Result<Triangle> tri = Triangle::create(v[0], v[1], v[2]);
        return tri ? f(t, v, *tri) : flat(t, FlatTriangle(v));
      });
}

/// Box of the convex shape in the mesh's frame.
Aabb convex_box_in_mesh(ShapeRef convex, const Transform& pose_mesh, const Transform& pose_convex) {
  const Transform rel = relative(pose_mesh, pose_convex);
  return proxima::detail::visit_convex(convex, [&](const auto& s) { return s.world_aabb(rel); });
}

Vec3 world_support(ShapeRef convex, const Transform& pose, const Vec3& world_direction) {
  return proxima::detail::visit_convex(
      convex, [&](const auto& s) { return pose.apply(s.support(pose.inverse_apply_vector(world_direction))); });
}

/// Which feature of triangle (a, b, c) holds `p` (mesh frame): 0 face, 1 edge, 2 vertex;
/// `index` is the edge (e: vertex e to e+1) or vertex number.
struct Feature {
  int kind = 0;
  int index = 0;
};

Feature classify(const std::array<Vec3, 3>& v, const Vec3& p) {
  // Barycentric coordinates of p's projection on the plane (Ericson 3.4).
  const Vec3 e0 = v[1] - v[0], e1 = v[2] - v[0], d = p - v[0];
  const Real d00 = glm::dot(e0, e0), d01 = glm::dot(e0, e1), d11 = glm::dot(e1, e1);
  const Real d20 = glm::dot(d, e0), d21 = glm::dot(d, e1);
  const Real den = d00 * d11 - d01 * d01;
  if (!(den > Real(0))) return {};
  const Real w1 = (d11 * d20 - d01 * d21) / den;  // weight of v1
  const Real w2 = (d00 * d21 - d01 * d20) / den;  // weight of v2
  const Real w0 = Real(1) - w1 - w2;
  const Real tol = Real(1e-3);
  const bool z0 = w0 <= tol, z1 = w1 <= tol, z2 = w2 <= tol;
  const int zeros = int(z0) + int(z1) + int(z2);
  if (zeros == 0) return {0, 0};
  if (zeros >= 2) return {2, !z0 ? 0 : (!z1 ? 1 : 2)};
  // One weight ~0: the edge opposite that vertex. Edge e joins vertex e and e+1.
  return {1, z0 ? 1 : (z1 ? 2 : 0)};
}

/// True when some edge of the mesh at vertex `vertex` (a corner of triangle `t`) is active:
/// walks the triangle fan around the vertex through the neighbours (at most 64 steps; an
/// open fan or a walk that does not close counts as active).
bool vertex_active(const TriangleMesh& mesh, std::uint32_t t, std::uint32_t vertex) {
  const auto tris = mesh.triangles();
  std::uint32_t cur = t;
  for (int step = 0; step < 64; ++step) {
    const TriangleIndices& idx = tris[cur];
    const int j = idx[0] == vertex ? 0 : (idx[1] == vertex ? 1 : 2);
    if (idx[static_cast<std::size_t>(j)] != vertex) return true;
    const std::uint8_t bits = mesh.active_edges(cur);
    if (((bits >> j) & 1u) || ((bits >> ((j + 2) % 3)) & 1u)) return true;
    const std::uint32_t next = mesh.neighbors(cur)[static_cast<std::size_t>(j)];
    if (next == kNoIndex) return true;
    if (next == t) return false;
    cur = next;
  }
  return true;
}

/// Signed distance of `convex` from triangle `tri` (mesh frame, placed at `pose_mesh`) along
/// the unit world direction `n`: for an overlapping pair, minus the smallest t >= 0 such that
/// the shape moved by t*n no longer overlaps the triangle; for a separated pair, the smallest
/// t >= 0 such that the shape moved by -t*n touches it (returns a value above `cutoff` when
/// none does within `cutoff`). `sd0` is the pair's signed distance, `m` the narrow phase's
/// normal, `plane_sd` the signed distance of the shape's support point from the triangle's
/// plane along n (a lower bound of the answer for an overlap). At most 48 distance calls.
Real directional_signed_distance(const Triangle& tri, const Transform& pose_mesh, ShapeRef convex,
                                 const Transform& pose_convex, const PairRequest& request, const Vec3& n, Real sd0,
                                 const Vec3& m, Real plane_sd, Real cutoff) {
  const Real scale = std::max(
      {std::abs(pose_convex.position.x), std::abs(pose_convex.position.y), std::abs(pose_convex.position.z), Real(1)});
  const Real tol = request.tolerance > Real(0) ? request.tolerance : linear_tolerance(scale);
  const auto f = [&](Real t) {
    Transform moved = pose_convex;
    moved.position += t * n;
    return distance(ShapeRef(tri), pose_mesh, convex, moved, request).signed_distance;
  };
  if (sd0 > tol) {  // approach along -n from above (conservative advancement)
    Real t = Real(0), d = sd0;
    for (int k = 0; k < 48 && d > tol; ++k) {
      t += d;
      if (t > cutoff) return t;
      d = f(-t);
    }
    return t;
  }
  // Overlap or touch: the end t1 of the interval {t : f(t) <= tol} along +n (f is convex in
  // t, so that set is an interval holding 0). f is 1-Lipschitz, so f(mid) <= 0 puts t1 at
  // or past mid - f(mid); bisection otherwise.
  Real lo = std::max(Real(0), -sd0);
  Real hi = -plane_sd;
  const Real c = glm::dot(n, m);  // m may point either way; only a positive c bounds t1
  if (c > Real(0.05)) hi = std::min(hi, -sd0 / c + tol);
  for (int k = 0; k < 48 && hi - lo > tol; ++k) {
    const Real mid = Real(0.5) * (lo + hi);
    const Real dm = f(mid);
    if (dm > tol)
      hi = mid;
    else
      lo = std::min(hi, mid + std::max(Real(0), -dm));
  }
  return -Real(0.5) * (lo + hi);
}

/// Per-thread scratch for collide_all (reserved for 512 contacts, grows beyond).
struct Scratch {
  struct Pending {
    ContactPoint contact;
    std::uint32_t v0, v1;  ///< mesh vertices of the feature (v1 == v0 for a vertex)
  };
  std::vector<Pending> pending;
  std::vector<std::uint32_t> voided;  ///< vertices of triangles that gave a face contact
  std::vector<std::uint8_t> seen;     ///< half-space path: vertex already reported
};

Scratch& scratch() {
  // Reserved on a thread's first use, for the same reason as reduced_manifold's scratch: a
  // pool hands a pair to any thread, so per-thread growth would allocate at random steps.
  constexpr std::size_t kReserved = 512;
  thread_local Scratch s;
  if (s.pending.capacity() < kReserved) {
    s.pending.reserve(kReserved);
    s.voided.reserve(3 * kReserved);
  }
  return s;
}

bool halfspace_intersect(const TriangleMesh& mesh, const Transform& pose_mesh, const HalfSpace& h,
                         const Transform& pose_h, const PairRequest& request) {
  const LocalPlane p = local_plane(h, pose_h, pose_mesh);
  const Real cd = request_reach(request);  // the touching rule (contact.hpp)
  const auto verts = mesh.vertices();
  const auto tris = mesh.triangles();
  bool hit = false;
  walk(
      mesh, [&](const BvhNode& n) { return box_plane_distance(n.bounds(), p) <= cd; },
      [&](std::uint32_t t) {
        for (std::uint32_t k : tris[t])
          if (glm::dot(p.normal, verts[k]) - p.offset <= cd) {
            hit = true;
            return false;
          }
        return true;
      });
  return hit;
}

DistanceResult halfspace_distance(const TriangleMesh& mesh, const Transform& pose_mesh, const HalfSpace& h,
                                  const Transform& pose_h, const PairRequest& request, Real cutoff) {
  const LocalPlane p = local_plane(h, pose_h, pose_mesh);
  const auto verts = mesh.vertices();
  const auto tris = mesh.triangles();
  DistanceResult best;
  best.signed_distance = kInf;
  Real bound = cutoff;
  std::uint32_t best_vertex = kNoIndex;
  walk(
      mesh, [&](const BvhNode& n) { return box_plane_distance(n.bounds(), p) < bound; },
      [&](std::uint32_t t) {
        for (std::uint32_t k : tris[t]) {
          const Real sd = glm::dot(p.normal, verts[k]) - p.offset;
          if (sd < bound) {
            bound = sd;
            best_vertex = k;
            best.sub_a.triangle = t;
          }
        }
        return true;
      });
  if (best_vertex == kNoIndex) return best;
  const Vec3 pa = pose_mesh.apply(verts[best_vertex]);
  DistanceResult& r = best;
  r.signed_distance = bound;
  r.point_a = pa;
  r.point_b = pa - bound * p.world_normal;
  r.normal = -p.world_normal;
  const Real tol = request.tolerance > Real(0)
                       ? request.tolerance
                       : linear_tolerance(std::max({std::abs(pa.x), std::abs(pa.y), std::abs(pa.z)}));
  r.status = status_from_distance(bound, tol);
  r.method = PairMethod::Support;
  r.tolerance = tol;
  return best;
}

void halfspace_collide_all(const TriangleMesh& mesh, const Transform& pose_mesh, const HalfSpace& h,
                           const Transform& pose_h, const PairRequest& request, ContactCollector& collector) {
  const LocalPlane p = local_plane(h, pose_h, pose_mesh);
  const Real cd = request_reach(request);  // the touching rule (contact.hpp)
  const auto verts = mesh.vertices();
  const auto tris = mesh.triangles();
  std::vector<std::uint8_t>& seen = scratch().seen;
  seen.assign(verts.size(), 0);
  walk(
      mesh, [&](const BvhNode& n) { return box_plane_distance(n.bounds(), p) <= cd; },
      [&](std::uint32_t t) {
        for (std::uint32_t k : tris[t]) {
          const Real sd = glm::dot(p.normal, verts[k]) - p.offset;
          if (sd > cd || seen[k]) continue;
          seen[k] = 1;
          ContactPoint c;
          c.point_a = pose_mesh.apply(verts[k]);
          c.point_b = c.point_a - sd * p.world_normal;
          c.normal = -p.world_normal;
          c.depth = -sd;
          c.feature_id = make_feature_id(FeatureKind::Vertex, k, FeatureKind::Face, 0);
          c.sub_a.triangle = t;
          collector.add(c);
          if (collector.done()) return false;
        }
        return true;
      });
}

}  // namespace

bool mesh_convex_intersect(const TriangleMesh& mesh, const Transform& pose_mesh, ShapeRef convex,
                           const Transform& pose_convex, const PairRequest& request, PartHint* hint) {
  if (convex.type() == ShapeType::HalfSpace)
    return halfspace_intersect(mesh, pose_mesh, convex.as<HalfSpace>(), pose_convex, request);
  const auto flat_hit = [&](const FlatTriangle& flat) {
    return flat.visit(pose_mesh, [&](ShapeRef part, const Transform& pose_part) {
      return intersect(part, pose_part, convex, pose_convex, request);
    });
  };
  if (hint != nullptr && hint->a < mesh.triangle_count()) {
    const std::array<Vec3, 3> v = mesh.triangle(hint->a);
    const Result<Triangle> tri = Triangle::create(v[0], v[1], v[2]);
    if (tri ? intersect(*tri, pose_mesh, convex, pose_convex, request) : flat_hit(FlatTriangle(v))) return true;
  }
  const Aabb box = convex_box_in_mesh(convex, pose_mesh, pose_convex).inflated(cull_margin(request));
  bool hit = false;
  const auto found = [&](std::uint32_t t, bool touches) {
    hit = touches;
    if (hit && hint != nullptr) *hint = {t, kNoIndex};
    return !hit;
  };
  for_each_triangle_near(
      mesh, box,
      [&](std::uint32_t t, const std::array<Vec3, 3>&, const Triangle& tri) {
        return found(t, intersect(tri, pose_mesh, convex, pose_convex, request));
      },
      [&](std::uint32_t t, const FlatTriangle& flat) { return found(t, flat_hit(flat)); });
  return hit;
}

DistanceResult mesh_convex_distance(const TriangleMesh& mesh, const Transform& pose_mesh, ShapeRef convex,
                                    const Transform& pose_convex, const PairRequest& request, Real cutoff,
                                    PartHint* hint) {
  if (convex.type() == ShapeType::HalfSpace)
    return halfspace_distance(mesh, pose_mesh, convex.as<HalfSpace>(), pose_convex, request, cutoff);
  DistanceResult best;
  best.signed_distance = kInf;
  Real bound = cutoff;
  const auto answer = [&](std::uint32_t t) {
    const auto v = mesh.triangle(t);
    const Result<Triangle> tri = Triangle::create(v[0], v[1], v[2]);
    const DistanceResult r = tri ? distance(ShapeRef(*tri), pose_mesh, convex, pose_convex, request)
                                 : FlatTriangle(v).visit(pose_mesh, [&](ShapeRef part, const Transform& pose_part) {
                                     return distance(part, pose_part, convex, pose_convex, request);
                                   });
    if (r.signed_distance < bound || (r.signed_distance == bound && t < best.sub_a.triangle)) {
      bound = r.signed_distance;
      best = r;
      best.sub_a.triangle = t;
    }
  };
  const std::uint32_t first = hint != nullptr && hint->a < mesh.triangle_count() ? hint->a : kNoIndex;
  if (first != kNoIndex) answer(first);
  const Aabb box = convex_box_in_mesh(convex, pose_mesh, pose_convex);
  mesh.bvh().traverse_nearest([&](const Aabb& node) { return proxima::detail::aabb_gap(node, box); }, bound,
                              [&](std::uint32_t t) {
                                if (t != first) answer(t);
                              });
  if (hint != nullptr) *hint = {best.sub_a.triangle, kNoIndex};
  return best;
}

void mesh_convex_collide_all(const TriangleMesh& mesh, const Transform& pose_mesh, ShapeRef convex,
                             const Transform& pose_convex, const PairRequest& request, ContactCollector& collector) {
  if (convex.type() == ShapeType::HalfSpace) {
    halfspace_collide_all(mesh, pose_mesh, convex.as<HalfSpace>(), pose_convex, request, collector);
    return;
  }
  const Real cd = request_reach(request);  // the touching rule (contact.hpp)
  const Transform rel = relative(pose_mesh, pose_convex);
  const Aabb box = proxima::detail::visit_convex(convex, [&](const auto& s) {
                     return s.world_aabb(rel);
                   }).inflated(cull_margin(request));
  const Vec3 center_local = box.center();
  // Cosine above which a manifold normal counts as the face normal (about 0.1 degree).
  const Real face_cos = Real(1) - Real(2e-6);
  Scratch& sc = scratch();
  sc.pending.clear();
  sc.voided.clear();
  const auto tris = mesh.triangles();
  // Cheap rejections before the triangle's contact set (each gives the answer an empty
  // manifold would): the shape wholly on one side of the triangle's plane by more than the
  // contact distance plus the narrow phase's tolerance (two support calls; the plane gap is a
  // lower bound of the distance to the triangle); for a box, the 13 separating axes.
  const bool reject_box = convex.type() == ShapeType::Box;
  const Real plane_margin = cd + linear_tolerance(std::max(max_abs_component(box.min), max_abs_component(box.max)) +
                                                  max_abs_component(pose_mesh.position));
  for_each_triangle_near(
      mesh, box,
      [&](std::uint32_t t, const std::array<Vec3, 3>& v, const Triangle& tri) {
        const Vec3 plane_normal = pose_mesh.apply_vector(tri.normal());
        const Vec3 plane_point = pose_mesh.apply(v[0]);
        if (glm::dot(world_support(convex, pose_convex, -plane_normal) - plane_point, plane_normal) > plane_margin ||
            glm::dot(world_support(convex, pose_convex, plane_normal) - plane_point, plane_normal) < -plane_margin)
          return true;
        if (reject_box && triangle_box_separated_beyond(tri, pose_mesh, convex.as<Box>(), pose_convex, cd)) return true;
        const ContactManifold m = collide(tri, pose_mesh, convex, pose_convex, request);
        if (m.count == 0) return true;
        // Face normal turned to the shape's side (the triangle is two-sided).
        const Vec3 n_local = pose_mesh.inverse_apply_vector(m.normal);
        Vec3 f = tri.normal();
        Real side = glm::dot(n_local, f);
        if (std::abs(side) < Real(0.1)) side = glm::dot(center_local - v[0], f);
        if (side < Real(0)) f = -f;
        const bool face = glm::dot(n_local, f) >= face_cos;
        const std::uint8_t active = mesh.active_edges(t);
        const TriangleIndices& idx = tris[t];
        bool corrected = false;  // ghost signed distance along the face normal computed yet
        Real ghost_sd = Real(0);
        Vec3 ghost_n(Real(0));
        for (int i = 0; i < m.count; ++i) {
          ContactPoint c;
          c = m.points[i];
          c.sub_a.triangle = t;
          if (face) {
            collector.add(c);
            sc.voided.insert(sc.voided.end(), idx.begin(), idx.end());
            continue;
          }
          const Feature feat = classify(v, pose_mesh.inverse_apply(c.point_a));
          bool real = true;
          std::uint32_t v0 = 0, v1 = 0;
          if (feat.kind == 1) {
            real = (active >> feat.index) & 1u;
            v0 = idx[static_cast<std::size_t>(feat.index)];
            v1 = idx[static_cast<std::size_t>((feat.index + 1) % 3)];
          } else if (feat.kind == 2) {
            v0 = v1 = idx[static_cast<std::size_t>(feat.index)];
            real = vertex_active(mesh, t, v0);
          }
          if (real) {
            collector.add(c);
            continue;
          }
          // Ghost candidate: normal -> face normal, signed distance along it to the triangle.
          // The side is the one the shape needs the shorter push to clear the plane towards
          // (a narrow-phase normal near the plane does not say which side the shape is on).
          if (!corrected) {
            corrected = true;
            ghost_n = pose_mesh.apply_vector(f);
            const Vec3 p0 = pose_mesh.apply(v[0]);
            Real plane_sd = glm::dot(world_support(convex, pose_convex, -ghost_n) - p0, ghost_n);
            const Real other_sd = -glm::dot(world_support(convex, pose_convex, ghost_n) - p0, ghost_n);
            if (other_sd > plane_sd) {
              ghost_n = -ghost_n;
              plane_sd = other_sd;
            }
            Real sd0 = kInf;
            for (int j = 0; j < m.count; ++j) sd0 = std::min(sd0, -m.points[j].depth);
            if (plane_sd > cd)
              ghost_sd = plane_sd;
            else if (reject_box)  // exact over the 13 axes
              ghost_sd =
                  triangle_box_directional_signed_distance(tri, pose_mesh, convex.as<Box>(), pose_convex, ghost_n);
            else
              ghost_sd = directional_signed_distance(tri, pose_mesh, convex, pose_convex, request, ghost_n, sd0,
                                                     m.normal, plane_sd, cd);
          }
          const Vec3 fw = ghost_n;
          const Real sd = ghost_sd;
          if (sd > cd) continue;
          c.normal = fw;
          c.depth = -sd;
          c.point_b = c.point_a + sd * fw;
          sc.pending.push_back({c, v0, v1});
        }
        return !collector.done();
      },
      [&](std::uint32_t t, const FlatTriangle& flat) {
        // A zero-area triangle has no face and no internal edges: its contacts as they come.
        const ContactManifold m = flat.visit(pose_mesh, [&](ShapeRef part, const Transform& pose_part) {
          return collide(part, pose_part, convex, pose_convex, request);
        });
        for (int i = 0; i < m.count && !collector.done(); ++i) {
          ContactPoint c = m.points[static_cast<std::size_t>(i)];
          c.sub_a.triangle = t;
          collector.add(c);
        }
        return !collector.done();
      });
  if (sc.pending.empty() || collector.done()) return;
  std::sort(sc.voided.begin(), sc.voided.end());
  for (const Scratch::Pending& p : sc.pending) {
    const bool covered = std::binary_search(sc.voided.begin(), sc.voided.end(), p.v0) &&
                         std::binary_search(sc.voided.begin(), sc.voided.end(), p.v1);
    if (!covered) collector.add(p.contact);
    if (collector.done()) return;
  }
}

}  // namespace proxima::narrow
