#pragma once
// `proxima demo-tunnelling`: fires fast bullets at thin spinning plates in two collision
// worlds, one detecting the hits discretely (contacts at the frame poses: CcdMode::Off), one
// continuously (impacts over each frame's motion: CcdMode::Bullet), prints the statistics
// and draws both runs side by side as an SVG.
#include <iosfwd>
#include <string>

#include "tunnelling_scene.hpp"

namespace proxima::tool {

/// Options of `proxima demo-tunnelling`.
struct TunnellingDemoOptions {
  TunnellingConfig config;                               ///< scene and simulation settings
  std::string svg_path = "proxima-demo-tunnelling.svg";  ///< where the picture goes; empty: none
  std::string png_path =
      "proxima-demo-tunnelling.png";  ///< one frame of the continuous run drawn by proxima render; empty: none
  int png_frame = 30;                 ///< the frame drawn in the PNG (clamped to the run)
  bool quiet = false;                 ///< print nothing on success
};

/// Two panels side by side, the field seen from above: left the discrete run (tunnelled
/// bullets dashed red, with their frame poses and the contact they missed), right the
/// continuous run (each hit bullet stopped at its time of impact, the contact point marked,
/// the plate drawn at that time); the plates' sweeps (faint discs), their final poses, and
/// a legend with the counts.
std::string render_tunnelling_svg(const TunnellingScene& scene);

/// The statistics lines: the scene, each detector's hits, events, steps and time per step,
/// the tunnelled count; warnings for unexpected answers.
std::string tunnelling_report(const TunnellingScene& scene);

/// Runs the demo: simulates, writes the statistics to `out` (unless quiet) and the SVG.
/// Returns the process exit status (0, or 1 when the SVG cannot be written).
int run_tunnelling_demo(const TunnellingDemoOptions& options, std::ostream& out, std::ostream& err);

}  // namespace proxima::tool
