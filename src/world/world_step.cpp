// CollisionWorld::step: the discrete pass (broad phase, filters, narrow phase, persistent
// manifolds, events), then continuous detection (world_ccd.cpp), then the callbacks.
//
// Steps:
//   1. candidates: the broad phase's proxy pairs (one proxy per attachment tree) expanded to
//      object pairs whose boxes overlap, filtered (Impl::may_pair), sorted by (lo, hi);
//   2. merge with the pair table of the last step (both sorted): a pair keeps its cache and
//      its previous manifold when both generations match; a pair that was touching and is
//      no longer a candidate (separated boxes, filtered out, an object removed or its slot
//      reused) ends here;
//   3. narrow phase per candidate on the executor (each item writes only its own result):
//      collide, or intersect for a pair with a sensor, warm-started by the pair's cache;
//   4. in pair order: points matched to the previous manifold (contact_matching.hpp),
//      on_pre_contact, then begin / persist / end and sensor enter / exit;
//   5. continuous detection for the fast objects, on the executor (world_ccd.cpp);
//   6. the moved objects' step poses become their poses; every event array is sorted;
//   7. callbacks in event order (world_listener.hpp).
#include <proxima/broadphase/pair_tracker.hpp>
#include <proxima/narrowphase/narrowphase.hpp>

#include <algorithm>
#include <cmath>

#include "world/contact_matching.hpp"
#include "world/world_ccd.hpp"
#include "world/world_state.hpp"

