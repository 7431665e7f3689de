/// @file compound_pairs.cpp
/// A compound against any shape, and the reduction of a composite pair's contacts to one
/// manifold.
///
/// Steps:
///  1. A compound against a non-compound: the other side's box is mapped into the compound's
///     frame; the compound's BVH is walked for the children whose boxes overlap it (inflated
///     by the contact distance), each child answered at its pose through the dispatch table
///     (nested compounds included) and tagged with its top-level child index. Distance walks
///     the BVH nearer node first and prunes nodes whose box gap is not below the best answer
///     (branch and bound; the best so far is passed down as a cutoff, so nested parts prune
///     against the global best).
///  2. Compound against compound (boolean, contacts): simultaneous descent of both BVHs over
///     node pairs (spatial/bvh_pair_descent.hpp; B's node box mapped into A's frame, Arvo's
///     box of a rotated box), the larger node split first; leaf pairs recurse on child pairs. Distance
///     descends A's BVH and answers each child against B (which descends B's BVH), sharing
///     the cutoff.
///  3. The manifold of a composite pair: collide_all, then the deepest contact's normal
///     becomes the manifold normal; contacts whose normal is within about 26 degrees of it
///     (cosine >= 0.9) are candidates, their depths projected on that normal (point_b moved
///     to keep point_b = point_a - depth * normal), and narrow::reduce_contacts keeps at most
///     max_contacts of them: deepest, farthest from it, largest triangle, largest
///     quadrilateral (Gregorius, GDC 2015). Feature ids are mixed with the sub-shape ids so
///     that points from different parts keep distinct ids.

#include "compound_pairs.hpp"

#include <proxima/core/tolerance.hpp>
#include <proxima/narrowphase/narrowphase.hpp>
#include <proxima/shapes/shape_queries.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <span>
#include <vector>

#include "collector_adapters.hpp"
#include "dispatch.hpp"
#include "manifold_reduction.hpp"
#include "pair_support.hpp"
#include "shapes/shape_visit.hpp"
#include "spatial/bvh_pair_descent.hpp"

namespace proxima::narrow {
namespace {

/// The node test of two compounds' hierarchies for spatial::descend_bvh_pairs: A's node
/// boxes inflated by the margin against B's mapped into A's frame (Arvo's box of a rotated
/// box); node size = surface area.
struct CompoundNodes {
  std::span<const BvhNode> na;
  std::span<const BvhNode> nb;
  Transform rel;  ///< B's frame seen from A's

