#pragma once
// The world protocol (`proxima world`): a CollisionWorld kept for a whole session and driven
// by one JSON request per input line, one JSON answer per output line, in order. See
// docs/world-protocol.md.
#include <proxima/core/executor.hpp>
#include <proxima/core/result.hpp>
#include <proxima/debug/capture_recorder.hpp>
#include <proxima/world/collision_world.hpp>
#include <proxima/world/world_settings.hpp>

#include <cstddef>
#include <fstream>
#include <iosfwd>
#include <memory>
#include <span>
#include <string>
#include <string_view>

#include "line_protocol.hpp"

namespace proxima::tool {

/// Options of `proxima world` (its command-line options).
struct WorldOptions {
  std::size_t threads = 1;  ///< threads of the step's narrow phase (1: on the calling thread)
  std::string record_path;  ///< write a capture of every step to this file (empty: none)
  WorldSettings settings;   ///< broad phase, contact distance, sensors sensing sensors, ...
};

/// A session of the world protocol: the world, and the executor its steps run on.
class WorldSession {
 public:
  /// A session over an empty world; an Error naming the bad setting ("settings.broadphase").
  static Result<WorldSession> create(const WorldOptions& options = {});

  /// Answers one parsed request (never throws: a bad request gives an error answer, sets
  /// `rejected` and leaves the world as it was).
  Json answer_request(const Json& request, bool& rejected);
  /// Parses and answers one input line.
  Json answer_line(std::string_view line, bool& rejected);
  /// Answers every line of `in` on `out` (see run_lines; `progress` may be null).
  QuerySummary run(std::istream& in, std::ostream& out, ProgressBar* progress = nullptr);

  /// The session's world.
  CollisionWorld& world() { return world_; }
  /// The session's world.
  const CollisionWorld& world() const { return world_; }
  /// The executor of the steps (a ThreadPool when more than one thread was asked for).
  Executor& executor() {
    if (pool_) return *pool_;
    return serial_executor();
  }
  /// Replaces the world (by "load"); the executor stays; a recording starts its objects anew.
  void replace_world(CollisionWorld world) {
    world_ = std::move(world);
    if (recorder_) recorder_->reset_objects();
  }

  /// The capture recorder of `--record` (nullptr when not recording).
  debug::CaptureRecorder* recorder() { return recorder_.get(); }
  /// Records the step just run (a no-op when not recording); remembers a write failure.
  void record_step(Real dt);
  /// True when writing the capture failed (the run then ends with status 1).
  bool record_failed() const { return record_failed_; }

 private:
  WorldSession(CollisionWorld world, std::unique_ptr<ThreadPool> pool)
      : world_(std::move(world)), pool_(std::move(pool)) {}
  Json dispatch(const Json& request);

  CollisionWorld world_;
  std::unique_ptr<ThreadPool> pool_;
  std::unique_ptr<std::ofstream> record_file_;
  std::unique_ptr<debug::CaptureRecorder> recorder_;
  bool record_failed_ = false;
};

/// Answers a request of one world operation: returns the answer's members (without "id"),
/// or throws FieldError naming the bad field, with the world unchanged.
using WorldOperationFunction = Json (*)(WorldSession& session, const Json& request);

/// One operation of the world protocol.
struct WorldOperation {
  std::string_view name;       ///< value of the request's "op"
  WorldOperationFunction run;  ///< the handler
  std::string_view synopsis;   ///< one line for --help: fields in, fields out
};

/// Every world operation, in the order the help lists them.
std::span<const WorldOperation> world_operations();

/// The world operation names, comma-separated (for error messages).
std::string world_operation_names();

}  // namespace proxima::tool
