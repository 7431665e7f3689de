// Capsule against capsule (Ericson, Real-Time Collision Detection, 4.5.1 and 5.1.9).
//
// Steps:
//  1. both core segments in world; their closest points and the contact normal
//     (core_segment_pair.hpp: robust for parallel and zero-length segments);
//  2. cores apart beyond rounding: the offset between the closest points from the cores'
//     geometry (core_offset: the common normal where both points are inside the cores,
//     across a core where one is), normal = offset / |offset|, signed distance = |offset| -
//     both radii;
//  3. cores crossing (apart by their coordinates' rounding only, where the direction of
//     on_b - on_a is noise): the Minkowski difference of two segments is flat, so the exact
//     penetration of the capsules is ra + rb along the common normal dA x dB (turned towards
//     B's centre); parallel or zero-length cores take A's local +x axis (B's when A is a
//     point), which is orthogonal to the core, turned the same way;
//  4. manifold: when both cores have length and are parallel within kCoreParallelSine, the
//     overlap of B's projection on A's axis gives two points (its ends), each kept when its
//     gap is within contact_distance + tolerance; else the single closest pair.
// intersect compares the squared core distance with (contact distance + radii)^2 directly.
#include "narrowphase/core_segment_pair.hpp"
#include "narrowphase/pairs_rounded.hpp"
#include "narrowphase/rounded_common.hpp"

namespace proxima::narrow {

namespace {

Real capsule_pair_tolerance(const Capsule& a, const Transform& pose_a, const Capsule& b, const Transform& pose_b,
                            const PairRequest& request) {
  return resolve_tolerance(
      request, detail::pair_scale(pose_a, pose_b, a.radius() + b.radius() + a.half_length() + b.half_length()));
}

// Flattened: every call inside inlined (the pose rotations and helpers had become calls
// when the translation unit grew; 10 % of a capsule pair's distance).
[[gnu::flatten]] detail::CoreSegmentPair capsule_capsule(const Capsule& a, const Transform& pose_a, const Capsule& b,
                                                         const Transform& pose_b, const PairRequest& request) {
  // The core's half axis rotated once: pose.apply(bottom()) is the centre less it, bit for
  // bit (a rotation of -v is minus the rotation of v in floating point).
  const Vec3 ha = pose_a.apply_vector(a.top());
  const Vec3 hb = pose_b.apply_vector(b.top());
  return detail::core_segment_pair(pose_a.position - ha, pose_a.position + ha, pose_b.position - hb,
                                   pose_b.position + hb, a.radius(), b.radius(), pose_a.rotation, pose_b.rotation,
                                   pose_b.position - pose_a.position,
                                   capsule_pair_tolerance(a, pose_a, b, pose_b, request));
}

}  // namespace

DistanceResult pair_distance(const Capsule& a, const Transform& pose_a, const Capsule& b, const Transform& pose_b,
                             const PairRequest& request, PairCache* /*cache*/) {
  if (!poses_in_range(pose_a, pose_b)) return invalid_distance();
  return capsule_capsule(a, pose_a, b, pose_b, request).result;
}

bool pair_intersect(const Capsule& a, const Transform& pose_a, const Capsule& b, const Transform& pose_b,
                    const PairRequest& request, PairCache* /*cache*/) {
  if (!poses_in_range(pose_a, pose_b)) return false;
  const Vec3 ha = pose_a.apply_vector(a.top());
  const Vec3 hb = pose_b.apply_vector(b.top());
  return detail::core_segments_within(
      pose_a.position - ha, pose_a.position + ha, pose_b.position - hb, pose_b.position + hb, a.radius(), b.radius(),
      request.contact_distance, capsule_pair_tolerance(a, pose_a, b, pose_b, request),
      [&] { return in_contact(pair_distance(a, pose_a, b, pose_b, request, nullptr), request); });
}

ContactManifold pair_collide(const Capsule& a, const Transform& pose_a, const Capsule& b, const Transform& pose_b,
                             const PairRequest& request, PairCache* /*cache*/) {
  if (!poses_in_range(pose_a, pose_b)) return invalid_manifold();
  return detail::core_segment_manifold(capsule_capsule(a, pose_a, b, pose_b, request), a.radius(), b.radius(), request);
}

}  // namespace proxima::narrow
