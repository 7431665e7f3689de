// proxima: the command-line tool of the Proxima library.
//   proxima --version          version and scalar precision
//   proxima demo [options]     the billiard-break demo (statistics + SVG picture)
//   proxima demo-tunnelling    discrete against continuous detection of fast bullets (+ SVG)
//   proxima demo-platformer    a 2D platformer on the 2D collision world (+ SVG, PNG)
//   proxima query [FILE|-]     the JSON query protocol, one request per line
//   proxima world [FILE|-]     a collision world driven by JSON requests, one per line
//   proxima bench broadphase   one broad-phase structure on a W1 workload file
//   proxima mesh-info FILE     validation/repair report, bounds, volume, BVH of a mesh file
//   proxima render CAPTURE     a picture (PNG or SVG) of one step of a capture
//   proxima view CAPTURE       the web viewer and the capture, served on 127.0.0.1
#include <proxima/core/config.hpp>

#include <CLI/CLI.hpp>

#include <cmath>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>

#include "bench_command.hpp"
#include "capture_render.hpp"
#include "demo_billiards.hpp"
#include "demo_platformer.hpp"
#include "demo_tunnelling.hpp"
#include "json_shapes.hpp"
#include "mesh_info.hpp"
#include "progress_bar.hpp"
#include "query.hpp"
#include "query_operations.hpp"
#include "view_server.hpp"
#include "world2d_session.hpp"
#include "world_session.hpp"

