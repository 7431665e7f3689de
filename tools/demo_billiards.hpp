#pragma once
// `proxima demo`: runs the billiard break, prints the detection statistics and draws the
// table with every ball's trajectory and every contact point as an SVG picture.
#include <iosfwd>
#include <string>

#include "billiard_table.hpp"

namespace proxima::tool {

/// Options of `proxima demo`.
struct DemoOptions {
  BilliardConfig config;                      ///< scene and simulation settings (frames, seed)
  std::string svg_path = "proxima-demo.svg";  ///< where the picture goes; empty: no picture
  std::string png_path = "proxima-demo.png";  ///< the world drawn by `proxima render` at png_frame; empty: none
  int png_frame = 40;                         ///< the frame drawn in the PNG (the last one when fewer are run)
  bool quiet = false;                         ///< print nothing on success
};

/// Draws the table, the trajectories (one polyline per ball, in the ball's colour; stripes
/// dashed), the contact points (white: ball-ball, yellow: cushion) and the final positions.
std::string render_billiards_svg(const BilliardTable& table);

/// Runs the demo: simulates, writes the statistics to `out` (unless quiet) and the SVG.
/// Returns the process exit status (0, or 1 when the SVG cannot be written).
int run_billiards_demo(const DemoOptions& options, std::ostream& out, std::ostream& err);

}  // namespace proxima::tool
