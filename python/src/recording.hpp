#pragma once
/// @file recording.hpp
/// What the 3D and 2D world bindings share to record captures (docs/capture-format.md):
/// the open file with its recorder, and the camera given as a dict.
#include <proxima/debug/capture_recorder.hpp>

#include <fstream>
#include <memory>
#include <string>

#include "conversions.hpp"

namespace proxima::python {

/// A capture file being written: one line per step.
template <class Recorder>
struct Recording {
  std::ofstream file;
  std::unique_ptr<Recorder> recorder;
};

/// A recording to `path` (truncated) seen by `camera` (None, or a dict of position, target,
/// up, fov_degrees, ortho_height; world frame, length units); proxima.Error naming "path"
/// when the file cannot be opened, "camera.<key>" for a bad value.
template <class Recorder>
std::unique_ptr<Recording<Recorder>> start_recording(const std::string& path, py::handle camera) {
  auto r = std::make_unique<Recording<Recorder>>();
  r->file.open(path, std::ios::binary | std::ios::trunc);
  if (!r->file) raise_argument_error("path", "cannot be opened for writing: " + path);
  debug::CaptureOptions options;
  if (!camera.is_none()) {
    const py::dict spec = camera.cast<py::dict>();
    debug::CaptureCamera cam;
    if (spec.contains("position")) cam.position = to_vec3(spec["position"], "camera.position");
    if (spec.contains("target")) cam.target = to_vec3(spec["target"], "camera.target");
    if (spec.contains("up")) cam.up = to_vec3(spec["up"], "camera.up");
    if (spec.contains("fov_degrees")) cam.fov_degrees = to_real(spec["fov_degrees"], "camera.fov_degrees");
    if (spec.contains("ortho_height")) cam.ortho_height = to_real(spec["ortho_height"], "camera.ortho_height");
    options.camera = cam;
  }
  r->recorder = std::make_unique<Recorder>(r->file, options);
  return r;
}

}  // namespace proxima::python
