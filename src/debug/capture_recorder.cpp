// CaptureRecorder (debug/capture_recorder.hpp): the capture format of
// docs/capture-format.md, one JSON line per record.
//
// Steps of record_step:
//   1. first call: the header line, then the scene line (every object with its mesh, the
//      world's snapshot in base64); the recorder remembers what it wrote of each object;
//   2. the step line: objects whose pose changed since it was last written ("poses"),
//      objects new or changed in kind, sensor flag, filter, user data, continuous mode or
//      geometry ("added", full records), objects gone ("removed"), the step's events and
//      manifolds, the queries recorded since the last step, and the draw stream (the
//      manifolds drawn by draw_manifold, then the caller's `extra`).
#include <proxima/debug/capture_recorder.hpp>
#include <proxima/debug/draw_contacts.hpp>
#include <proxima/debug/draw_world.hpp>

#include <ostream>

#include "debug/capture_json.hpp"
#include "debug/capture_objects.hpp"
#include "debug/json_text.hpp"

namespace proxima::debug {

namespace {

detail::CaptureObjectState state_of(const ObjectDesc& desc) {
  return {desc.pose, desc.kind, desc.sensor, desc.filter, desc.user_data, desc.ccd};
}

}  // namespace

CaptureRecorder::CaptureRecorder(std::ostream& out, CaptureOptions options)
    : out_(&out), options_(std::move(options)) {}

std::string CaptureRecorder::object_record(ObjectHandle handle, const ObjectDesc& desc) const {
  std::string out = "{";
  detail::object_members(out, handle.to_integer(), state_of(desc), object_color(desc));
  json::key(out, "geometry");
  json::geometry(out, desc.geometry);
  detail::pose_members(out, desc.pose);
  json::key(out, "mesh");
  json::mesh(out, tessellate(desc.geometry, options_.tessellation));
  out += '}';
  return out;
}

std::string CaptureRecorder::scene_line(const CollisionWorld& world) {
  const auto record = [this](ObjectHandle handle, const ObjectDesc& desc) { return object_record(handle, desc); };
  return detail::scene_line(world, options_.snapshot, written_, record, state_of);
}

std::string CaptureRecorder::object_changes(const CollisionWorld& world) {
  const auto record = [this](ObjectHandle handle, const ObjectDesc& desc) { return object_record(handle, desc); };
  return detail::object_changes(world, written_, record, state_of);
}

std::string CaptureRecorder::step_line(const CollisionWorld& world, Real dt, const DrawBuffer* extra) {
  std::string out = "{\"type\":\"step\"";
  json::key(out, "index");
  json::integer(out, steps_);
  json::key(out, "world_step");
  json::integer(out, world.step_count());
  json::key(out, "dt");
  json::real(out, dt);
  out += object_changes(world);
  json::key(out, "events");
  json::events(out, world.events());
  json::key(out, "contacts");
  json::manifolds(out, world.contacts());
  out += ",\"queries\":[";
  for (std::size_t i = 0; i < queries_.size(); ++i) out.append(i ? "," : "").append(queries_[i]);
  out += ']';
  queries_.clear();
  DrawBuffer draw;
  if (options_.draw_contacts) {
    for (const WorldManifold& manifold : world.contacts()) draw_manifold(draw, manifold, options_.contact);
  }
  if (extra) extra->replay(draw);
  json::key(out, "draw");
  json::draw_stream(out, draw);
  out += '}';
  return out;
}

std::optional<Error> CaptureRecorder::record_step(const CollisionWorld& world, Real dt, const DrawBuffer* extra) {
  const auto failure = [] { return Error{ErrorCode::InvalidArgument, "out", "writing the capture failed"}; };
  if (failed_) return failure();
  if (!started_) {
    std::string header;
    json::header(header, options_, 3);
    started_ = true;
    if (!json::write_line(*out_, header, failed_) || !json::write_line(*out_, scene_line(world), failed_)) {
      return failure();
    }
  }
  if (!json::write_line(*out_, step_line(world, dt, extra), failed_)) return failure();
  ++steps_;
  return std::nullopt;
}

void CaptureRecorder::record_ray(const Ray& ray, Real max_t, std::span<const WorldHit> hits) {
  std::string out = "{\"kind\":\"ray\"";
  json::key(out, "origin");
  json::vec3(out, ray.origin);
  json::key(out, "direction");
  json::vec3(out, ray.direction);
  json::key(out, "max_t");
  json::real(out, max_t);
  out += ",\"hits\":[";
  for (std::size_t i = 0; i < hits.size(); ++i) {
    out += i ? ",{\"object\":" : "{\"object\":";
    json::integer(out, hits[i].object.to_integer());
    json::key(out, "t");
    json::real(out, hits[i].t);
    json::key(out, "point");
    json::vec3(out, hits[i].point);
    json::key(out, "normal");
    json::vec3(out, hits[i].normal);
    out += '}';
  }
  out += "]}";
  queries_.push_back(std::move(out));
}

void CaptureRecorder::invalidate(ObjectHandle object) {
  const auto it = written_.find(object.to_integer());
  if (it != written_.end()) it->second.stale = true;
}

void CaptureRecorder::reset_objects() {
  for (auto& [id, written] : written_) written.stale = true;
}

}  // namespace proxima::debug
