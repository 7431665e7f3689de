// Continuous detection in the world's step: the fast objects' first impacts and the
// sensors they cross.
//
// Steps:
//   1. the fast objects, by index: moved since the last step, moving, with a CcdMode other
//      than Off, not sensors; fast when |displacement| + angle * radius exceeds the safety
//      factor times the thinnest extent (the motion runs from the pose at the last step to
//      the pose now, ccd/motion.hpp; radius: the farthest point from the origin);
//   2. the fast objects cut into blocks of consecutive indices, swept on the executor, each
//      block writing only its own CcdChunk (the world is only read):
//      a. the swept box: the union of the boxes at both ends, padded by radius * angle / 2 (a
//         point turning by angle at distance r leaves the chord by r (1 - cos(angle / 2)) <=
//         r angle / 2) and by the contact distance;
//      b. the broad phase's proxies meeting the swept box, expanded to objects, filtered as
//         in the step (Impl::may_pair); Auto keeps the static ones, Bullet every one (a
//         moving one with its own motion over the step);
//      c. the certified time of impact (ccd/time_of_impact.hpp) against each, at the contact
//         distance: the earliest hit of a non-sensor object is the impact (ties: lower
//         index); a sensor hit while the pair overlaps neither before nor after the step
//         gets enter and exit events (the object crossed it within the step);
//   3. the blocks' events appended in block order: the serial loop's order for every
//      executor and split. With a pair filter set, the sweeps run on the calling thread
//      (the filter is the application's code, called on the step's thread only).
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

/// Steps 2a-2b: the objects that object i may reach during its motion, into chunk.candidates.
void sweep_candidates(const Impl& w, const CollisionWorld& world, std::uint32_t i, const Motion& motion,
                      CcdChunk& chunk) {
  const ObjectSlot& s = w.slots[i];
  const Aabb start = world_aabb(s.geometry, motion.start);
  const Real pad = s.radius * motion.rotation_angle() * Real(0.5) + w.settings.contact_distance;
  Aabb swept{glm::min(start.min, s.box.min), glm::max(start.max, s.box.max)};
  swept = proxy_box(swept, pad);
  std::vector<std::uint32_t>& out = chunk.candidates;
  out.clear();
  chunk.roots.clear();
  w.broadphase->query_aabb(swept, [&](ProxyId id) {
    chunk.roots.push_back(id);
    return true;
  });
  std::sort(chunk.roots.begin(), chunk.roots.end());
  for (std::uint32_t r : chunk.roots) {
    w.for_each_member(r, [&](std::uint32_t j) {
      if (j == i || !w.may_pair(world, i, j)) return;
      if (s.ccd == CcdMode::Auto && w.slots[j].kind != ObjectKind::Static) return;
      out.push_back(j);
    });
  }
  std::sort(out.begin(), out.end());
}

/// Step 2c for the fast object i: its first impact and the sensors it crosses, appended to
/// the chunk.
void sweep_object(const Impl& w, const CollisionWorld& world, std::uint32_t i, const ToiOptions& options,
                  CcdChunk& chunk) {
  const ObjectSlot& s = w.slots[i];
  const Motion motion{s.step_pose, s.pose};
  sweep_candidates(w, world, i, motion, chunk);
  ImpactEvent best;
  bool found = false;
  for (std::uint32_t j : chunk.candidates) {
    const ObjectSlot& o = w.slots[j];
    const Result<ToiResult> r = time_of_impact(s.geometry, motion, o.geometry, motion_of(o), options);
    if (!r.ok() || r->status != CcdStatus::Hit) continue;
    if (o.sensor) {
      const PairState* p = find_pair(w, i, j);
      if (p == nullptr || (!p->touching && !p->was_touching)) {
        chunk.sensor_events.push_back({o.handle(j), s.handle(i), o.user_data, s.user_data});
      }
      continue;
    }
    if (found && r->toi >= best.toi) continue;
    found = true;
    best = ImpactEvent{s.handle(i), o.handle(j), r->toi,      r->point,   r->normal,
                       r->sub_a,    r->sub_b,    s.user_data, o.user_data};
  }
  if (found) chunk.impacts.push_back(best);
}

/// Step 1: the fast objects, by index, into w.fast.
void find_fast_objects(Impl& w) {
  w.fast.clear();
  for (std::uint32_t i : w.moved) {
    const ObjectSlot& s = w.slots[i];
    if (!s.alive || s.kind != ObjectKind::Moving || s.ccd == CcdMode::Off || s.sensor) continue;
    if (is_fast(s, Motion{s.step_pose, s.pose}, w.settings.ccd_safety_factor)) w.fast.push_back(i);
  }
  // The moved list is in call order, and names a slot twice when its object was removed
  // and the slot reused and moved again within one step: sorted, each object once.
  std::sort(w.fast.begin(), w.fast.end());
  w.fast.erase(std::unique(w.fast.begin(), w.fast.end()), w.fast.end());
}

}  // namespace

bool is_fast(const ObjectSlot& s, const Motion& motion, Real safety_factor) {
  const Real travel = glm::length(motion.displacement()) + motion.rotation_angle() * s.radius;
  return travel > safety_factor * s.min_extent;
}

void continuous_pass(Impl& w, const CollisionWorld& world, Executor& executor) {
  find_fast_objects(w);
  const std::size_t n = w.fast.size();
  if (n == 0) return;
  ToiOptions options;
  options.target_distance = w.settings.contact_distance;
  if (w.settings.ccd_tolerance > 0) options.tolerance = w.settings.ccd_tolerance;
  Executor& run_on = w.pair_filter != nullptr ? static_cast<Executor&>(serial_executor()) : executor;
  // Step 2: about 4 blocks per thread; the chunks (and their vectors' capacity) are kept.
  const std::size_t blocks = std::min(n, run_on.concurrency() * 4);
  const std::size_t per_block = (n + blocks - 1) / blocks;
  if (w.ccd_chunks.size() < blocks) w.ccd_chunks.resize(blocks);
  run_on.run(blocks, [&](std::size_t begin, std::size_t end) {
    for (std::size_t b = begin; b < end; ++b) {
      CcdChunk& chunk = w.ccd_chunks[b];
      chunk.impacts.clear();
      chunk.sensor_events.clear();
      for (std::size_t k = b * per_block; k < std::min(n, (b + 1) * per_block); ++k)
        sweep_object(w, world, w.fast[k], options, chunk);
    }
  });
  // Step 3: the blocks in order.
  for (std::size_t b = 0; b < blocks; ++b) {
    const CcdChunk& chunk = w.ccd_chunks[b];
    w.events.impacts.insert(w.events.impacts.end(), chunk.impacts.begin(), chunk.impacts.end());
    w.events.sensor_enter.insert(w.events.sensor_enter.end(), chunk.sensor_events.begin(), chunk.sensor_events.end());
    w.events.sensor_exit.insert(w.events.sensor_exit.end(), chunk.sensor_events.begin(), chunk.sensor_events.end());
  }
}

}  // namespace proxima::detail
