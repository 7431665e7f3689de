// CaptureRecorder2D (debug/capture_recorder_2d.hpp).
//
// Steps of record_step:
//   1. first call: the header line ("dimension": 2) and a scene line with no objects;
//   2. the step line: empty "poses", "added" and "removed" (the objects are drawn), the
//      step's events and manifolds at z = 0, no queries, and the draw stream: the world
//      drawn by draw_world_2d, then the caller's `extra`.
#include <proxima/debug/capture_recorder_2d.hpp>

#include <ostream>

#include "debug/capture_json.hpp"
#include "debug/json_text.hpp"

namespace proxima::debug {

CaptureRecorder2D::CaptureRecorder2D(std::ostream& out, CaptureOptions options)
    : out_(&out), options_(std::move(options)) {}

std::optional<Error> CaptureRecorder2D::record_step(const d2::CollisionWorld& world,
                                                    std::span<const WorldObject2D> objects, Real dt,
                                                    const DrawBuffer* extra) {
  const auto failure = [] { return Error{ErrorCode::InvalidArgument, "out", "writing the capture failed"}; };
  if (failed_) return failure();
  if (!started_) {
    std::string header;
    json::header(header, options_, 2);
    started_ = true;
    if (!json::write_line(*out_, header, failed_) ||
        !json::write_line(*out_, "{\"type\":\"scene\",\"objects\":[]}", failed_)) {
      return failure();
    }
  }
  std::string line = "{\"type\":\"step\"";
  json::key(line, "index");
  json::integer(line, steps_);
  json::key(line, "dt");
  json::real(line, dt);
  line += ",\"poses\":[],\"added\":[],\"removed\":[]";
  json::key(line, "events");
  json::events(line, world.events());
  json::key(line, "contacts");
  json::manifolds(line, world.manifolds());
  line += ",\"queries\":[]";
  World2DDrawOptions look;
  look.shape.segments = options_.tessellation.segments;
  look.contacts = look.impacts = options_.draw_contacts;
  look.contact = options_.contact;
  DrawBuffer draw;
  draw_world_2d(draw, world, objects, look);
  if (extra) extra->replay(draw);
  json::key(line, "draw");
  json::draw_stream(line, draw);
  line += '}';
  if (!json::write_line(*out_, line, failed_)) return failure();
  ++steps_;
  return std::nullopt;
}

}  // namespace proxima::debug
