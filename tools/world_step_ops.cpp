// The step and state operations of the world protocol: step (events and manifolds), hash,
// save and load (binary snapshots).
#include <algorithm>
#include <cstdio>
#include <utility>
#include <vector>

#include "world_json.hpp"
#include "world_ops.hpp"
#include "world_session.hpp"
#include "world_snapshot_file.hpp"

namespace proxima::tool {

namespace {

// The protocol writes a handle as its integer (ObjectHandle::to_integer: generation in the
// high bits) and promises pairs [Ha, Hb] with Ha < Hb as integers, each list sorted. The
// world orders pairs by slot index, which differs once a slot has been reused, so every
// list is re-ordered here (a manifold turned round gets its normal negated and its points
// swapped, as the narrow phase's convention requires).

using Key = std::pair<std::uint64_t, std::uint64_t>;

/// Sorts (key, json) entries by key and returns the json list.
Json sorted_list(std::vector<std::pair<Key, Json>>& entries) {
  std::stable_sort(entries.begin(), entries.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
  Json list = Json::array();
  for (auto& e : entries) list.push_back(std::move(e.second));
  return list;
}

Json contact_events(const std::vector<ContactEvent>& events) {
  std::vector<std::pair<Key, Json>> entries;
  for (const ContactEvent& e : events) {
    std::uint64_t a = e.pair.a.to_integer(), b = e.pair.b.to_integer();
    if (a > b) std::swap(a, b);
    entries.push_back({{a, b}, Json::array({a, b})});
  }
  return sorted_list(entries);
}

Json sensor_events(const std::vector<SensorEvent>& events) {
  std::vector<std::pair<Key, Json>> entries;
  for (const SensorEvent& e : events) {
    const std::uint64_t sensor = e.sensor.to_integer(), other = e.other.to_integer();
    entries.push_back({{sensor, other}, Json::array({sensor, other})});
  }
  return sorted_list(entries);
}

Json impact_events(const std::vector<ImpactEvent>& events) {
  std::vector<std::pair<Key, Json>> entries;
  for (const ImpactEvent& e : events) {
    Json impact = Json::object();
    impact["a"] = handle_to_json(e.a);
    impact["b"] = handle_to_json(e.b);
    impact["toi"] = to_json(e.toi);
    impact["point"] = to_json(e.point);
    impact["normal"] = to_json(e.normal);
    entries.push_back({{e.a.to_integer(), e.b.to_integer()}, std::move(impact)});
  }
  return sorted_list(entries);
}

Json manifolds(std::span<const WorldManifold> contacts) {
  std::vector<std::pair<Key, Json>> entries;
  for (const WorldManifold& m : contacts) {
    const bool turn = m.pair.a.to_integer() > m.pair.b.to_integer();
    const ObjectHandle a = turn ? m.pair.b : m.pair.a, b = turn ? m.pair.a : m.pair.b;
    Json manifold = Json::object();
    manifold["a"] = handle_to_json(a);
    manifold["b"] = handle_to_json(b);
    manifold["normal"] = to_json(turn ? -m.normal : m.normal);
    Json points = Json::array();
    for (int i = 0; i < m.count; ++i) {
      const WorldContactPoint& p = m.points[static_cast<std::size_t>(i)];
      Json point = Json::object();
      point["id"] = p.id;
      point["point_a"] = to_json(turn ? p.contact.point_b : p.contact.point_a);
      point["point_b"] = to_json(turn ? p.contact.point_a : p.contact.point_b);
      point["depth"] = to_json(p.contact.depth);
      point["persisted"] = p.persisted;
      points.push_back(std::move(point));
    }
    manifold["points"] = std::move(points);
    entries.push_back({{a.to_integer(), b.to_integer()}, std::move(manifold)});
  }
  return sorted_list(entries);
}

}  // namespace

std::string hash_text(std::uint64_t hash) {
  char text[17];
  std::snprintf(text, sizeof(text), "%016llx", static_cast<unsigned long long>(hash));
  return text;
}

Json op_world_step(WorldSession& session, const Json& request) {
  reject_unknown_fields(request, "", {"id", "op", "dt", "contacts"});
  Real dt = Real(1) / Real(60);
  if (const Json* d = find_member(request, "dt")) dt = read_real(*d, "dt");
  bool with_contacts = false;
  if (const Json* c = find_member(request, "contacts")) with_contacts = read_bool(*c, "contacts");
  CollisionWorld& world = session.world();
  check_world(world.step(dt, session.executor()));
  session.record_step(dt);
  const StepEvents& events = world.events();
  Json answer = Json::object();
  answer["begin"] = contact_events(events.begin);
  answer["persist"] = contact_events(events.persist);
  answer["end"] = contact_events(events.end);
  answer["sensor_enter"] = sensor_events(events.sensor_enter);
  answer["sensor_exit"] = sensor_events(events.sensor_exit);
  answer["impacts"] = impact_events(events.impacts);
  if (with_contacts) answer["contacts"] = manifolds(world.contacts());
  return answer;
}

Json op_world_hash(WorldSession& session, const Json& request) {
  reject_unknown_fields(request, "", {"id", "op"});
  Json answer = Json::object();
  answer["hash"] = hash_text(session.world().state_hash());
  return answer;
}

Json op_world_save(WorldSession& session, const Json& request) {
  reject_unknown_fields(request, "", {"id", "op", "file"});
  save_snapshot_file(session.world(), request);
  Json answer = Json::object();
  answer["ok"] = true;
  return answer;
}

Json op_world_load(WorldSession& session, const Json& request) {
  reject_unknown_fields(request, "", {"id", "op", "file"});
  session.replace_world(load_snapshot_file<CollisionWorld>(request));
  Json answer = Json::object();
  answer["objects"] = session.world().size();
  return answer;
}

}  // namespace proxima::tool
