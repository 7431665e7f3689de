// Segment against segment (Ericson, Real-Time Collision Detection, 5.1.9): the capsule pair
// with both radii 0 (core_segment_pair.hpp).
//
// Steps:
//  1. both segments in world; their closest points;
//  2. apart: normal = (on_b - on_a) / |on_b - on_a|, distance |on_b - on_a|;
//  3. touching or crossing (within the tolerance): distance 0 (segments have no interior)
//     along the common normal dA x dB; parallel (collinear or coplanar overlapping) segments
//     take a direction orthogonal to both, derived from A's local +x axis, so that moving B
//     along the normal separates them; turned towards B's origin;
//  4. manifold: the ends of the overlap of parallel segments (two points), else one.
#include "narrowphase/core_segment_pair.hpp"
#include "narrowphase/pairs_rounded.hpp"
#include "narrowphase/rounded_common.hpp"

namespace proxima::narrow {

namespace {

Real segment_pair_tolerance(const Segment& a, const Transform& pose_a, const Segment& b, const Transform& pose_b,
                            const PairRequest& request) {
  const Real size = std::max(
      {max_abs_component(a.a()), max_abs_component(a.b()), max_abs_component(b.a()), max_abs_component(b.b())});
  return resolve_tolerance(request, detail::pair_scale(pose_a, pose_b, size));
}

detail::CoreSegmentPair segment_segment(const Segment& a, const Transform& pose_a, const Segment& b,
                                        const Transform& pose_b, const PairRequest& request) {
  return detail::core_segment_pair(pose_a.apply(a.a()), pose_a.apply(a.b()), pose_b.apply(b.a()), pose_b.apply(b.b()),
                                   Real(0), Real(0), pose_a.rotation, pose_b.rotation,
                                   pose_b.position - pose_a.position,
                                   segment_pair_tolerance(a, pose_a, b, pose_b, request));
}

}  // namespace

DistanceResult pair_distance(const Segment& a, const Transform& pose_a, const Segment& b, const Transform& pose_b,
                             const PairRequest& request, PairCache* /*cache*/) {
  if (!poses_in_range(pose_a, pose_b)) return invalid_distance();
  return segment_segment(a, pose_a, b, pose_b, request).result;
}

bool pair_intersect(const Segment& a, const Transform& pose_a, const Segment& b, const Transform& pose_b,
                    const PairRequest& request, PairCache* /*cache*/) {
  if (!poses_in_range(pose_a, pose_b)) return false;
  return detail::core_segments_within(
      pose_a.apply(a.a()), pose_a.apply(a.b()), pose_b.apply(b.a()), pose_b.apply(b.b()), Real(0), Real(0),
      request.contact_distance, segment_pair_tolerance(a, pose_a, b, pose_b, request),
      [&] { return in_contact(pair_distance(a, pose_a, b, pose_b, request, nullptr), request); });
}

ContactManifold pair_collide(const Segment& a, const Transform& pose_a, const Segment& b, const Transform& pose_b,
                             const PairRequest& request, PairCache* /*cache*/) {
  if (!poses_in_range(pose_a, pose_b)) return invalid_manifold();
  return detail::core_segment_manifold(segment_segment(a, pose_a, b, pose_b, request), Real(0), Real(0), request);
}

}  // namespace proxima::narrow