namespace {

// A number option must be finite (CLI::Range lets NaN through: every comparison with it is
// false).
const CLI::Validator kFinite(
    [](std::string& text) {
      std::size_t used = 0;
      double value = 0.0;
      try {
        value = std::stod(text, &used);
      } catch (const std::exception&) {
        return std::string("not a number: ") + text;
      }
      return used == text.size() && std::isfinite(value) ? std::string() : "must be a finite number: " + text;
    },
    "FINITE");

std::string version_line() {
  return std::string("proxima ") + PROXIMA_VERSION_STRING + " (" + (PROXIMA_DOUBLE ? "double" : "float") +
         " precision)";
}

std::string query_footer() {
  std::string text = "\nOperations (\"op\"):\n";
  for (const auto& op : proxima::tool::operations()) {
    text += "  " + std::string(op.name) + ": " + std::string(op.synopsis) + "\n";
  }
  text += "Shape types: " + proxima::tool::shape_type_names() + "\n";
  text +=
      "Exit status: 0 when every line was answered, 2 when a line was rejected, 1 when the input\n"
      "cannot be read. See docs/query-protocol.md.";
  return text;
}

int run_query(const std::string& input) {
  if (input.empty() || input == "-") {
    return proxima::tool::exit_status(proxima::tool::run_queries(std::cin, std::cout));
  }
  std::ifstream file(input);
  if (!file || std::filesystem::is_directory(input)) {
    std::cerr << "proxima query: cannot open " << input << " (not a readable file)\n";
    return 1;
  }
  const int status = proxima::tool::exit_status(proxima::tool::run_queries(file, std::cout));
  if (file.bad()) {
    std::cerr << "proxima query: reading " << input << " failed\n";
    return 1;
  }
  return status;
}

std::string world_footer() {
  std::string text = "\nOperations (\"op\"):\n";
  for (const auto& op : proxima::tool::world_operations()) {
    text += "  " + std::string(op.name) + ": " + std::string(op.synopsis) + "\n";
  }
  text +=
      "Handles are the integers \"add\" answers. Shapes and poses as in `proxima query`.\n"
      "Exit status: 0 when every line was answered, 2 when a line was rejected, 1 when the input\n"
      "cannot be read or the options make no world. See docs/world-protocol.md.";
  return text;
}

/// The exit status after a run: 1 when writing the capture of --record failed.
template <class Session>
int record_status(const Session& session, const proxima::tool::WorldOptions& options, int status) {
  if constexpr (requires { session.record_failed(); }) {
    if (session.record_failed()) {
      std::cerr << "proxima world: writing " << options.record_path << " failed\n";
      return 1;
    }
  }
  return status;
}

/// Runs a world session (3D: WorldSession, 2D: WorldSession2d) over `input`.
template <class Session>
int run_world(const proxima::tool::WorldOptions& options, const std::string& input) {
  auto session = Session::create(options);
  if (!session.ok()) {
    std::cerr << "proxima world: " << session.error().what() << "\n";
    return 1;
  }
  if (input.empty() || input == "-") {
    return record_status(session.value(), options,
                         proxima::tool::exit_status(session.value().run(std::cin, std::cout)));
  }
  std::ifstream file(input);
  if (!file || std::filesystem::is_directory(input)) {
    std::cerr << "proxima world: cannot open " << input << " (not a readable file)\n";
    return 1;
  }
  // A bar over the request file's bytes, when it would not interleave with the answers.
  std::error_code size_error;
  const std::uintmax_t size = std::filesystem::file_size(input, size_error);
  proxima::tool::ProgressBar progress(
      std::cerr, !size_error && proxima::tool::stderr_is_terminal() && !proxima::tool::stdout_is_terminal(),
      size_error ? 0 : static_cast<std::size_t>(size), "bytes of requests");
  const int status = proxima::tool::exit_status(session.value().run(file, std::cout, &progress));
  if (file.bad()) {
    std::cerr << "proxima world: reading " << input << " failed\n";
    return 1;
  }
  return record_status(session.value(), options, status);
}

/// Options of `proxima render`.
struct RenderCommand {
  std::string capture;                   ///< the capture file
  std::size_t frame = 0;                 ///< the step drawn
  std::string output;                    ///< .png or .svg
  std::string view = "auto";             ///< auto, iso, top, front
  bool no_capture_camera = false;        ///< ignore the capture's camera
  proxima::tool::RenderOptions options;  ///< size, layers
};

int run_render(RenderCommand command) {
  std::ifstream file(command.capture);
  if (!file || std::filesystem::is_directory(command.capture)) {
    std::cerr << "proxima render: cannot open " << command.capture << " (not a readable file)\n";
    return 1;
  }
  const auto capture = proxima::tool::read_capture(file);
  if (!capture.ok()) {
    std::cerr << "proxima render: " << command.capture << ": " << capture.error().what() << "\n";
    return 1;
  }
  using proxima::tool::RenderView;
  command.options.view = command.view == "iso"     ? RenderView::Iso
                         : command.view == "top"   ? RenderView::Top
                         : command.view == "front" ? RenderView::Front
                                                   : RenderView::Auto;
  command.options.capture_camera = !command.no_capture_camera;
  if (auto e = proxima::tool::render_file(capture.value(), command.frame, command.options, command.output)) {
    std::cerr << "proxima render: " << e->what() << "\n";
    return 1;
  }
  return 0;
}

/// The running executable's path (/proc/self/exe), or argv[0] when that cannot be read.
std::filesystem::path executable_path(const char* argv0) {
  std::error_code ec;
  std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (!ec) return self;
  return std::filesystem::absolute(argv0 != nullptr ? argv0 : "", ec);
}

int run(int argc, char** argv) {
  std::ios::sync_with_stdio(false);
  CLI::App app{"proxima: collision detection from the command line (demo, JSON queries, a JSON-driven world)",
               "proxima"};
  app.set_version_flag("--version", version_line(), "Print the version and the scalar precision, then exit");
  app.require_subcommand(0, 1);

  proxima::tool::DemoOptions demo;
  CLI::App* demo_cmd = app.add_subcommand(
      "demo",
      "Billiard break on the collision world: 16 balls, 10 s at 60 Hz; prints the world's events and "
      "statistics, draws an SVG");
  demo_cmd->add_option("--frames", demo.config.frames, "Frames to simulate at 60 Hz")
      ->capture_default_str()
      ->check(CLI::Range(0, 1000000));
  demo_cmd->add_option("--svg", demo.svg_path, "Picture of the table and trajectories (empty: none)")
      ->capture_default_str();
  demo_cmd->add_option("--png", demo.png_path, "Picture of one frame drawn by proxima render (empty: none)")
      ->capture_default_str();
  demo_cmd->add_option("--png-frame", demo.png_frame, "The frame drawn in the PNG")
      ->capture_default_str()
      ->check(CLI::Range(0, 1000000));
  demo_cmd->add_option("--seed", demo.config.seed, "Jitter of the rack and the shot (0: perfectly symmetric)")
      ->capture_default_str();
  demo_cmd->add_option("--speed", demo.config.cue_speed, "Speed of the cue ball, m/s")
      ->capture_default_str()
      ->check(kFinite & CLI::Range(0.0, 1000.0));
  demo_cmd->add_option("--substeps", demo.config.substeps, "World steps per frame")
      ->capture_default_str()
      ->check(CLI::Range(1, 1000));
  demo_cmd->add_option("--broadphase", demo.config.broadphase, "The world's broad-phase structure, by name")
      ->capture_default_str();
  demo_cmd->add_flag("--quiet,-q", demo.quiet, "Print nothing (still writes the SVG)");

  proxima::tool::TunnellingDemoOptions tunnelling;
  CLI::App* tunnelling_cmd = app.add_subcommand("demo-tunnelling",
                                                "Fast bullets at thin spinning plates in two collision worlds: "
                                                "discrete (ccd off) against continuous (ccd bullet) "
                                                "detection; prints statistics, draws both runs side by side as an SVG");
  tunnelling_cmd->add_option("--frames", tunnelling.config.frames, "Frames to simulate at 60 Hz")
      ->capture_default_str()
      ->check(CLI::Range(0, 100000));
  tunnelling_cmd->add_option("--bullets", tunnelling.config.bullets, "Bullets fired, spread over the run")
      ->capture_default_str()
      ->check(CLI::Range(0, 100000));
  tunnelling_cmd->add_option("--png", tunnelling.png_path,
                             "Picture of one frame of the continuous run drawn by proxima render (empty: none)");
  tunnelling_cmd->add_option("--png-frame", tunnelling.png_frame, "The frame drawn in the PNG");
  tunnelling_cmd->add_option("--svg", tunnelling.svg_path, "Picture of both runs side by side (empty: none)")
      ->capture_default_str();
  tunnelling_cmd->add_option("--seed", tunnelling.config.seed, "Bullets' lanes, aims, speeds, sizes; plates' phases")
      ->capture_default_str();
  tunnelling_cmd->add_flag("--quiet,-q", tunnelling.quiet, "Print nothing (still writes the SVG)");

  proxima::tool::PlatformerDemoOptions platformer;
  CLI::App* platformer_cmd =
      app.add_subcommand("demo-platformer",
                         "A 2D platformer on the 2D collision world: a player walking over a tiled chain ground, "
                         "fast projectiles at a thin wall with and without continuous detection; prints statistics, "
                         "draws both runs as an SVG and one frame as a PNG");
  platformer_cmd->add_option("--frames", platformer.config.frames, "Frames to simulate at 60 Hz")
      ->capture_default_str()
      ->check(CLI::Range(1, 100000));
  platformer_cmd->add_option("--projectiles", platformer.config.projectiles, "Projectiles fired, spread over the run")
      ->capture_default_str()
      ->check(CLI::Range(0, 1000));
  platformer_cmd->add_option("--svg", platformer.svg_path, "Picture of both runs (empty: none)")->capture_default_str();
  platformer_cmd
      ->add_option("--png", platformer.png_path,
                   "Picture of one frame of the continuous run drawn by proxima render (empty: none)")
      ->capture_default_str();
  platformer_cmd->add_option("--png-frame", platformer.png_frame, "The frame drawn in the PNG")->capture_default_str();
  platformer_cmd->add_flag("--quiet,-q", platformer.quiet, "Print nothing (still writes the pictures)");

  std::string query_input;
  CLI::App* query_cmd = app.add_subcommand(
      "query", "Answer JSON requests, one per line, from FILE or standard input; one JSON answer per line");
  query_cmd->add_option("input", query_input, "Request file; '-' or absent: standard input");
  query_cmd->footer(query_footer());

  proxima::tool::WorldOptions world;
  std::string world_input;
  double world_contact_distance = 0.0;
  CLI::App* world_cmd = app.add_subcommand(
      "world",
      "Drive a collision world with JSON requests, one per line, from FILE or standard input; one JSON answer per "
      "line");
  world_cmd->add_option("input", world_input, "Request file; '-' or absent: standard input");
  world_cmd->add_option("--threads", world.threads, "Threads of the step's narrow phase (0: one per core)")
      ->capture_default_str()
      ->check(CLI::Range(0, 256));
  world_cmd->add_option("--broadphase", world.settings.broadphase, "Broad-phase structure (registry name)")
      ->capture_default_str();
  world_cmd
      ->add_option("--contact-distance", world_contact_distance,
                   "Pairs within this gap touch (length units; 0: touching or overlapping only)")
      ->capture_default_str()
      ->check(kFinite & CLI::Range(0.0, 1e18));
  world_cmd->add_flag("--sensors-sense-sensors", world.settings.sensors_sense_sensors,
                      "Two sensors report enter / exit of each other");
  world_cmd->add_option("--record", world.record_path,
                        "Write a capture of every step to this file (docs/capture-format.md; 3D worlds)");
  bool world_2d = false;
  world_cmd->add_flag("--2d", world_2d, "A 2D world: 2D shapes and poses (docs/world-protocol.md, \"2D worlds\")");
  world_cmd->footer(world_footer());

  proxima::tool::BenchBroadphaseOptions bench_broadphase;
  CLI::App* bench_cmd = app.add_subcommand("bench", "Benchmarks on workload files");
  bench_cmd->require_subcommand(1);
  CLI::App* bench_broadphase_cmd = bench_cmd->add_subcommand(
      "broadphase", "One broad-phase structure on a W1 workload: build time, ms/frame, pairs/frame, checksum");
  bench_broadphase_cmd->add_option("--structure", bench_broadphase.structure, "Structure name (registry)")
      ->capture_default_str();
  bench_broadphase_cmd->add_option("--workload", bench_broadphase.workload, "W1 broadphase file")->required();
  bench_broadphase_cmd->add_option("--frames", bench_broadphase.frames, "Frames to run (0: the file's frames=)")
      ->capture_default_str()
      ->check(CLI::Range(0, 1000000));
  bench_broadphase_cmd->add_option("--threads", bench_broadphase.threads, "Threads for the pair search")
      ->capture_default_str()
      ->check(CLI::Range(1, 256));
  bool bench_no_check = false;
  bench_broadphase_cmd->add_flag("--no-check", bench_no_check, "Skip the reference checksum");

  proxima::tool::MeshInfoOptions mesh_info;
  bool mesh_info_no_repair = false;
  CLI::App* mesh_info_cmd = app.add_subcommand(
      "mesh-info", "Validation and repair report, bounds, volume, surface area and BVH statistics of a mesh file");
  mesh_info_cmd->add_option("file", mesh_info.path, "Mesh file: OBJ, STL, PLY, OFF, glTF (anything assimp reads)")
      ->required();
  mesh_info_cmd->add_flag("--no-repair", mesh_info_no_repair, "Only analyse; build the mesh shape as given");
  mesh_info_cmd
      ->add_option("--weld", mesh_info.weld_distance,
                   "Weld vertices closer than this (length units; negative: 1e-5 (float) or 2e-14 (double) of the "
                   "box diagonal)")
      ->capture_default_str();
  mesh_info_cmd->add_flag("--json", mesh_info.json, "Print one JSON object instead of text");

  RenderCommand render;
  CLI::App* render_cmd = app.add_subcommand(
      "render", "Draw one step of a capture (docs/capture-format.md) as a PNG or SVG picture with cairo");
  render_cmd->add_option("capture", render.capture, "Capture file (proxima world --record, the demos)")->required();
  render_cmd->add_option("--frame", render.frame, "The step drawn (0: the first)")->capture_default_str();
  render_cmd->add_option("-o,--output", render.output, "Picture file: .png or .svg")->required();
  render_cmd->add_option("--width", render.options.width, "Pixels")->capture_default_str()->check(CLI::Range(16, 8192));
  render_cmd->add_option("--height", render.options.height, "Pixels")
      ->capture_default_str()
      ->check(CLI::Range(16, 8192));
  render_cmd
      ->add_option(
          "--layers", render.options.layers,
          "Layers drawn, comma-separated (shapes, bounds, bvh, broadphase, contacts, normals, sweeps, queries, "
          "text, user); default: all")
      ->delimiter(',');
  render_cmd->add_option("--view", render.view, "Default camera: auto, iso, top, front")
      ->capture_default_str()
      ->check(CLI::IsMember({"auto", "iso", "top", "front"}));
  render_cmd->add_flag("--no-capture-camera", render.no_capture_camera, "Ignore the capture's camera");

  proxima::tool::ViewOptions view;
  CLI::App* view_cmd = app.add_subcommand(
      "view",
      "Serve the web viewer and a capture on 127.0.0.1 and print the address; open it in a browser (Ctrl-C stops)");
  view_cmd->add_option("capture", view.capture, "Capture file (proxima world --record, the demos)")->required();
  view_cmd->add_option("--port", view.port, "TCP port on 127.0.0.1 (0: a free one)")
      ->capture_default_str()
      ->check(CLI::Range(0, 65535));
  view_cmd->add_option("--viewer-dir", view.viewer_dir,
                       "The viewer folder (default: $PROXIMA_VIEWER_DIR, <bin>/../share/proxima/viewer, then the "
                       "source tree's viewer/)");

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }

