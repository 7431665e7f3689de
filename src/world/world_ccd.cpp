// Continuous detection in the world's step: the fast objects' first impacts and the
// sensors they cross.
//
// Steps, for each object moved since the last step (by index), moving, with a CcdMode other
// than Off:
//   1. its motion runs from its pose at the last step to its pose now (ccd/motion.hpp); it
//      is fast when |displacement| + angle * radius exceeds the safety factor times its
//      thinnest extent (radius: its farthest point from its origin);
//   2. its swept box: the union of its boxes at both ends, padded by radius * angle / 2 (a
//      point turning by angle at distance r leaves the chord by r (1 - cos(angle / 2)) <=
//      r angle / 2) and by the contact distance;
//   3. the broad phase's proxies meeting the swept box, expanded to objects, filtered as in
//      the step (Impl::may_pair); Auto keeps the static ones, Bullet every one (a moving one
//      with its own motion over the step);
//   4. the certified time of impact (ccd/time_of_impact.hpp) against each, at the contact
//      distance: the earliest hit of a non-sensor object is the impact (ties: lower index);
//      a sensor hit while the pair overlaps neither before nor after the step gets enter and
//      exit events (the object crossed it within the step).
#include "world/world_ccd.hpp"

#include <proxima/ccd/time_of_impact.hpp>
#include <proxima/shapes/shape_queries.hpp>

#include <algorithm>
#include <cmath>

namespace proxima::detail {

namespace {

using Impl = CollisionWorld::Impl;

/// The pair state of (i, j) in the step's table, or nullptr.
const PairState* find_pair(const Impl& w, std::uint32_t i, std::uint32_t j) {
  const std::uint64_t key = pair_key(i, j);
  const auto it = std::lower_bound(w.pairs.begin(), w.pairs.end(), key,
                                   [](const PairState& s, std::uint64_t k) { return s.key() < k; });
  return it != w.pairs.end() && it->key() == key ? &*it : nullptr;
}

Motion motion_of(const ObjectSlot& s) { return s.moved ? Motion{s.step_pose, s.pose} : Motion::stationary(s.pose); }

/// Steps 2-3: the objects that object i may reach during its motion.
void sweep_candidates(const Impl& w, const CollisionWorld& world, std::uint32_t i, const Motion& motion,
                      std::vector<std::uint32_t>& out) {
  const ObjectSlot& s = w.slots[i];
  const Aabb start = world_aabb(s.geometry, motion.start);
  const Real pad = s.radius * motion.rotation_angle() * Real(0.5) + w.settings.contact_distance;
  Aabb swept{glm::min(start.min, s.box.min), glm::max(start.max, s.box.max)};
  swept = proxy_box(swept, pad);
  out.clear();
  std::vector<std::uint32_t> roots;
  w.broadphase->query_aabb(swept, [&](ProxyId id) {
    roots.push_back(id);
    return true;
  });
  std::sort(roots.begin(), roots.end());
  for (std::uint32_t r : roots) {
    w.for_each_member(r, [&](std::uint32_t j) {
      if (j == i || !w.may_pair(world, i, j)) return;
      if (s.ccd == CcdMode::Auto && w.slots[j].kind != ObjectKind::Static) return;
      out.push_back(j);
    });
  }
  std::sort(out.begin(), out.end());
}

}  // namespace

bool is_fast(const ObjectSlot& s, const Motion& motion, Real safety_factor) {
  const Real travel = glm::length(motion.displacement()) + motion.rotation_angle() * s.radius;
  return travel > safety_factor * s.min_extent;
}

void continuous_pass(Impl& w, const CollisionWorld& world) {
  // By index (the moved list is in call order; usually already sorted).
  std::vector<std::uint32_t> sorted;
  const std::vector<std::uint32_t>* order = &w.moved;
  if (!std::is_sorted(w.moved.begin(), w.moved.end())) {
    sorted = w.moved;
    std::sort(sorted.begin(), sorted.end());
    order = &sorted;
  }
  const std::vector<std::uint32_t>& moved = *order;
  ToiOptions options;
  options.target_distance = w.settings.contact_distance;
  if (w.settings.ccd_tolerance > 0) options.tolerance = w.settings.ccd_tolerance;
  std::vector<std::uint32_t> candidates;
  for (std::uint32_t i : moved) {
    const ObjectSlot& s = w.slots[i];
    if (!s.alive || s.kind != ObjectKind::Moving || s.ccd == CcdMode::Off || s.sensor) continue;
    const Motion motion{s.step_pose, s.pose};
    if (!is_fast(s, motion, w.settings.ccd_safety_factor)) continue;
    sweep_candidates(w, world, i, motion, candidates);
    ImpactEvent best;
    bool found = false;
    for (std::uint32_t j : candidates) {
      const ObjectSlot& o = w.slots[j];
      const Result<ToiResult> r = time_of_impact(s.geometry, motion, o.geometry, motion_of(o), options);
      if (!r.ok() || r->status != CcdStatus::Hit) continue;
      if (o.sensor) {
        const PairState* p = find_pair(w, i, j);
        if (p == nullptr || (!p->touching && !p->was_touching)) {
          const ObjectHandle hs = o.handle(j), ho = s.handle(i);
          w.events.sensor_enter.push_back({hs, ho, o.user_data, s.user_data});
          w.events.sensor_exit.push_back({hs, ho, o.user_data, s.user_data});
        }
        continue;
      }
      if (found && r->toi >= best.toi) continue;
      found = true;
      best = ImpactEvent{s.handle(i), o.handle(j), r->toi,      r->point,   r->normal,
                         r->sub_a,    r->sub_b,    s.user_data, o.user_data};
    }
    if (found) w.events.impacts.push_back(best);
  }
}

}  // namespace proxima::detail
