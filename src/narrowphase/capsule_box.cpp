// Capsule against box (Ericson, Real-Time Collision Detection, 5.1.3, 5.2.1 and 5.5).
//
// Steps (in the box frame):
//  1. the capsule's core segment p0p1; its exact closest points to the solid box
//     (detail::closest_segment_box, piecewise quadratic minimisation);
//  2. core apart from the box: normal = (on_box - on_segment) / distance, signed distance =
//     distance - r;
//  3. core touching the box (within the tolerance, where the direction of on_box - on_segment
//     is rounding noise): separating-axis test of segment against box over the 3 face
//     axes and the 3 axes d x e_i (the face normals of their Minkowski difference, so the
//     minimum overlap is the exact core penetration; face axes win ties within tolerance);
//     normal turned from the segment's centre towards the box centre; witnesses: the closest
//     points of the box and of the core moved out along the normal by the overlap (they touch
//     there), the core's point moved back;
//  4. manifold: when the normal n is within kFaceCosine of a face normal, the core is clipped
//     to that face's side planes; each clipped end whose gap (its height over the box's
//     supporting plane along n, minus r; for a face contact its height over the face) is
//     within contact_distance + tolerance is a contact with the pair's normal, so no point is
//     deeper than the pair. Two distinct ends give the two-point manifold of a capsule lying
//     on a face; otherwise the single closest pair.
#include "narrowphase/pairs_rounded.hpp"
#include "narrowphase/rounded_common.hpp"

