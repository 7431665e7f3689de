// CaptureRecorder2D (debug/capture_recorder_2d.hpp).
//
// Steps of record_step:
//   1. first call: the header line ("dimension": 2), then the scene line: every object with
//      its 2D geometry, its pose as a turn about +z (plane_pose) and its fill as a mesh at
//      z = 0 (tessellate_2d), and the world's snapshot in base64; the recorder remembers what
//      it wrote of each object;
//   2. the step line: objects whose pose changed ("poses"), objects new or changed in kind,
//      sensor flag, filter, user data or continuous mode ("added", full records), objects gone
//      ("removed"), the step's events and manifolds at z = 0, no queries, and the draw
//      stream: every object's outline and each chain's segments (draw_world_2d without fills),
//      contacts and impacts, then the caller's `extra`.
#include <proxima/debug/capture_recorder_2d.hpp>
#include <proxima/debug/draw_shapes_2d.hpp>

#include <ostream>

#include "debug/capture_json.hpp"
#include "debug/capture_objects.hpp"
#include "debug/json_text.hpp"

namespace proxima::debug {

namespace {

detail::CaptureObjectState state_of(const d2::ObjectDesc& desc) {
  return {plane_pose(desc.pose), desc.kind, desc.sensor, desc.filter, desc.user_data, desc.ccd};
}

}  // namespace

CaptureRecorder2D::CaptureRecorder2D(std::ostream& out, CaptureOptions options)
    : out_(&out), options_(std::move(options)) {}

std::string CaptureRecorder2D::object_record(d2::ObjectHandle handle, const d2::ObjectDesc& desc) const {
  std::string out = "{";
  detail::object_members(out, handle.to_integer(), state_of(desc), object_color(desc));
  json::key(out, "geometry");
  json::geometry(out, desc.shape);
  detail::pose_members(out, plane_pose(desc.pose));
  json::key(out, "mesh");
  json::mesh(out, tessellate_2d(desc.shape, options_.tessellation.segments));
  out += '}';
  return out;
}

std::string CaptureRecorder2D::scene_line(const d2::CollisionWorld& world) {
  const auto record = [this](d2::ObjectHandle handle, const d2::ObjectDesc& desc) {
    return object_record(handle, desc);
  };
  return detail::scene_line(world, options_.snapshot, written_, record,
                            [](const d2::ObjectDesc& desc) { return state_of(desc); });
}

std::string CaptureRecorder2D::object_changes(const d2::CollisionWorld& world) {
  const auto record = [this](d2::ObjectHandle handle, const d2::ObjectDesc& desc) {
    return object_record(handle, desc);
  };
  return detail::object_changes(world, written_, record, [](const d2::ObjectDesc& desc) { return state_of(desc); });
}

std::string CaptureRecorder2D::step_line(const d2::CollisionWorld& world, Real dt, const DrawBuffer* extra) {
  std::string out = "{\"type\":\"step\"";
  json::key(out, "index");
  json::integer(out, steps_);
  json::key(out, "dt");
  json::real(out, dt);
  out += object_changes(world);
  json::key(out, "events");
  json::events(out, world.events());
  json::key(out, "contacts");
  json::manifolds(out, world.manifolds());
  out += ",\"queries\":[]";
  World2DDrawOptions look;
  look.shape.segments = options_.tessellation.segments;
  look.shape.fill = false;  // the scene's meshes are the fills
  look.contacts = look.impacts = options_.draw_contacts;
  look.contact = options_.contact;
  DrawBuffer draw;
  draw_world_2d(draw, world, look);
  if (extra) extra->replay(draw);
  json::key(out, "draw");
  json::draw_stream(out, draw);
  out += '}';
  return out;
}

std::optional<Error> CaptureRecorder2D::record_step(const d2::CollisionWorld& world, Real dt, const DrawBuffer* extra) {
  const auto failure = [] { return Error{ErrorCode::InvalidArgument, "out", "writing the capture failed"}; };
  if (failed_) return failure();
  if (!started_) {
    std::string header;
    json::header(header, options_, 2);
    started_ = true;
    if (!json::write_line(*out_, header, failed_) || !json::write_line(*out_, scene_line(world), failed_)) {
      return failure();
    }
  }
  if (!json::write_line(*out_, step_line(world, dt, extra), failed_)) return failure();
  ++steps_;
  return std::nullopt;
}

void CaptureRecorder2D::reset_objects() {
  for (auto& [id, written] : written_) written.stale = true;
}

}  // namespace proxima::debug
