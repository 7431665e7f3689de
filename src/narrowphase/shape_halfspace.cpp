// Every convex shape against a half-space: the pair routines of pairs_halfspace.hpp, each the
// generic routine of generic_halfspace.hpp (van den Bergen, Collision Detection in Interactive
// 3D Environments, 4.3: support mappings) for its shape, and the closed forms of the generic
// routine's third step, the contact candidates, where a shape's supporting feature would give
// other points or ids, or take longer than the answer.
//
// Steps of the candidate closed forms (A's core, world frame; feature index in brackets):
//  1. segment: its end points a, b [0, 1]; triangle: its vertices a, b, c [0, 1, 2]; capsule:
//     its core ends, bottom and top [0, 1], with its radius, also when they coincide;
//  2. box: its 8 corners [bit i set for the + side on axis i] (a tilted box touches with
//     corners of two faces);
//  3. cylinder: the deepest rim point of each cap [4 * cap + 0] and, on the cap facing the
//     plane, the rim points at 90, 180 and 270 degrees from it [4 * cap + 1..3]: 2 points on
//     its side, 4 standing on a cap; cone: the apex [0], the deepest base rim point [1] and the
//     rim points turned from it [2..4];
//  4. the 4 deepest candidates within contact_distance + tolerance (candidate_manifold),
//     reduced to max_contacts by reduce_contacts;
//  5. convex hull: every vertex within contact_distance + tolerance, streamed through
//     select_contacts (deepest, then the largest area; no copy, no allocation) [vertex
//     index]. O(V) per pass, four passes.
#include <proxima/narrowphase/contact.hpp>

#include <array>
#include <initializer_list>

#include "narrowphase/generic_halfspace.hpp"
#include "narrowphase/manifold_reduction.hpp"
#include "narrowphase/pairs_halfspace.hpp"
#include "shapes/radial.hpp"

namespace proxima::narrow {

namespace detail {

namespace {

/// Up to 8 candidate points with their feature indices.
struct Candidates {
  std::array<Vec3, 8> points;  // left uninitialised beyond count
  std::array<std::uint32_t, 8> index;
  std::size_t count = 0;

  /// Appends a point with its feature index on A.
  void add(const Vec3& p, std::uint32_t i) {
    points[count] = p;
    index[count] = i;
    ++count;
  }

  /// The manifold of these candidates with core radius r.
  ContactManifold manifold(const PlaneQuery& q, Real r, const PairRequest& request) const {
    return candidate_manifold(q, {points.data(), count}, {index.data(), count}, r, request);
  }
};

/// The 4 smallest gaps offered, in increasing order (equal gaps in the order offered), with
/// the index of their candidate.
struct DeepestFour {
  std::array<Real, kMaxContactPoints> gap{};
  std::array<std::size_t, kMaxContactPoints> index{};
  std::size_t count = 0;