namespace proxima::narrow {

namespace {

/// A normal within this cosine of a face normal counts as that face's normal for the
/// two-point manifold.
constexpr Real kFaceCosine = Real(0.999);

struct CapsuleBox {
  DistanceResult result;
  Vec3 p0, p1;  ///< core ends, box frame
  Real t = Real(0);
  Real tolerance = Real(0);
  std::uint32_t feature = 0;
};

CapsuleBox capsule_box(const Capsule& a, const Transform& pose_a, const Box& b, const Transform& pose_b,
                       const PairRequest& request) {
  CapsuleBox cb;
  const Vec3& h = b.half_extents();
  cb.p0 = pose_b.inverse_apply(pose_a.apply(a.bottom()));
  cb.p1 = pose_b.inverse_apply(pose_a.apply(a.top()));
  cb.tolerance = resolve_tolerance(
      request, detail::pair_scale(pose_a, pose_b, a.radius() + a.half_length() + max_abs_component(h)));
  const detail::SegmentBoxClosest sb = detail::closest_segment_box(cb.p0, cb.p1, h);
  Vec3 n;
  Real core = Real(0);
  Vec3 on_a = sb.on_segment;
  Vec3 on_b = sb.on_box;
  cb.t = sb.t;
  if (!(unit_and_length(sb.on_box - sb.on_segment, n, core) && core > cb.tolerance)) {
    // The core touches the box: SAT over the face axes and the edge axes d x e_i.
    const Vec3 d = cb.p1 - cb.p0;
    const Vec3 half = Real(0.5) * d;
    const Vec3 mid = cb.p0 + half;
    const Real ld = glm::length(d);
    Real best = std::numeric_limits<Real>::infinity();
    Vec3 axis(Real(0), Real(0), Real(1));
    const auto consider = [&](const Vec3& u, Real bias) {
      const Real overlap = std::abs(u.x) * h.x + std::abs(u.y) * h.y + std::abs(u.z) * h.z +
                           std::abs(glm::dot(u, half)) - std::abs(glm::dot(u, mid));
      if (overlap < best - bias) {
        best = overlap;
        axis = u;
      }
    };
    consider(Vec3(Real(1), Real(0), Real(0)), Real(0));
    consider(Vec3(Real(0), Real(1), Real(0)), Real(0));
    consider(Vec3(Real(0), Real(0), Real(1)), Real(0));
    const Vec3 crosses[3] = {{Real(0), d.z, -d.y}, {-d.z, Real(0), d.x}, {d.y, -d.x, Real(0)}};
    for (const Vec3& c : crosses) {
      Vec3 u;
      Real lc = Real(0);
      if (unit_and_length(c, u, lc) && lc > kSqrtEpsilon * ld) consider(u, cb.tolerance);
    }
    n = glm::dot(axis, mid) > Real(0) ? -axis : axis;
    core = -best;
    // Witnesses: move the core out of the box along -n by the overlap; it then touches the
    // box, and the closest points of the moved core are the contact.
    const Vec3 shift = core * n;
    const detail::SegmentBoxClosest touch = detail::closest_segment_box(cb.p0 + shift, cb.p1 + shift, h);
    cb.t = touch.t;
    on_a = touch.on_segment - shift;
    on_b = touch.on_box;
  }
  FeatureKind ka{};
  FeatureKind kb{};
  std::uint32_t ia = 0;
  std::uint32_t ib = 0;
  detail::capsule_feature(cb.t, ka, ia);
  detail::box_feature(glm::clamp(on_b, -h, h), h, kb, ib);
  cb.feature = make_feature_id(ka, ia, kb, ib);
  cb.result = detail::rounded_result(pose_b.apply(on_a), pose_b.apply(on_b), pose_b.apply_vector(n), core, a.radius(),
                                     Real(0), cb.tolerance);
  return cb;
}

}  // namespace

DistanceResult pair_distance(const Capsule& a, const Transform& pose_a, const Box& b, const Transform& pose_b,
                             const PairRequest& request, PairCache* /*cache*/) {
  if (!poses_in_range(pose_a, pose_b)) return invalid_distance();
  return capsule_box(a, pose_a, b, pose_b, request).result;
}

bool pair_intersect(const Capsule& a, const Transform& pose_a, const Box& b, const Transform& pose_b,
                    const PairRequest& request, PairCache* cache) {
  if (!poses_in_range(pose_a, pose_b)) return false;
  return in_contact(pair_distance(a, pose_a, b, pose_b, request, cache), request);
}

ContactManifold pair_collide(const Capsule& a, const Transform& pose_a, const Box& b, const Transform& pose_b,
                             const PairRequest& request, PairCache* /*cache*/) {
  if (!poses_in_range(pose_a, pose_b)) return invalid_manifold();
  const CapsuleBox cb = capsule_box(a, pose_a, b, pose_b, request);
  ContactManifold m = manifold_from_distance(cb.result, request, cb.feature);
  if (m.count == 0 || request.max_contacts < 2) return m;

  // Face contact: clip the core to the face's four side planes.
  const Vec3& h = b.half_extents();
  const Vec3 n_local = pose_b.inverse_apply_vector(cb.result.normal);
  int axis = 0;
  for (int i = 1; i < 3; ++i) {
    if (std::abs(n_local[i]) > std::abs(n_local[axis])) axis = i;
  }
  if (!(std::abs(n_local[axis]) >= kFaceCosine)) return m;
  const Real side = n_local[axis] > Real(0) ? Real(-1) : Real(1);  // outward normal of the face: side * e_axis
  Real t0 = Real(0);
  Real t1 = Real(1);
  int clipped_by[2] = {-1, -1};
  for (int j = 0, plane = 0; j < 3; ++j) {
    if (j == axis) continue;
    for (const Real s : {Real(1), Real(-1)}) {
      Vec3 m_plane(Real(0));
      m_plane[j] = s;
      const Real old0 = t0;
      const Real old1 = t1;
      if (!detail::clip_segment(cb.p0, cb.p1, m_plane, h[j], t0, t1)) return m;
      if (t0 != old0) clipped_by[0] = plane;
      if (t1 != old1) clipped_by[1] = plane;
      ++plane;
    }
  }
  const Vec3 d = cb.p1 - cb.p0;
  if (!((t1 - t0) * glm::length(d) > cb.tolerance)) return m;
  // Gaps along the pair's own normal (within kFaceCosine of the face's, equal to it for a
  // face contact): the box's supporting plane along -n is at n . x = -(|n| . h), so no core
  // point can be deeper along n than the pair itself (an edge axis d x e_i close to a face
  // axis has a smaller overlap than the face).
  const Vec3& normal = cb.result.normal;
  const Real plane = -(std::abs(n_local.x) * h.x + std::abs(n_local.y) * h.y + std::abs(n_local.z) * h.z);
  const std::uint32_t face = static_cast<std::uint32_t>(2 * axis) + (side > Real(0) ? 1u : 0u);
  ContactManifold two;
  two.normal = normal;
  two.status = cb.result.status;
  two.method = cb.result.method;
  for (int k = 0; k < 2; ++k) {
    const Real t = k == 0 ? t0 : t1;
    const Vec3 p = cb.p0 + t * d;
    const Real gap = plane - glm::dot(n_local, p) - a.radius();
    if (!(gap <= request.contact_distance + cb.tolerance)) continue;
    ContactPoint& c = two.points[static_cast<std::size_t>(two.count++)];
    c.point_a = pose_b.apply(p) + a.radius() * normal;
    c.point_b = c.point_a + gap * normal;
    c.normal = normal;
    c.depth = -gap;
    const int by = clipped_by[k];
    c.feature_id = by < 0 ? make_feature_id(FeatureKind::Vertex, static_cast<std::uint32_t>(k), FeatureKind::Face, face)
                          : make_feature_id(FeatureKind::Edge, static_cast<std::uint32_t>(by), FeatureKind::Face, face);
  }
  if (two.count < 2) return m;
  if (two.points[1].depth > two.points[0].depth) std::swap(two.points[0], two.points[1]);
  // The pair's deepest point must be among them (else the closest points lie elsewhere, e.g.
  // near an edge): otherwise keep the exact single point.
  if (two.points[0].depth < -cb.result.signed_distance - cb.tolerance) return m;
  return two;
}

}  // namespace proxima::narrow
