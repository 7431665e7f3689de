/// @file narrowphase.cpp
/// The 2D queries on Shapes: convex pairs to the core algorithms, chain sides segment by
/// segment (segments whose rectangle is out of reach skipped), mirrored where B is the chain.

#include <proxima/d2/narrowphase.hpp>

namespace proxima::d2 {
namespace {

/// The rectangle of `other` in the chain's frame grown by `reach`.
Aabb reach_in_chain_frame(const Pose& chain_pose, const Shape& other, const Pose& other_pose, Real reach) {
  return other.world_aabb(relative(chain_pose, other_pose)).inflated(reach);
}

/// Calls f(segment index, segment) for the chain's segments whose rectangle meets `reach`.
template <class F>
void for_segments_near(const Chain& chain, const Aabb& reach, F&& f) {
  for (int i = 0; i < chain.segment_count(); ++i) {
    const ChainSegment s = chain.segment(i);
    Aabb box;
    box.grow(s.a);
    box.grow(s.b);
    if (overlap(box, reach)) f(i, s);
  }
}

/// Distance from chain A to B (convex or chain): the nearest segment pair (two-sided).
DistanceResult chain_distance(const Chain& chain, const Pose& pose_a, const Shape& b, const Pose& pose_b) {
  DistanceResult best;
  best.signed_distance = std::numeric_limits<Real>::infinity();
  const auto offer = [&](DistanceResult r, PartIndex part_a, PartIndex part_b) {
    r.part_a = part_a;
    r.part_b = part_b;
    if (r.signed_distance < best.signed_distance) best = r;
  };
  for (int i = 0; i < chain.segment_count(); ++i) {
    const ConvexCore segment = chain.segment(i).core();
    if (b.is_convex()) {
      offer(core_distance(segment, pose_a, b.core(), pose_b), i, -1);
      continue;
    }
    const Chain& other = b.chain();
    for (int j = 0; j < other.segment_count(); ++j)
      offer(core_distance(segment, pose_a, other.segment(j).core(), pose_b), i, j);
  }
  return best;
}

/// Manifolds of chain A against B, one per touching segment, appended to out.
int chain_manifolds(const Chain& chain, const Pose& pose_a, const Shape& b, const Pose& pose_b, Real contact_distance,
                    std::vector<Manifold>* out, Manifold* deepest) {
  int found = 0;
  Real deepest_depth = -std::numeric_limits<Real>::infinity();
  const Aabb reach = reach_in_chain_frame(pose_a, b, pose_b, contact_distance);
  for_segments_near(chain, reach, [&](int i, const ChainSegment& s) {
    const auto add = [&](Manifold m, PartIndex part_b) {
      if (m.count == 0) return;
      m.part_a = i;
      m.part_b = part_b;
      ++found;
      for (int k = 0; k < m.count; ++k) {
        if (m.points[k].depth > deepest_depth && deepest != nullptr) deepest_depth = m.points[k].depth, *deepest = m;
      }
      if (out != nullptr) out->push_back(m);
    };
    if (b.is_convex()) {
      add(chain_segment_manifold(s, pose_a, b.core(), pose_b, contact_distance), -1);
      return;
    }
    const Chain& other = b.chain();
    for (int j = 0; j < other.segment_count(); ++j)
      add(chain_segment_manifold(s, pose_a, other.segment(j).core(), pose_b, contact_distance), j);
  });
  return found;
}

}  // namespace

DistanceResult distance(const Shape& a, const Pose& pose_a, const Shape& b, const Pose& pose_b) {
  if (!a.is_convex()) return chain_distance(a.chain(), pose_a, b, pose_b);
  if (!b.is_convex()) return mirrored(chain_distance(b.chain(), pose_b, a, pose_a));
  return core_distance(a.core(), pose_a, b.core(), pose_b);
}

bool intersect(const Shape& a, const Pose& pose_a, const Shape& b, const Pose& pose_b) {
  const DistanceResult r = distance(a, pose_a, b, pose_b);
  return r.status != PairStatus::InvalidInput && r.status != PairStatus::Separated;
}

Manifold collide(const Shape& a, const Pose& pose_a, const Shape& b, const Pose& pose_b, Real contact_distance) {
  if (!a.is_convex()) {
    Manifold deepest;
    chain_manifolds(a.chain(), pose_a, b, pose_b, contact_distance, nullptr, &deepest);
    return deepest;
  }
  if (!b.is_convex()) return mirrored(collide(b, pose_b, a, pose_a, contact_distance));
  return core_manifold(a.core(), pose_a, b.core(), pose_b, contact_distance);
}

int collide_all(const Shape& a, const Pose& pose_a, const Shape& b, const Pose& pose_b, Real contact_distance,
                std::vector<Manifold>& out) {
  if (!a.is_convex()) return chain_manifolds(a.chain(), pose_a, b, pose_b, contact_distance, &out, nullptr);
  if (!b.is_convex()) {
    const std::size_t first = out.size();
    const int n = chain_manifolds(b.chain(), pose_b, a, pose_a, contact_distance, &out, nullptr);
    for (std::size_t i = first; i < out.size(); ++i) out[i] = mirrored(out[i]);
    return n;
  }
  const Manifold m = collide(a, pose_a, b, pose_b, contact_distance);
  if (m.count == 0) return 0;
  out.push_back(m);
  return 1;
}

std::optional<RayHit> raycast(const Shape& shape, const Pose& pose, const Ray& ray, Real max_t) {
  if (shape.is_convex()) return core_raycast(shape.core(), pose, ray, max_t);
  std::optional<RayHit> best;
  const Chain& chain = shape.chain();
  for (int i = 0; i < chain.segment_count(); ++i) {
    auto hit = chain_segment_raycast(chain.segment(i), pose, ray, best ? best->t : max_t);
    if (hit && (!best || hit->t < best->t)) best = hit, best->part = i;
  }
  return best;
}

bool contains(const Shape& shape, const Pose& pose, const Vec2& point) {
  return shape.is_convex() && core_contains(shape.core(), pose, point);
}

SurfacePoint closest_point(const Shape& shape, const Pose& pose, const Vec2& point) {
  if (shape.is_convex()) return core_closest_point(shape.core(), pose, point);
  SurfacePoint best;
  best.signed_distance = std::numeric_limits<Real>::infinity();
  const Chain& chain = shape.chain();
  for (int i = 0; i < chain.segment_count(); ++i) {
    const SurfacePoint s = core_closest_point(chain.segment(i).core(), pose, point);
    if (std::abs(s.signed_distance) < best.signed_distance)
      best = s, best.signed_distance = std::abs(s.signed_distance);
  }
  return best;
}

}  // namespace proxima::d2