namespace proxima {

namespace {

using Impl = CollisionWorld::Impl;

/// Step 1: the filtered object pairs whose boxes overlap, sorted by (lo, hi).
void find_candidates(Impl& w, const CollisionWorld& world, Executor& executor, std::vector<ProxyPair>& out) {
  w.broadphase->find_pairs(w.proxy_pairs, executor);
  out.clear();
  bool expanded = false;
  for (const ProxyPair& p : w.proxy_pairs) {
    const bool single_a = w.slots[p.lo].first_child == ObjectHandle::kNoObject;
    const bool single_b = w.slots[p.hi].first_child == ObjectHandle::kNoObject;
    if (single_a && single_b) {
      if (w.may_pair(world, p.lo, p.hi)) out.push_back(p);
      continue;
    }
    expanded = true;
    w.for_each_member(p.lo, [&](std::uint32_t i) {
      w.for_each_member(p.hi, [&](std::uint32_t j) {
        if (w.slots[i].box.overlaps(w.slots[j].box) && w.may_pair(world, i, j))
          out.push_back(i < j ? ProxyPair{i, j} : ProxyPair{j, i});
      });
    });
  }
  if (expanded) sort_pairs(out);
}

ContactEvent contact_event(const PairState& s) { return {s.pair(), s.user_lo, s.user_hi}; }

/// The sensor events of a sensor pair (one per sensor side; two when both are sensors).
void sensor_events(const PairState& s, std::vector<SensorEvent>& out) {
  const ObjectHandle lo{s.lo, s.gen_lo}, hi{s.hi, s.gen_hi};
  if ((s.sensor & 1u) != 0) out.push_back({lo, hi, s.user_lo, s.user_hi});
  if ((s.sensor & 2u) != 0) out.push_back({hi, lo, s.user_hi, s.user_lo});
}

/// The end event of a pair that touched before this step and does not now, with the
/// objects' user data of now (as last seen for a removed object).
void end_pair(const Impl& w, PairState s, StepEvents& ev) {
  if (const ObjectSlot* a = w.find({s.lo, s.gen_lo})) s.user_lo = a->user_data;
  if (const ObjectSlot* b = w.find({s.hi, s.gen_hi})) s.user_hi = b->user_data;
  if (s.sensor)
    sensor_events(s, ev.sensor_exit);
  else
    ev.end.push_back(contact_event(s));
}

/// Step 2: the new pair table from the candidates and the old table; ended pairs reported.
void merge_pairs(Impl& w, const std::vector<ProxyPair>& candidates, std::vector<PairState>& next) {
  next.clear();
  next.reserve(candidates.size());
  std::size_t o = 0;
  const std::vector<PairState>& old = w.pairs;
  for (const ProxyPair& c : candidates) {
    const std::uint64_t key = (std::uint64_t(c.lo) << 32) | c.hi;
    while (o < old.size() && old[o].key() < key) {
      if (old[o].touching) end_pair(w, old[o], w.events);
      ++o;
    }
    const ObjectSlot& a = w.slots[c.lo];
    const ObjectSlot& b = w.slots[c.hi];
    PairState s;
    if (o < old.size() && old[o].key() == key && old[o].gen_lo == a.generation && old[o].gen_hi == b.generation) {
      s = old[o];
      if (a.geometry_changed || b.geometry_changed) s.cache = PairCache{};
    } else {
      if (o < old.size() && old[o].key() == key && old[o].touching) end_pair(w, old[o], w.events);
      s.lo = c.lo;
      s.hi = c.hi;
      s.gen_lo = a.generation;
      s.gen_hi = b.generation;
    }
    if (o < old.size() && old[o].key() == key) ++o;
    s.user_lo = a.user_data;
    s.user_hi = b.user_data;
    const std::uint8_t sensor = static_cast<std::uint8_t>((a.sensor ? 1u : 0u) | (b.sensor ? 2u : 0u));
    if (sensor != s.sensor && s.touching) {  // became or stopped being a sensor pair: end the old kind
      end_pair(w, s, w.events);
      s.touching = false;
      s.contact = -1;
    }
    s.sensor = sensor;
    s.was_touching = s.touching;
    next.push_back(s);
  }
  for (; o < old.size(); ++o)
    if (old[o].touching) end_pair(w, old[o], w.events);
}

/// Step 3: the narrow phase of every candidate, on the executor.
void narrow_phase(Impl& w, std::vector<PairState>& pairs, std::vector<ContactManifold>& manifolds,
                  std::vector<std::uint8_t>& overlaps, Executor& executor) {
  manifolds.resize(pairs.size());
  overlaps.assign(pairs.size(), 0);
  PairRequest request;
  request.max_contacts = w.settings.max_contacts;
  request.contact_distance = w.settings.contact_distance;
  const std::size_t n = pairs.size();
  const std::size_t grain = std::max<std::size_t>(1, n / (executor.concurrency() * 8 + 1));
  const std::size_t items = (n + grain - 1) / grain;
  executor.run(items, [&](std::size_t begin, std::size_t end) {
    for (std::size_t item = begin; item < end; ++item) {
      for (std::size_t k = item * grain; k < std::min(n, (item + 1) * grain); ++k) {
        PairState& s = pairs[k];
        const ObjectSlot& a = w.slots[s.lo];
        const ObjectSlot& b = w.slots[s.hi];
        if (s.sensor)
          overlaps[k] = intersect(a.geometry, a.pose, b.geometry, b.pose, request, &s.cache) ? 1 : 0;
        else
          manifolds[k] = collide(a.geometry, a.pose, b.geometry, b.pose, request, &s.cache);
      }
    }
  });
}

/// Step 4: manifolds, pre-contact callbacks and events, in pair order.
void derive_events(Impl& w, const CollisionWorld& world, std::vector<PairState>& pairs,
                   const std::vector<ContactManifold>& manifolds, const std::vector<std::uint8_t>& overlaps) {
  std::vector<WorldManifold>& contacts = w.next_contacts;
  contacts.clear();
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    PairState& s = pairs[k];
    bool touching;
    if (s.sensor) {
      touching = overlaps[k] != 0;
      s.contact = -1;
    } else {
      touching = manifolds[k].count > 0;
      if (touching) {
        WorldManifold& m = contacts.emplace_back();  // built in place; dropped below if vetoed
        m.pair = s.pair();
        const WorldManifold* previous = s.was_touching && s.contact >= 0 ? &w.contacts[s.contact] : nullptr;
        detail::match_contact_points(previous, manifolds[k], s.next_point_id, m);
        if (w.listener != nullptr) {
          w.in_pre_contact = true;
          touching = w.listener->on_pre_contact(world, m) && m.count > 0;
          w.in_pre_contact = false;
        }
        if (!touching) contacts.pop_back();
      }
      s.contact = touching ? static_cast<std::int32_t>(contacts.size() - 1) : -1;
    }
    s.touching = touching;
    if (touching && !s.was_touching) {
      if (s.sensor)
        sensor_events(s, w.events.sensor_enter);
      else
        w.events.begin.push_back(contact_event(s));
    } else if (touching) {
      if (!s.sensor) w.events.persist.push_back(contact_event(s));
    } else if (s.was_touching) {
      end_pair(w, s, w.events);
    }
  }
  std::swap(w.contacts, w.next_contacts);
}

/// Step 6: the motion of the next step starts at the poses of now; arrays sorted.
void finish_step(Impl& w) {
  for (std::uint32_t i : w.moved) {
    ObjectSlot& s = w.slots[i];
    s.step_pose = s.pose;
    s.moved = false;
    s.geometry_changed = false;
  }
  w.moved.clear();
  auto by_pair = [](const ContactEvent& x, const ContactEvent& y) { return x.pair < y.pair; };
  auto by_sensor = [](const SensorEvent& x, const SensorEvent& y) {
    return std::tie(x.sensor, x.other) < std::tie(y.sensor, y.other);
  };
  std::sort(w.events.end.begin(), w.events.end.end(), by_pair);
  std::sort(w.events.sensor_enter.begin(), w.events.sensor_enter.end(), by_sensor);
  std::sort(w.events.sensor_exit.begin(), w.events.sensor_exit.end(), by_sensor);
  std::sort(w.events.impacts.begin(), w.events.impacts.end(),
            [](const ImpactEvent& x, const ImpactEvent& y) { return std::tie(x.a, x.b) < std::tie(y.a, y.b); });
  ++w.steps;
}

/// Calls `call(listener)` on the world listener, then on the listeners of the live objects
/// `a` and `b` (each once).
template <class Call>
void notify(Impl& w, ObjectHandle a, ObjectHandle b, Call&& call) {
  if (w.listener != nullptr) call(*w.listener);
  for (ObjectHandle h : {a, b}) {
    if (w.find(h) == nullptr) continue;
    const auto it = w.object_listeners.find(h.index);
    if (it != w.object_listeners.end()) call(*it->second);
  }
}

/// Step 7: every event to the listeners, in event order. The arrays are copied first: a
/// callback may change the world (never the events of this step).
void run_callbacks(Impl& w, CollisionWorld& world) {
  if (w.listener == nullptr && w.object_listeners.empty()) return;
  const StepEvents ev = w.events;
  w.in_callback = true;
  for (const ContactEvent& e : ev.begin)
    notify(w, e.pair.a, e.pair.b, [&](WorldListener& l) { l.on_contact_begin(world, e); });
  for (const ContactEvent& e : ev.persist)
    notify(w, e.pair.a, e.pair.b, [&](WorldListener& l) { l.on_contact_persist(world, e); });
  for (const ContactEvent& e : ev.end)
    notify(w, e.pair.a, e.pair.b, [&](WorldListener& l) { l.on_contact_end(world, e); });
  for (const SensorEvent& e : ev.sensor_enter)
    notify(w, e.sensor, e.other, [&](WorldListener& l) { l.on_sensor_enter(world, e); });
  for (const SensorEvent& e : ev.sensor_exit)
    notify(w, e.sensor, e.other, [&](WorldListener& l) { l.on_sensor_exit(world, e); });
  for (const ImpactEvent& e : ev.impacts) notify(w, e.a, e.b, [&](WorldListener& l) { l.on_impact(world, e); });
  w.in_callback = false;
}

}  // namespace

