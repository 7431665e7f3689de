// Pictures of a collision world (world_picture.hpp).
#include "world_picture.hpp"

#include <sstream>

namespace proxima::tool {

std::optional<Error> write_world_picture(const CollisionWorld& world, const std::string& path,
                                         const RenderOptions& options,
                                         const std::optional<debug::CaptureCamera>& camera, const DrawBuffer* extra) {
  std::stringstream text;
  debug::CaptureOptions capture_options;
  capture_options.camera = camera;
  capture_options.snapshot = false;
  debug::CaptureRecorder recorder(text, capture_options);
  if (auto e = recorder.record_step(world, Real(1), extra)) return e;
  Result<Capture> capture = read_capture(text);
  if (!capture.ok()) return capture.error();
  return render_file(capture.value(), 0, options, path);
}

}  // namespace proxima::tool