  Aabb fix_a(std::uint32_t i) const { return na[i].bounds(); }
  Aabb fix_b(std::uint32_t j) const { return nb[j].bounds().transformed(rel); }
  bool overlap(std::uint32_t i, const Aabb& b, Real margin) const {
    return na[i].bounds().inflated(margin).overlaps(b);
  }
  bool overlap(const Aabb& a, std::uint32_t j, Real margin) const { return a.inflated(margin).overlaps(fix_b(j)); }
  Real size_a(std::uint32_t i) const { return na[i].bounds().surface_area(); }
  Real size_b(std::uint32_t j) const { return nb[j].bounds().surface_area(); }
};

/// Calls leaf(i, j) for every pair of children of A and B whose BVH leaves overlap (A's boxes
/// inflated by `margin`). leaf returns false to stop; returns false when stopped.
template <class Leaf>
bool pair_descent(const Compound& a, const Transform& pose_a, const Compound& b, const Transform& pose_b, Real margin,
                  Leaf&& leaf) {
  const auto pa = a.bvh().primitives(), pb = b.bvh().primitives();
  const CompoundNodes nodes{a.bvh().nodes(), b.bvh().nodes(), relative(pose_a, pose_b)};
  return spatial::descend_bvh_pairs(a.bvh(), b.bvh(), nodes, margin, [&](const BvhNode& x, const BvhNode& y) {
    for (std::uint32_t s = x.first; s != x.first + x.count; ++s)
      for (std::uint32_t t = y.first; t != y.first + y.count; ++t)
        if (!leaf(pa[s], pb[t])) return false;
    return true;
  });
}

std::uint32_t mix_sub_ids(const ContactPoint& c) {
  std::uint32_t h = 0x811c9dc5u;
  for (std::uint32_t x : {c.sub_a.child, c.sub_a.triangle, c.sub_b.child, c.sub_b.triangle}) h = (h ^ x) * 0x01000193u;
  return h;
}

}  // namespace

namespace {

/// Largest |world coordinate| of a placed shape's box (a half-space: of its position).
Real world_extent(ShapeRef s, const Transform& pose) {
  if (s.type() == ShapeType::HalfSpace) return max_abs_component(pose.position);
  const Aabb box = world_aabb(s, pose);
  return std::max(max_abs_component(box.min), max_abs_component(box.max));
}

}  // namespace

PairRequest composite_request(ShapeRef a, const Transform& pose_a, ShapeRef b, const Transform& pose_b,
                              const PairRequest& request) {
  if (request.tolerance > Real(0)) return request;
  PairRequest r = request;
  r.tolerance = linear_tolerance(std::max(world_extent(a, pose_a), world_extent(b, pose_b)));
  return r;
}

DistanceResult distance_below(ShapeRef a, const Transform& pose_a, ShapeRef b, const Transform& pose_b,
                              const PairRequest& request, Real cutoff) {
  return pair_functions(a.type(), b.type()).distance(a.data(), pose_a, b.data(), pose_b, request, nullptr, cutoff);
}

bool compound_intersect(const Compound& a, const Transform& pa, ShapeRef b, const Transform& pb, const PairRequest& req,
                        PartHint* hint) {
  const auto kids = a.children();
  if (b.type() == ShapeType::Compound) {
    const auto kb = b.as<Compound>().children();
    // B's part first, as compound_distance meets the pair (A's part against compound B is
    // B's descent against A's part): at exactly the contact distance both compute the same
    // number in the same frame.
    const auto touch = [&](std::uint32_t i, std::uint32_t j) {
      return intersect(kb[j].shape, pb * kb[j].pose, kids[i].shape, pa * kids[i].pose, req);
    };
    if (hint != nullptr && hint->a < kids.size() && hint->b < kb.size() && touch(hint->a, hint->b)) return true;
    bool hit = false;
    pair_descent(a, pa, b.as<Compound>(), pb, cull_margin(req), [&](std::uint32_t i, std::uint32_t j) {
      hit = touch(i, j);
      if (hit && hint != nullptr) *hint = {i, j};
      return !hit;
    });
    return hit;
  }
  const auto touch = [&](std::uint32_t i) { return intersect(kids[i].shape, pa * kids[i].pose, b, pb, req); };
  if (hint != nullptr && hint->a < kids.size() && touch(hint->a)) return true;
  const Aabb box = world_aabb(b, relative(pa, pb)).inflated(cull_margin(req));
  bool hit = false;
  a.bvh().traverse([&](const BvhNode& n) { return n.bounds().overlaps(box); },
                   [&](std::uint32_t i) {
                     hit = touch(i);
                     if (hit && hint != nullptr) *hint = {i, kNoIndex};
                     return !hit;
                   });
  return hit;
}

DistanceResult compound_distance(const Compound& a, const Transform& pa, ShapeRef b, const Transform& pb,
                                 const PairRequest& req, Real cutoff, PartHint* hint) {
  DistanceResult best;
  best.signed_distance = std::numeric_limits<Real>::infinity();
  Real bound = cutoff;
  const auto kids = a.children();
  const auto answer = [&](std::uint32_t i) {
    const DistanceResult d = distance_below(kids[i].shape, pa * kids[i].pose, b, pb, req, bound);
    if (d.signed_distance < bound || (d.signed_distance == bound && i < best.sub_a.child)) {
      best = d;
      best.sub_a.child = i;
      bound = d.signed_distance;
    }
  };
  const std::uint32_t first = hint != nullptr && hint->a < kids.size() ? hint->a : kNoIndex;
  if (first != kNoIndex) answer(first);
  const Aabb box = world_aabb(b, relative(pa, pb));
  a.bvh().traverse_nearest([&](const Aabb& node) { return proxima::detail::aabb_gap(node, box); }, bound,
                           [&](std::uint32_t i) {
                             if (i != first) answer(i);
                           });
  if (hint != nullptr)
    *hint = {best.sub_a.child, b.type() == ShapeType::Compound ? best.sub_b.child : best.sub_b.triangle};
  return best;
}

void compound_collide_all(const Compound& a, const Transform& pa, ShapeRef b, const Transform& pb,
                          const PairRequest& req, ContactCollector& collector) {
  const auto kids = a.children();
  if (b.type() == ShapeType::Compound) {
    const auto kb = b.as<Compound>().children();
    pair_descent(a, pa, b.as<Compound>(), pb, cull_margin(req), [&](std::uint32_t i, std::uint32_t j) {
      // B's part first, as in compound_intersect and compound_distance, mirrored back.
      ChildPairCollector tagged(collector, i, j);
      MirroredCollector b_first(tagged);
      collide_all(kb[j].shape, pb * kb[j].pose, kids[i].shape, pa * kids[i].pose, req, b_first);
      return !collector.done();
    });
    return;
  }
  const Aabb box = world_aabb(b, relative(pa, pb)).inflated(cull_margin(req));
  a.bvh().traverse([&](const BvhNode& n) { return n.bounds().overlaps(box); },
                   [&](std::uint32_t i) {
                     ChildOfACollector tagged(collector, i);
                     collide_all(kids[i].shape, pa * kids[i].pose, b, pb, req, tagged);
                     return !collector.done();
                   });
}

ContactManifold reduced_manifold(ShapeRef a, const Transform& pose_a, ShapeRef b, const Transform& pose_b,
                                 const PairRequest& request) {
  // Per-thread scratch, reserved on a thread's first use: a step on a pool hands each pair
  // to whichever thread is free, so growing to each thread's largest manifold so far would
  // allocate at random steps (seen: WorldAllocations.SteadyStateStepAllocatesNothingOnAPool).
  constexpr std::size_t kReserved = 512;
  thread_local ContactVector all;
  thread_local std::vector<ContactPoint> candidates;
  if (all.contacts.capacity() < kReserved) {
    all.contacts.reserve(kReserved);
    candidates.reserve(kReserved);
  }
  all.contacts.clear();
  candidates.clear();
  collide_all(a, pose_a, b, pose_b, request, all);
  ContactManifold m;
  const std::vector<ContactPoint>& found = all.contacts;
  if (found.empty()) return m;
  std::size_t deepest = 0;
  for (std::size_t k = 1; k < found.size(); ++k)
    if (found[k].depth > found[deepest].depth) deepest = k;
  const Vec3 n = found[deepest].normal;
  for (const ContactPoint& c : found) {
    const Real cosine = glm::dot(c.normal, n);
    if (cosine < Real(0.9)) continue;
    ContactPoint p = c;
    p.depth = c.depth * cosine;
    p.normal = n;
    p.point_b = p.point_a - p.depth * n;
    p.feature_id ^= mix_sub_ids(c);
    candidates.push_back(p);
  }
  m.count = reduce_contacts(candidates, n, std::clamp(request.max_contacts, 1, kMaxContactPoints), m.points);
  m.normal = n;
  const ContactPoint& top = m.points[0];
  m.status = status_from_distance(-top.depth, composite_request(a, pose_a, b, pose_b, request).tolerance);
  m.method = PairMethod::Analytic;
  return m;
}

}  // namespace proxima::narrow
