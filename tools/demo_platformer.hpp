#pragma once
// `proxima demo-platformer`: the 2D platformer scene (platformer_scene.hpp) run twice — the
// projectiles with continuous detection and without — its statistics printed and both runs
// drawn as an SVG.
#include <iosfwd>
#include <string>

#include "platformer_scene.hpp"

namespace proxima::tool {

/// Options of `proxima demo-platformer`.
struct PlatformerDemoOptions {
  PlatformerConfig config;                               ///< scene settings (projectile_ccd is set per run)
  std::string svg_path = "proxima-demo-platformer.svg";  ///< where the picture goes; empty: none
  bool quiet = false;                                    ///< print nothing on success
};

/// Two panels, one above the other: the continuous run (projectiles stopped at the wall, their
/// impacts marked) and the discrete run (the projectiles that passed the wall dashed red);
/// both show the tiled ground with its seams, the wall and the player every 10 frames.
std::string render_platformer_svg(const PlatformerRun& continuous, const PlatformerRun& discrete);

/// The statistics lines of both runs.
std::string platformer_report(const PlatformerRun& continuous, const PlatformerRun& discrete);

/// Runs the demo; returns the exit status (0, or 1 when the SVG cannot be written).
int run_platformer_demo(const PlatformerDemoOptions& options, std::ostream& out, std::ostream& err);

}  // namespace proxima::tool
