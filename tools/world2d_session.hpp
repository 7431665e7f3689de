#pragma once
// The 2D world protocol (`proxima world --2d`): a d2::CollisionWorld kept for a session and
// driven by JSON lines like `proxima world`, with 2D shapes and poses (docs/world-protocol.md,
// "2D worlds"): add, remove, move, set_filter, exclude, step, raycast, overlap, hash, save,
// load.
#include <proxima/core/executor.hpp>
#include <proxima/d2/collision_world.hpp>
#include <proxima/debug/capture_recorder_2d.hpp>

#include <iosfwd>
#include <memory>
#include <string_view>

#include "line_protocol.hpp"
#include "world_session.hpp"

namespace proxima::tool {

/// A session of the 2D world protocol: the world and the executor its steps run on.
class WorldSession2d {
 public:
  /// A session over an empty 2D world; an Error naming the bad setting.
  static Result<WorldSession2d> create(const WorldOptions& options = {});
  /// Answers one parsed request (never throws; a rejected request changes nothing).
  Json answer_request(const Json& request, bool& rejected);
  /// Parses and answers one input line.
  Json answer_line(std::string_view line, bool& rejected);
  /// Answers every line of `in` on `out` (see run_lines; `progress` may be null).
  QuerySummary run(std::istream& in, std::ostream& out, ProgressBar* progress = nullptr);
  /// True when writing the capture of `--record` failed (the session went on without it).
  bool record_failed() const { return record_failed_; }

 private:
  WorldSession2d(d2::CollisionWorld world, std::unique_ptr<ThreadPool> pool)
      : world_(std::move(world)), pool_(std::move(pool)) {}
  Json dispatch(const Json& request);
  Json add(const Json& request);
  Json remove(const Json& request);
  Json move(const Json& request);
  Json set_filter(const Json& request);
  Json exclude(const Json& request);
  Json step(const Json& request);
  Json raycast(const Json& request) const;
  Json overlap(const Json& request) const;
  Json hash(const Json& request) const;
  Json save(const Json& request) const;
  Json load(const Json& request);
  d2::ObjectHandle live_handle(const Json& request, std::string_view key) const;

  d2::CollisionWorld world_;
  std::unique_ptr<ThreadPool> pool_;
  std::unique_ptr<std::ofstream> record_file_;
  std::unique_ptr<debug::CaptureRecorder2D> recorder_;
  bool record_failed_ = false;
};

}  // namespace proxima::tool