  /// Inserts gap g of candidate i when it is among the 4 smallest so far.
  void offer(Real g, std::size_t i) {
    std::size_t j = count;
    for (; j > 0 && gap[j - 1] > g; --j) {
      if (j < gap.size()) {
        gap[j] = gap[j - 1];
        index[j] = index[j - 1];
      }
    }
    if (j < gap.size()) {
      gap[j] = g;
      index[j] = i;
    }
    count = std::min(count + 1, gap.size());
  }
};

/// r times the unit radial direction of u about the z axis (A's frame; (r, 0) on the axis):
/// the deepest rim point of a circle of radius r is (w.x, w.y, z), the points turned from it
/// by 90, 180 and 270 degrees (-w.y, w.x, z), (-w.x, -w.y, z) and (w.y, -w.x, z).
Vec2 rim_offset(const Vec3& u, Real r) {
  Real ux = Real(1);
  Real uy = Real(0);
  static_cast<void>(::proxima::detail::radial_direction(u.x, u.y, ux, uy));
  return {r * ux, r * uy};
}

}  // namespace

ContactManifold candidate_manifold(const PlaneQuery& q, std::span<const Vec3> points,
                                   std::span<const std::uint32_t> ids, Real r, const PairRequest& request) {
  DeepestFour deepest;
  const Real limit = request.contact_distance + q.tolerance;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Real g = q.plane.gap(points[i]) - r;
    if (g <= limit) deepest.offer(g, i);
  }
  if (deepest.count == 0) return manifold_from_distance(q.distance, request);  // rounding: the support point only
  const DistanceResult& d = q.distance;
  std::array<ContactPoint, kMaxContactPoints> all{};
  for (std::size_t k = 0; k < deepest.count; ++k) {
    ContactPoint& p = all[k];
    p.point_a = points[deepest.index[k]] - r * q.plane.n;
    p.point_b = p.point_a - deepest.gap[k] * q.plane.n;
    p.normal = d.normal;
    p.depth = -deepest.gap[k];
    p.feature_id = make_feature_id(FeatureKind::Vertex, ids[deepest.index[k]], FeatureKind::Face, 0);
  }
  ContactManifold m = empty_manifold(d);
  const int kept = static_cast<int>(deepest.count);
  if (kept <= request.max_contacts) {
    std::copy(all.begin(), all.begin() + kept, m.points.begin());
    m.count = kept;
    return m;
  }
  m.count = reduce_contacts(std::span<const ContactPoint>(all.data(), deepest.count), d.normal, request.max_contacts,
                            m.points);
  return m;
}

// Contacts of the listed vertices (local frame, ids 0, 1, ... in order) placed by `pose`,
// each rounded by `radius`.
ContactManifold vertex_contacts(std::initializer_list<Vec3> vertices, const Transform& pose, Real radius,
                                const PlaneQuery& q, const PairRequest& r) {
  Candidates c;
  std::uint32_t id = 0;
  for (const Vec3& v : vertices) c.add(pose.apply(v), id++);
  return c.manifold(q, radius, r);
}

ContactManifold plane_contacts(const Segment& a, const Transform& pose_a, const PlaneQuery& q, const PairRequest& r) {
  return vertex_contacts({a.a(), a.b()}, pose_a, Real(0), q, r);
}

ContactManifold plane_contacts(const Triangle& a, const Transform& pose_a, const PlaneQuery& q, const PairRequest& r) {
  return vertex_contacts({a.a(), a.b(), a.c()}, pose_a, Real(0), q, r);
}

ContactManifold plane_contacts(const Capsule& a, const Transform& pose_a, const PlaneQuery& q, const PairRequest& r) {
  return vertex_contacts({a.bottom(), a.top()}, pose_a, a.radius(), q, r);
}

ContactManifold plane_contacts(const Box& a, const Transform& pose_a, const PlaneQuery& q, const PairRequest& r) {
  Candidates c;
  const Vec3& h = a.half_extents();
  for (std::uint32_t i = 0; i < 8; ++i) {
    const Vec3 v((i & 1u) != 0u ? h.x : -h.x, (i & 2u) != 0u ? h.y : -h.y, (i & 4u) != 0u ? h.z : -h.z);
    c.add(pose_a.apply(v), i);
  }
  return c.manifold(q, Real(0), r);
}

ContactManifold plane_contacts(const Cylinder& a, const Transform& pose_a, const PlaneQuery& q, const PairRequest& r) {
  const Vec3 u = pose_a.inverse_apply_vector(-q.plane.n);
  const Vec2 w = rim_offset(u, a.radius());
  const Real hl = a.half_length();
  const std::uint32_t deep = u.z >= Real(0) ? 1u : 0u;  // the cap facing the plane
  const Real z = deep == 1u ? hl : -hl;
  Candidates c;
  c.add(pose_a.apply(Vec3(w.x, w.y, -hl)), 0);
  c.add(pose_a.apply(Vec3(w.x, w.y, hl)), 4);
  c.add(pose_a.apply(Vec3(-w.y, w.x, z)), 4 * deep + 1);
  c.add(pose_a.apply(Vec3(-w.x, -w.y, z)), 4 * deep + 2);
  c.add(pose_a.apply(Vec3(w.y, -w.x, z)), 4 * deep + 3);
  return c.manifold(q, Real(0), r);
}

ContactManifold plane_contacts(const Cone& a, const Transform& pose_a, const PlaneQuery& q, const PairRequest& r) {
  const Vec2 w = rim_offset(pose_a.inverse_apply_vector(-q.plane.n), a.radius());
  const Real hl = a.half_length();
  Candidates c;
  c.add(pose_a.apply(Vec3(Real(0), Real(0), hl)), 0);
  c.add(pose_a.apply(Vec3(w.x, w.y, -hl)), 1);
  c.add(pose_a.apply(Vec3(-w.y, w.x, -hl)), 2);
  c.add(pose_a.apply(Vec3(-w.x, -w.y, -hl)), 3);
  c.add(pose_a.apply(Vec3(w.y, -w.x, -hl)), 4);
  return c.manifold(q, Real(0), r);
}

ContactManifold plane_contacts(const ConvexHull& a, const Transform& pose_a, const PlaneQuery& q,
                               const PairRequest& r) {
  // Gaps in A's frame: the plane's normal and offset seen from A.
  const WorldPlane& plane = q.plane;
  const Vec3 n_local = pose_a.inverse_apply_vector(plane.n);
  const Real offset_local = plane.offset + glm::dot(plane.n, plane.origin - pose_a.position);
  const std::span<const Vec3> v = a.vertices();
  const Real limit = r.contact_distance + q.tolerance;
  const auto gap = [&](int i) { return glm::dot(n_local, v[static_cast<std::size_t>(i)]) - offset_local; };
  std::array<int, 4> chosen{};
  const int count = select_contacts(
      static_cast<int>(v.size()), [&](int i) { return v[static_cast<std::size_t>(i)]; }, [&](int i) { return -gap(i); },
      [&](int i) { return gap(i) <= limit; }, n_local, r.max_contacts, chosen);
  if (count == 0) return manifold_from_distance(q.distance, r);
  ContactManifold m = empty_manifold(q.distance);
  for (int k = 0; k < count; ++k) {
    const int i = chosen[static_cast<std::size_t>(k)];
    const Real g = gap(i);
    ContactPoint& p = m.points[static_cast<std::size_t>(k)];
    p.point_a = pose_a.apply(v[static_cast<std::size_t>(i)]);
    p.point_b = p.point_a - g * plane.n;
    p.normal = q.distance.normal;
    p.depth = -g;
    p.feature_id = make_feature_id(FeatureKind::Vertex, static_cast<std::uint32_t>(i), FeatureKind::Face, 0);
  }
  m.count = count;
  return m;
}

}  // namespace detail

