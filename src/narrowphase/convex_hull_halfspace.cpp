// Convex hull against half-space (van den Bergen, Collision Detection in Interactive 3D
// Environments, 4.3: support mappings; the half-space is n . x <= d in B's frame).
//
// Steps:
//  1. the half-space's plane in world (normal n, offset relative to B's origin);
//  2. the hull's support vertex in the direction -n (hill climbing above
//     ConvexHull::kLinearScanMaxVertices vertices): signed distance n . x - d, normal -n
//     (A to B), point_b the projection on the plane;
//  3. manifold: every vertex whose gap is within contact_distance + tolerance is a candidate;
//     select_contacts streams over the vertices (no copy, no allocation) and keeps the deepest,
//     then the candidates spanning the largest area, at most max_contacts (feature: the
//     vertex index). O(V) per pass, four passes.
#include "narrowphase/halfspace_common.hpp"
#include "narrowphase/pairs_halfspace.hpp"

namespace proxima::narrow {

namespace {

Real tolerance_of(const ConvexHull& a, const Transform& pose_a, const HalfSpace& b, const Transform& pose_b,
                  const PairRequest& request) {
  return detail::halfspace_tolerance(request, pose_a, pose_b, b,
                                     max_abs_component(a.local_aabb().max - a.local_aabb().min) +
                                         max_abs_component(a.local_aabb().max) + max_abs_component(a.local_aabb().min));
}

}  // namespace

DistanceResult pair_distance(const ConvexHull& a, const Transform& pose_a, const HalfSpace& b, const Transform& pose_b,
                             const PairRequest& request, PairCache* /*cache*/) {
  if (!finite_poses(pose_a, pose_b)) return invalid_distance();
  return detail::halfspace_distance(a, pose_a, b, pose_b, tolerance_of(a, pose_a, b, pose_b, request));
}

bool pair_intersect(const ConvexHull& a, const Transform& pose_a, const HalfSpace& b, const Transform& pose_b,
                    const PairRequest& request, PairCache* cache) {
  if (!finite_poses(pose_a, pose_b)) return false;
  return pair_distance(a, pose_a, b, pose_b, request, cache).signed_distance <= request.contact_distance;
}

ContactManifold pair_collide(const ConvexHull& a, const Transform& pose_a, const HalfSpace& b, const Transform& pose_b,
                             const PairRequest& request, PairCache* /*cache*/) {
  if (!finite_poses(pose_a, pose_b)) return invalid_manifold();
  const Real tol = tolerance_of(a, pose_a, b, pose_b, request);
  const DistanceResult d = detail::halfspace_distance(a, pose_a, b, pose_b, tol);
  ContactManifold m;
  m.normal = d.normal;
  m.status = d.status;
  m.method = d.method;
  if (!(d.signed_distance <= request.contact_distance) || request.max_contacts < 1) return m;

  // Gaps in A's frame: the plane's normal and offset seen from A.
  const detail::WorldPlane plane = detail::world_plane(b, pose_b);
  const Vec3 n_local = pose_a.inverse_apply_vector(plane.n);
  const Real offset_local = plane.offset + glm::dot(plane.n, plane.origin - pose_a.position);
  const std::span<const Vec3> v = a.vertices();
  const Real limit = request.contact_distance + tol;
  const auto gap = [&](int i) { return glm::dot(n_local, v[static_cast<std::size_t>(i)]) - offset_local; };
  std::array<int, 4> chosen{};
  const int count = select_contacts(
      static_cast<int>(v.size()), [&](int i) { return v[static_cast<std::size_t>(i)]; }, [&](int i) { return -gap(i); },
      [&](int i) { return gap(i) <= limit; }, n_local, request.max_contacts, chosen);
  if (count == 0) return manifold_from_distance(d, request);
  for (int k = 0; k < count; ++k) {
    const int i = chosen[static_cast<std::size_t>(k)];
    const Real g = gap(i);
    ContactPoint& p = m.points[static_cast<std::size_t>(k)];
    p.point_a = pose_a.apply(v[static_cast<std::size_t>(i)]);
    p.point_b = p.point_a - g * plane.n;
    p.normal = d.normal;
    p.depth = -g;
    p.feature_id = make_feature_id(FeatureKind::Vertex, static_cast<std::uint32_t>(i), FeatureKind::Face, 0);
  }
  m.count = count;
  return m;
}

}  // namespace proxima::narrow
