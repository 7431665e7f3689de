#include "world2d_session.hpp"

#include <proxima/d2/narrowphase.hpp>

#include <algorithm>
#include <array>
#include <fstream>

#include "json_shapes_2d.hpp"
#include "world_json.hpp"
#include "world_snapshot_file.hpp"

namespace proxima::tool {

namespace {

constexpr std::array<std::string_view, 11> kOperations = {"add",     "remove",  "move", "set_filter", "exclude", "step",
                                                          "raycast", "overlap", "hash", "save",       "load"};

std::string operation_names() {
  std::string names;
  for (std::string_view n : kOperations) names += (names.empty() ? "" : ", ") + std::string(n);
  return names;
}

Json pairs(const std::vector<ContactEvent>& events) {
  Json list = Json::array();
  for (const ContactEvent& e : events)
    list.push_back(Json::array({handle_to_json(e.pair.a), handle_to_json(e.pair.b)}));
  return list;
}

Json sensor_pairs(const std::vector<SensorEvent>& events) {
  Json list = Json::array();
  for (const SensorEvent& e : events) list.push_back(Json::array({handle_to_json(e.sensor), handle_to_json(e.other)}));
  return list;
}

Json manifold_json(const d2::WorldManifold& wm) {
  const d2::Manifold& m = wm.manifold;
  Json points = Json::array();
  for (int i = 0; i < m.count; ++i) {
    const d2::ContactPoint& p = m.points[static_cast<std::size_t>(i)];
    points.push_back({{"point_a", to_json(p.point_a)},
                      {"point_b", to_json(p.point_b)},
                      {"depth", to_json(p.depth)},
                      {"feature_id", p.feature_id}});
  }
  Json j = {{"a", handle_to_json(wm.pair.a)},
            {"b", handle_to_json(wm.pair.b)},
            {"normal", to_json(m.normal)},
            {"points", points}};
  if (m.part_a >= 0) j["part_a"] = Json{{"segment", m.part_a}};
  if (m.part_b >= 0) j["part_b"] = Json{{"segment", m.part_b}};
  return j;
}

}  // namespace

Result<WorldSession2d> WorldSession2d::create(const WorldOptions& options) {
  Result<d2::CollisionWorld> world = d2::CollisionWorld::create(options.settings);
  if (!world.ok()) return world.error();
  std::unique_ptr<ThreadPool> pool;
  if (options.threads != 1) pool = std::make_unique<ThreadPool>(options.threads);
  WorldSession2d session(std::move(world).value(), std::move(pool));
  if (!options.record_path.empty()) {
    session.record_file_ = std::make_unique<std::ofstream>(options.record_path, std::ios::trunc);
    if (!*session.record_file_) {
      return Error{ErrorCode::InvalidArgument, "record", "cannot write " + options.record_path};
    }
    session.recorder_ = std::make_unique<debug::CaptureRecorder2D>(*session.record_file_);
  }
  return session;
}

d2::ObjectHandle WorldSession2d::live_handle(const Json& request, std::string_view key) const {
  const d2::ObjectHandle h = read_handle(require_member(request, "", key), std::string(key));
  if (!world_.contains(h)) throw FieldError(std::string(key), "unknown_object", "names no object of this world");
  return h;
}

Json WorldSession2d::add(const Json& request) {
  reject_unknown_fields(request, "", {"id", "op", "geometry", "pose", "kind", "filter", "sensor", "ccd", "user_data"});
  d2::ObjectDesc desc{read_shape_2d(require_member(request, "", "geometry"), "geometry")};
  if (const Json* pose = find_member(request, "pose")) desc.pose = read_pose_2d(*pose, "pose");
  if (const Json* kind = find_member(request, "kind")) desc.kind = read_kind(*kind, "kind");
  if (const Json* filter = find_member(request, "filter")) desc.filter = read_collision_filter(*filter, "filter");
  if (const Json* sensor = find_member(request, "sensor")) desc.sensor = read_bool(*sensor, "sensor");
  if (const Json* ccd = find_member(request, "ccd")) desc.ccd = read_ccd(*ccd, "ccd");
  if (const Json* user_data = find_member(request, "user_data")) desc.user_data = read_u64(*user_data, "user_data");
  return Json{{"object", handle_to_json(unwrap_world(world_.add(desc)))}};
}

Json WorldSession2d::remove(const Json& request) {
  reject_unknown_fields(request, "", {"id", "op", "object"});
  check_world(world_.remove(live_handle(request, "object")));
  return ok_answer();
}

Json WorldSession2d::move(const Json& request) {
  reject_unknown_fields(request, "", {"id", "op", "object", "pose", "teleport"});
  const d2::ObjectHandle h = live_handle(request, "object");
  const d2::Pose pose = read_pose_2d(require_member(request, "", "pose"), "pose");
  bool teleport = false;
  if (const Json* t = find_member(request, "teleport")) teleport = read_bool(*t, "teleport");
  check_world(teleport ? world_.teleport(h, pose) : world_.move(h, pose));
  return ok_answer();
}

Json WorldSession2d::set_filter(const Json& request) {
  reject_unknown_fields(request, "", {"id", "op", "object", "filter"});
  const d2::ObjectHandle h = live_handle(request, "object");
  check_world(world_.set_filter(h, read_collision_filter(require_member(request, "", "filter"), "filter")));
  return ok_answer();
}

Json WorldSession2d::exclude(const Json& request) {
  reject_unknown_fields(request, "", {"id", "op", "a", "b", "excluded"});
  const d2::ObjectHandle a = live_handle(request, "a");
  const d2::ObjectHandle b = live_handle(request, "b");
  bool excluded = true;
  if (const Json* e = find_member(request, "excluded")) excluded = read_bool(*e, "excluded");
  check_world(world_.set_pair_excluded(a, b, excluded));
  return ok_answer();
}

Json WorldSession2d::step(const Json& request) {
  reject_unknown_fields(request, "", {"id", "op", "contacts"});
  bool contacts = false;
  if (const Json* c = find_member(request, "contacts")) contacts = read_bool(*c, "contacts");
  check_world(world_.step(pool_ ? static_cast<Executor&>(*pool_) : serial_executor()));
  // A 2D step has no duration: its capture line's dt is 1 (one step).
  if (recorder_ && recorder_->record_step(world_, Real(1))) record_failed_ = true;
  const d2::StepEvents& ev = world_.events();
  Json answer = {{"begin", pairs(ev.begin)},
                 {"persist", pairs(ev.persist)},
                 {"end", pairs(ev.end)},
                 {"sensor_enter", sensor_pairs(ev.sensor_enter)},
                 {"sensor_exit", sensor_pairs(ev.sensor_exit)}};
  Json impacts = Json::array();
  for (const d2::ImpactEvent& e : ev.impacts) {
    impacts.push_back({{"a", handle_to_json(e.a)},
                       {"b", handle_to_json(e.b)},
                       {"toi", to_json(e.toi)},
                       {"point", to_json(e.point)},
                       {"normal", to_json(e.normal)}});
  }
  answer["impacts"] = std::move(impacts);
  if (contacts) {
    Json list = Json::array();
    for (const d2::WorldManifold& m : world_.manifolds()) list.push_back(manifold_json(m));
    answer["contacts"] = std::move(list);
  }
  return answer;
}

Json WorldSession2d::raycast(const Json& request) const {
  reject_unknown_fields(request, "", {"id", "op", "origin", "direction", "max_t", "filter"});
  const d2::Ray ray{read_vec2(require_member(request, "", "origin"), "origin"),
                    read_vec2(require_member(request, "", "direction"), "direction")};
  Real max_t = kRealMax;
  if (const Json* m = find_member(request, "max_t")) {
    max_t = read_real(*m, "max_t");
    if (max_t < Real(0)) throw FieldError("max_t", "negative", "must not be negative");
  }
  QueryFilter filter;
  if (const Json* f = find_member(request, "filter")) filter = read_query_filter(*f, "filter");
  const auto hit = world_.raycast(ray, max_t, filter);
  if (!hit) return Json{{"hit", nullptr}};
  return Json{{"hit",
               {{"object", handle_to_json(hit->object)},
                {"t", to_json(hit->hit.t)},
                {"point", to_json(hit->hit.point)},
                {"normal", to_json(hit->hit.normal)}}}};
}

Json WorldSession2d::overlap(const Json& request) const {
  reject_unknown_fields(request, "", {"id", "op", "geometry", "pose", "filter"});
  const d2::Shape shape = read_shape_2d(require_member(request, "", "geometry"), "geometry");
  d2::Pose pose{};
  if (const Json* p = find_member(request, "pose")) pose = read_pose_2d(*p, "pose");
  QueryFilter filter;
  if (const Json* f = find_member(request, "filter")) filter = read_query_filter(*f, "filter");
  std::vector<d2::ObjectHandle> found;
  world_.overlap(shape, pose, filter, found);
  Json list = Json::array();
  for (const d2::ObjectHandle h : found) list.push_back(handle_to_json(h));
  return Json{{"objects", list}};
}

Json WorldSession2d::hash(const Json& request) const {
  reject_unknown_fields(request, "", {"id", "op"});
  return Json{{"hash", hash_text(world_.state_hash())}};
}

Json WorldSession2d::save(const Json& request) const {
  reject_unknown_fields(request, "", {"id", "op", "file"});
  save_snapshot_file(world_, request);
  return ok_answer();
}

Json WorldSession2d::load(const Json& request) {
  reject_unknown_fields(request, "", {"id", "op", "file"});
  world_ = load_snapshot_file<d2::CollisionWorld>(request);
  if (recorder_) recorder_->reset_objects();
  return Json{{"objects", world_.size()}};
}

Json WorldSession2d::dispatch(const Json& request) {
  const std::string name = read_op(request);
  if (name == "add") return add(request);
  if (name == "remove") return remove(request);
  if (name == "move") return move(request);
  if (name == "set_filter") return set_filter(request);
  if (name == "exclude") return exclude(request);
  if (name == "hash") return hash(request);
  if (name == "save") return save(request);
  if (name == "load") return load(request);
  if (name == "step") return step(request);
  if (name == "raycast") return raycast(request);
  if (name == "overlap") return overlap(request);
  throw FieldError("op", "unknown_op",
                   "unknown operation \"" + name + "\" (expected one of " + operation_names() + ")");
}

Json WorldSession2d::answer_request(const Json& request, bool& rejected) {
  return answer_request_with(request, rejected, [this](const Json& r) { return dispatch(r); });
}

Json WorldSession2d::answer_line(std::string_view line, bool& rejected) {
  return answer_line_with(line, rejected, [this](const Json& r) { return dispatch(r); });
}

QuerySummary WorldSession2d::run(std::istream& in, std::ostream& out, ProgressBar* progress) {
  return run_lines(
      in, out, [this](const Json& r) { return dispatch(r); }, progress);
}

}  // namespace proxima::tool