std::optional<Error> CollisionWorld::step(Real dt, Executor& executor) {
  const detail::WriteScope writing(impl_->access);
  Impl& w = *impl_;
  if (!std::isfinite(dt) || dt <= 0) return make_error(ErrorCode::NonPositive, "dt", "must be finite and > 0");
  if (w.in_callback || w.in_pre_contact)
    return make_error(ErrorCode::InvalidArgument, "world", "step() cannot be called from a callback");
  w.events.clear();
  find_candidates(w, *this, executor, w.candidates);
  merge_pairs(w, w.candidates, w.next_pairs);
  narrow_phase(w, w.next_pairs, w.manifolds, w.overlaps, executor);
  derive_events(w, *this, w.next_pairs, w.manifolds, w.overlaps);
  std::swap(w.pairs, w.next_pairs);
  if (w.settings.continuous) detail::continuous_pass(w, *this, executor);
  finish_step(w);
  run_callbacks(w, *this);
  return std::nullopt;
}

const StepEvents& CollisionWorld::events() const {
  const detail::ReadScope reading(impl_->access);
  return impl_->events;
}

std::span<const WorldManifold> CollisionWorld::contacts() const {
  const detail::ReadScope reading(impl_->access);
  return impl_->contacts;
}

const WorldManifold* CollisionWorld::contact(ObjectHandle a, ObjectHandle b) const {
  const detail::ReadScope reading(impl_->access);
  return const_cast<CollisionWorld*>(this)->contact(a, b);
}

WorldManifold* CollisionWorld::contact(ObjectHandle a, ObjectHandle b) {
  const detail::ReadScope reading(impl_->access);
  const ObjectPair key = a.index < b.index ? ObjectPair{a, b} : ObjectPair{b, a};
  auto& c = impl_->contacts;
  const auto it =
      std::lower_bound(c.begin(), c.end(), key, [](const WorldManifold& m, const ObjectPair& k) { return m.pair < k; });
  return it != c.end() && it->pair == key ? &*it : nullptr;
}

std::uint64_t CollisionWorld::step_count() const {
  const detail::ReadScope reading(impl_->access);
  return impl_->steps;
}

}  // namespace proxima
