// Pictures of a collision world (world_picture.hpp): record one step into a capture text,
// read it back as `proxima render` does, draw its only frame.
#include "world_picture.hpp"

#include <proxima/debug/capture_recorder_2d.hpp>

#include <sstream>

namespace proxima::tool {

namespace {

std::optional<Error> render_recorded(std::istream& text, const std::string& path, const RenderOptions& options) {
  Result<Capture> capture = read_capture(text);
  if (!capture.ok()) return capture.error();
  return render_file(capture.value(), 0, options, path);
}

}  // namespace

std::optional<Error> write_world_picture(const CollisionWorld& world, const std::string& path,
                                         const RenderOptions& options,
                                         const std::optional<debug::CaptureCamera>& camera, const DrawBuffer* extra) {
  std::stringstream text;
  debug::CaptureOptions capture_options;
  capture_options.camera = camera;
  capture_options.snapshot = false;
  debug::CaptureRecorder recorder(text, capture_options);
  if (auto e = recorder.record_step(world, Real(1), extra)) return e;
  return render_recorded(text, path, options);
}

std::optional<Error> write_world_picture_2d(const d2::CollisionWorld& world, const std::string& path,
                                            const RenderOptions& options, const debug::CaptureOptions& capture,
                                            const DrawBuffer* extra) {
  std::stringstream text;
  debug::CaptureOptions options_2d = capture;
  options_2d.snapshot = false;  // a picture needs no snapshot
  debug::CaptureRecorder2D recorder(text, options_2d);
  if (auto e = recorder.record_step(world, Real(1), extra)) return e;
  return render_recorded(text, path, options);
}

}  // namespace proxima::tool
