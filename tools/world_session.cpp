#include "world_session.hpp"

#include <array>
#include <utility>

#include "world_json.hpp"
#include "world_ops.hpp"

namespace proxima::tool {

namespace {

const std::array kWorldOperations = {
    WorldOperation{"add", op_world_add,
                   "geometry, pose?, kind?, filter?, sensor?, ccd?, parent?, local_pose?, user_data? -> object"},
    WorldOperation{"remove", op_world_remove, "object -> removed (the object and the objects attached below it)"},
    WorldOperation{"move", op_world_move, "object, pose | objects [{object, pose}, ...] (all or nothing) -> ok"},
    WorldOperation{"set_geometry", op_world_set_geometry, "object, geometry -> ok"},
    WorldOperation{"set_filter", op_world_set_filter, "object, filter {layer?, mask?, group?} -> ok"},
    WorldOperation{"set_kind", op_world_set_kind, "object, kind (static | moving) -> ok"},
    WorldOperation{"set_ccd", op_world_set_ccd, "object, ccd (off | auto | bullet) -> ok"},
    WorldOperation{"set_user_data", op_world_set_user_data, "object, user_data -> ok"},
    WorldOperation{"attach", op_world_attach, "object, parent (null: detach), local_pose? -> ok"},
    WorldOperation{"exclude", op_world_exclude, "a, b, excluded? (default true) -> ok"},
    WorldOperation{"step", op_world_step,
                   "dt?, contacts? -> begin, persist, end, sensor_enter, sensor_exit, impacts (, contacts)"},
    WorldOperation{"raycast", op_world_raycast,
                   "origin, direction, max_t?, filter?, mode? -> hits [{object, t, point, normal}, ...]"},
    WorldOperation{"line_of_sight", op_world_line_of_sight, "from, to, filter? -> clear"},
    WorldOperation{"overlap", op_world_overlap, "geometry and pose? | box | point, filter?, mode? -> objects"},
    WorldOperation{"sweep", op_world_sweep,
                   "geometry (convex), pose?, translation, filter?, mode? -> hits [{object, t, point, normal}, ...]"},
    WorldOperation{"closest", op_world_closest,
                   "point | geometry and pose?, max_distance, filter? -> object (null: none), distance, point, normal"},
    WorldOperation{"hash", op_world_hash, "-> hash (16 hex digits of the world's state hash)"},
    WorldOperation{"save", op_world_save, "file -> ok (writes a binary snapshot of the world)"},
    WorldOperation{"load", op_world_load, "file -> objects (the world becomes the snapshot's)"},
};

}  // namespace

std::span<const WorldOperation> world_operations() { return kWorldOperations; }

std::string world_operation_names() { return joined_names(kWorldOperations); }

Result<WorldSession> WorldSession::create(const WorldOptions& options) {
  Result<CollisionWorld> world = CollisionWorld::create(options.settings);
  if (!world.ok()) return world.error();
  std::unique_ptr<ThreadPool> pool;
  if (options.threads != 1) pool = std::make_unique<ThreadPool>(options.threads);
  WorldSession session(std::move(world).value(), std::move(pool));
  if (!options.record_path.empty()) {
    session.record_file_ = std::make_unique<std::ofstream>(options.record_path, std::ios::trunc);
    if (!*session.record_file_) {
      return Error{ErrorCode::InvalidArgument, "record", "cannot write " + options.record_path};
    }
    session.recorder_ = std::make_unique<debug::CaptureRecorder>(*session.record_file_);
  }
  return session;
}

void WorldSession::record_step(Real dt) {
  if (recorder_ && recorder_->record_step(world_, dt)) record_failed_ = true;
}

Json WorldSession::dispatch(const Json& request) {
  const std::string name = read_op(request);
  for (const WorldOperation& op : kWorldOperations) {
    if (op.name != name) continue;
    Json answer = op.run(*this, request);
    // A new geometry is written again with the next recorded step.
    if (recorder_ && name == "set_geometry") recorder_->invalidate(read_handle(request["object"], "object"));
    return answer;
  }
  throw FieldError("op", "unknown_op",
                   "unknown operation \"" + name + "\" (expected one of " + world_operation_names() + ")");
}

Json WorldSession::answer_request(const Json& request, bool& rejected) {
  return answer_request_with(request, rejected, [this](const Json& r) { return dispatch(r); });
}

Json WorldSession::answer_line(std::string_view line, bool& rejected) {
  return answer_line_with(line, rejected, [this](const Json& r) { return dispatch(r); });
}

QuerySummary WorldSession::run(std::istream& in, std::ostream& out, ProgressBar* progress) {
  return run_lines(
      in, out, [this](const Json& r) { return dispatch(r); }, progress);
}

}  // namespace proxima::tool
