#pragma once
// `proxima demo-platformer`: the 2D platformer scene (platformer_scene.hpp) run twice — the
// projectiles with continuous detection and without — its statistics printed, both runs
// drawn as an SVG, and one frame of the continuous run drawn as a PNG by `proxima render`'s
// renderer from the 2D world's draw stream (debug::CaptureRecorder2D).
#include <proxima/core/debug_draw.hpp>
#include <proxima/debug/capture_recorder.hpp>

#include <iosfwd>
#include <string>

#include "platformer_scene.hpp"

namespace proxima::tool {

/// Options of `proxima demo-platformer`.
struct PlatformerDemoOptions {
  PlatformerConfig config;                               ///< scene settings (projectile_ccd is set per run)
  std::string svg_path = "proxima-demo-platformer.svg";  ///< where the picture goes; empty: none
  std::string png_path =
      "proxima-demo-platformer.png";  ///< one frame of the continuous run drawn by proxima render; empty: none
  int png_frame = 439;                ///< the frame drawn in the PNG (clamped to the run): the last impact
  bool quiet = false;                 ///< print nothing on success
};

/// Two panels, one above the other: the continuous run (projectiles stopped at the wall, their
/// impacts marked) and the discrete run (the projectiles that passed the wall dashed red);
/// both show the tiled ground with its seams, the wall and the player every 10 frames.
std::string render_platformer_svg(const PlatformerRun& continuous, const PlatformerRun& discrete);

/// What the PNG adds to the world's own drawing, up to the run's last frame: the player's
/// outline every 10 frames (User layer), each projectile's track from its muzzle (Sweeps
/// layer; green: stopped, red: passed the wall, yellow: in flight), and a title (Text).
DrawBuffer platformer_overlay(const PlatformerRun& run);

/// How the PNG's capture is made: an orthographic camera looking down -z at the plane, y up,
/// the scene's 62 m by 11 m filling a picture of 1240 x 220 pixels; contacts without depth
/// labels (the projectiles held at the wall touch it).
debug::CaptureOptions platformer_capture();

/// The statistics lines of both runs.
std::string platformer_report(const PlatformerRun& continuous, const PlatformerRun& discrete);

/// Runs the demo; returns the exit status (0, or 1 when a picture cannot be written).
int run_platformer_demo(const PlatformerDemoOptions& options, std::ostream& out, std::ostream& err);

}  // namespace proxima::tool
