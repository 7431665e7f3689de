/// @file world_step.cpp
/// The 2D world's step.
///
/// Steps (collision_world.hpp has the contract):
///   1. moved objects' rectangles go to the broad phase as flat boxes; find_pairs gives the
///      candidates sorted by slot;
///   2. candidates are filtered (filters, exclusions, sensors), then measured on the executor, each
///      writing only its own outcome: manifolds (collide_all) or a sensor's overlap;
///   3. the touching pairs (sorted) are merged with the last step's into begin / persist /
///      end; sensor pairs likewise;
///   4. fast objects are swept by time_of_impact against what their swept rectangle meets;
///   5. the listener hears the arrays in order; the poses become the next step's starts.

#include <proxima/d2/collision_world.hpp>
#include <proxima/d2/narrowphase.hpp>
#include <proxima/d2/time_of_impact.hpp>

#include <algorithm>

#include "d2/world_state.hpp"

namespace proxima::d2 {
namespace {

using detail::Slot;

/// A candidate pair's outcome.
struct PairOutcome {
  ObjectPair pair;
  bool sensor = false;
  bool touching = false;
  std::vector<Manifold> manifolds;
};

/// The elements of `now` not in `before` (both sorted by `key`) appended to `out`.
template <class T, class Key>
void difference(const std::vector<T>& now, const std::vector<T>& before, Key key, std::vector<T>& out) {
  std::size_t j = 0;
  for (const T& x : now) {
    while (j < before.size() && key(before[j]) < key(x)) ++j;
    if (j == before.size() || key(before[j]) != key(x)) out.push_back(x);
  }
}

/// Sets the proxies of moved objects.
void update_proxies(detail::WorldState& w) {
  std::vector<ProxyUpdate> updates;
  for (std::uint32_t i = 0; i < w.slots.size(); ++i) {
    const Slot& s = w.slots[i];
    if (s.alive && s.moved) updates.push_back({i, w.proxy_box(s.shape, s.pose)});
  }
  w.broadphase->update(updates);
}

/// Candidate pairs that the filters allow, in the broad phase's sorted order.
std::vector<PairOutcome> filtered_candidates(const detail::WorldState& w, Executor& executor) {
  std::vector<ProxyPair> candidates;
  w.broadphase->find_pairs(candidates, executor);
  std::vector<PairOutcome> out;
  for (const ProxyPair& p : candidates) {
    const Slot& a = w.slots[p.lo];
    const Slot& b = w.slots[p.hi];
    if (!can_collide(a.filter, b.filter) || !w.allowed(p.lo, p.hi)) continue;
    if (a.sensor && b.sensor && !w.settings.sensors_sense_sensors) continue;
    out.push_back({{w.handle(p.lo), w.handle(p.hi)}, a.sensor || b.sensor, false, {}});
  }
  return out;
}

void measure(const detail::WorldState& w, PairOutcome& o) {
  const Slot& a = w.slots[o.pair.a.index];
  const Slot& b = w.slots[o.pair.b.index];
  if (o.sensor) {
    o.touching = intersect(a.shape, a.pose, b.shape, b.pose);
    return;
  }
  collide_all(a.shape, a.pose, b.shape, b.pose, w.settings.contact_distance, o.manifolds);
  if (w.settings.max_contacts == 1) {
    for (Manifold& m : o.manifolds) {
      if (m.count == 2 && m.points[1].depth > m.points[0].depth) m.points[0] = m.points[1];
      m.count = std::min(m.count, 1);
    }
  }
  o.touching = !o.manifolds.empty();
}

ContactEvent contact_event(const detail::WorldState& w, ObjectPair pair) {
  return {pair, w.slots[pair.a.index].user_data, w.slots[pair.b.index].user_data};
}

/// Contact and sensor events and the manifolds from this step's outcomes.
void assemble_events(detail::WorldState& w, std::vector<PairOutcome>& outcomes) {
  std::vector<ContactEvent> touching;
  std::vector<SensorEvent> sensing;
  w.manifolds.clear();
  for (PairOutcome& o : outcomes) {
    if (!o.touching) continue;
    if (!o.sensor) {
      touching.push_back(contact_event(w, o.pair));
      for (const Manifold& m : o.manifolds) w.manifolds.push_back({o.pair, m});
      continue;
    }
    const Slot& a = w.slots[o.pair.a.index];
    const Slot& b = w.slots[o.pair.b.index];
    if (a.sensor) sensing.push_back({o.pair.a, o.pair.b, a.user_data, b.user_data});
    if (b.sensor) sensing.push_back({o.pair.b, o.pair.a, b.user_data, a.user_data});
  }
  const auto sensor_key = [](const SensorEvent& e) { return std::pair(e.sensor, e.other); };
  std::sort(sensing.begin(), sensing.end(),
            [&](const SensorEvent& x, const SensorEvent& y) { return sensor_key(x) < sensor_key(y); });
  const auto pair_key = [](const ContactEvent& e) { return e.pair; };
  StepEvents& ev = w.events;
  ev = StepEvents{};
  difference(touching, w.touching, pair_key, ev.begin);
  difference(w.touching, touching, pair_key, ev.end);
  difference(touching, ev.begin, pair_key, ev.persist);
  difference(sensing, w.sensing, sensor_key, ev.sensor_enter);
  difference(w.sensing, sensing, sensor_key, ev.sensor_exit);
  w.touching = std::move(touching);
  w.sensing = std::move(sensing);
}

/// True when slot `s` may move farther than the safety factor times its thinner side.
bool is_fast(const WorldSettings& settings, const Slot& s) {
  const Real turn = std::abs((s.previous.rotation.inverse() * s.pose.rotation).angle());
  const Real travel = glm::length(s.pose.position - s.previous.position) + turn * s.reach;
  return travel > settings.ccd_safety_factor * s.min_extent;
}

/// The slots whose rectangles meet what slot `a` sweeps over this step, sorted. Only those
/// rectangles: a structure may report more, depending on its history (a grid's bounds), and
/// the answer must not (a loaded world rebuilds the structure).
std::vector<std::uint32_t> sweep_candidates(const detail::WorldState& w, const Slot& a) {
  Aabb swept = a.shape.world_aabb(a.previous);
  swept.grow(a.shape.world_aabb(a.pose));
  const Aabb reach = swept.inflated(w.settings.contact_distance);
  std::vector<std::uint32_t> others;
  w.broadphase->query_aabb(detail::flat_box(reach), [&](ProxyId id) {
    others.push_back(id);
    return true;
  });
  std::erase_if(others, [&](std::uint32_t j) {
    return !overlap(w.slots[j].shape.world_aabb(w.slots[j].pose).inflated(Real(0.5) * w.settings.contact_distance),
                    reach);
  });
  std::sort(others.begin(), others.end());
  return others;
}

/// The first impact of fast slot `i` against what its swept rectangle meets, if any.
std::optional<ImpactEvent> first_impact(const detail::WorldState& w, std::uint32_t i) {
  const Slot& a = w.slots[i];
  const std::vector<std::uint32_t> others = sweep_candidates(w, a);
  ToiOptions options;
  options.target_distance = w.settings.contact_distance;
  options.tolerance = w.settings.ccd_tolerance > Real(0) ? w.settings.ccd_tolerance : options.tolerance;
  const Motion motion_a = Motion::between(a.previous, a.pose);
  std::optional<ImpactEvent> best;
  for (std::uint32_t j : others) {
    const Slot& b = w.slots[j];
    if (j == i || b.sensor || !can_collide(a.filter, b.filter) || !w.allowed(i, j)) continue;
    if (a.ccd == CcdMode::Auto && b.kind != ObjectKind::Static) continue;
    const Motion motion_b = Motion::between(b.previous, b.pose);
    const auto r = time_of_impact(a.shape, motion_a, b.shape, motion_b, options);
    if (!r || r->status != CcdStatus::Hit || (best && r->toi >= best->toi)) continue;
    best = ImpactEvent{w.handle(i), w.handle(j), r->toi, r->point, r->normal, r->part_b, a.user_data, b.user_data};
  }
  return best;
}

void continuous_detection(detail::WorldState& w) {
  if (!w.settings.continuous) return;
  for (std::uint32_t i = 0; i < w.slots.size(); ++i) {
    const Slot& s = w.slots[i];
    if (!s.alive || !s.moved || s.sensor || s.kind != ObjectKind::Moving || s.ccd == CcdMode::Off ||
        !is_fast(w.settings, s)) {
      continue;
    }
    if (auto impact = first_impact(w, i)) w.events.impacts.push_back(*impact);
  }
}

void notify(const CollisionWorld& world, WorldListener& l, const StepEvents& ev) {
  for (const ContactEvent& e : ev.begin) l.on_contact_begin(world, e);
  for (const ContactEvent& e : ev.persist) l.on_contact_persist(world, e);
  for (const ContactEvent& e : ev.end) l.on_contact_end(world, e);
  for (const SensorEvent& e : ev.sensor_enter) l.on_sensor_enter(world, e);
  for (const SensorEvent& e : ev.sensor_exit) l.on_sensor_exit(world, e);
  for (const ImpactEvent& e : ev.impacts) l.on_impact(world, e);
}

}  // namespace

std::optional<Error> CollisionWorld::step(Executor& executor) {
  if (auto e = state_->busy()) return e;
  detail::WorldState& w = *state_;
  update_proxies(w);
  std::vector<PairOutcome> outcomes = filtered_candidates(w, executor);
  executor.run(outcomes.size(), [&](std::size_t begin, std::size_t end) {
    for (std::size_t k = begin; k < end; ++k) measure(w, outcomes[k]);
  });
  assemble_events(w, outcomes);
  continuous_detection(w);
  for (Slot& s : w.slots) {
    s.previous = s.pose;
    s.moved = false;
  }
  if (w.listener != nullptr) {
    w.in_callback = true;
    notify(*this, *w.listener, w.events);
    w.in_callback = false;
  }
  return std::nullopt;
}

}  // namespace proxima::d2