  try {
    if (demo_cmd->parsed()) return proxima::tool::run_billiards_demo(demo, std::cout, std::cerr);
    if (tunnelling_cmd->parsed()) return proxima::tool::run_tunnelling_demo(tunnelling, std::cout, std::cerr);
    if (platformer_cmd->parsed()) return proxima::tool::run_platformer_demo(platformer, std::cout, std::cerr);
    if (query_cmd->parsed()) return run_query(query_input);
    if (render_cmd->parsed()) return run_render(render);
    if (view_cmd->parsed()) return proxima::tool::run_view(view, executable_path(argv[0]), std::cout, std::cerr);
    if (world_cmd->parsed()) {
      world.settings.contact_distance = static_cast<proxima::Real>(world_contact_distance);
      return world_2d ? run_world<proxima::tool::WorldSession2d>(world, world_input)
                      : run_world<proxima::tool::WorldSession>(world, world_input);
    }
    if (mesh_info_cmd->parsed()) {
      mesh_info.repair = !mesh_info_no_repair;
      mesh_info.progress = proxima::tool::stderr_is_terminal();
      return proxima::tool::run_mesh_info(mesh_info, std::cout, std::cerr);
    }
    if (bench_broadphase_cmd->parsed()) {
      bench_broadphase.check = !bench_no_check;
      bench_broadphase.progress = proxima::tool::stderr_is_terminal();
      return proxima::tool::run_bench_broadphase(bench_broadphase, std::cout, std::cerr);
    }
  } catch (const std::exception& e) {
    std::cerr << "proxima: " << e.what() << "\n";
    return 1;
  }
  std::cout << app.help();
  return 1;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const std::exception& e) {
    std::cerr << "proxima: " << e.what() << "\n";
  } catch (...) {
    std::cerr << "proxima: unknown error\n";
  }
  return 1;
}