// The three routines of each pair (A, HalfSpace): the generic routine instantiated for A.
#define PROXIMA_DEFINE_HALFSPACE_PAIR(A)                                                                         \
  bool pair_intersect(const A& a, const Transform& pose_a, const HalfSpace& b, const Transform& pose_b,          \
                      const PairRequest& request, PairCache* /*cache*/) {                                        \
    return detail::halfspace_intersect(a, pose_a, b, pose_b, request);                                           \
  }                                                                                                              \
  DistanceResult pair_distance(const A& a, const Transform& pose_a, const HalfSpace& b, const Transform& pose_b, \
                               const PairRequest& request, PairCache* /*cache*/) {                               \
    return detail::halfspace_distance(a, pose_a, b, pose_b, request);                                            \
  }                                                                                                              \
  ContactManifold pair_collide(const A& a, const Transform& pose_a, const HalfSpace& b, const Transform& pose_b, \
                               const PairRequest& request, PairCache* /*cache*/) {                               \
    return detail::halfspace_collide(a, pose_a, b, pose_b, request);                                             \
  }

PROXIMA_DEFINE_HALFSPACE_PAIR(Point)
PROXIMA_DEFINE_HALFSPACE_PAIR(Segment)
PROXIMA_DEFINE_HALFSPACE_PAIR(Triangle)
PROXIMA_DEFINE_HALFSPACE_PAIR(Sphere)
PROXIMA_DEFINE_HALFSPACE_PAIR(Capsule)
PROXIMA_DEFINE_HALFSPACE_PAIR(Box)
PROXIMA_DEFINE_HALFSPACE_PAIR(Cylinder)
PROXIMA_DEFINE_HALFSPACE_PAIR(Cone)
PROXIMA_DEFINE_HALFSPACE_PAIR(Ellipsoid)
PROXIMA_DEFINE_HALFSPACE_PAIR(ConvexHull)

#undef PROXIMA_DEFINE_HALFSPACE_PAIR

}  // namespace proxima::narrow
