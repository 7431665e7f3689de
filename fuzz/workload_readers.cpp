// Fuzz target: the workload readers of support/ (the formats of shared/bench/FORMATS.md,
// W1 to W9). The first byte picks the reader, the rest is the file's text (written to a
// file of this process's own, since the readers take paths). Every reader either refuses
// the text (an Error) or returns records whose numbers are finite, and the motion rules of
// the accepted W1, W8 and W9 worlds give finite poses for the first frames. The readers
// that open the other files a header names (read_world_workload, read_convex_workload,
// read_ccd_workload) are left out: a fuzzed name would reach any file of the machine.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>
#include <support/polygons2d_workloads.hpp>
#include <support/sprite_workloads.hpp>
#include <support/workloads.hpp>
#include <support/world2d_workloads.hpp>
#include <support/world_workloads.hpp>
#include <unistd.h>

#include "fuzz_support.hpp"

namespace pf = proxima::fuzz;
using namespace proxima;
using namespace proxima::bench;

namespace {

const std::string& input_path() {
  static const std::string path = "/tmp/proxima_fuzz_workload_" + std::to_string(::getpid()) + ".txt";
  return path;
}

bool finite(const Vec3d& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

void check_w1(const BroadphaseWorkload& w) {
  std::vector<BroadphaseBox> boxes = w.boxes;
  for (int frame = 0; frame < 3; ++frame) {
    for (const BroadphaseBox& b : boxes) {
      pf::check(finite(b.center) && finite(b.half_extents) && finite(b.velocity), "W1: box not finite");
    }
    advance_frame(boxes, w.dt, w.lo, w.hi);
  }
}

void check_world(const World& w) {
  for (std::size_t i = 0; i < std::min<std::size_t>(w.objects.size(), 16); ++i) {
    for (int frame : {0, 1, w.frames}) {
      const Pose p = pose_at_frame(w, i, frame);
      pf::check(finite(p.position) && std::isfinite(p.rotation.w) && std::isfinite(p.rotation.x) &&
                    std::isfinite(p.rotation.y) && std::isfinite(p.rotation.z),
                "W8: pose not finite");
    }
  }
}

void check_world2d(const World2d& w) {
  for (std::size_t i = 0; i < std::min<std::size_t>(w.objects.size(), 16); ++i) {
    for (int frame : {0, 1, w.frames}) {
      const Pose2d p = pose2d_at_frame(w, i, frame);
      pf::check(std::isfinite(p.position.x) && std::isfinite(p.position.y) && std::isfinite(p.angle),
                "W9 world: pose not finite");
    }
  }
}

void read_with(std::uint8_t which, const std::string& path) {
  switch (which % 18) {
    case 0: (void)read_header(path); break;
    case 1:
      if (auto w = read_broadphase(path); w.ok()) check_w1(w.value());
      break;
    case 2: (void)read_convex_shapes(path); break;
    case 3: (void)read_convex_pairs(path); break;
    case 4: (void)read_box_pairs(path); break;
    case 5: (void)read_obj(path); break;
    case 6: (void)read_mesh_poses(path); break;
    case 7: (void)read_rays(path); break;
    case 8: (void)read_ccd_pairs(path); break;
    case 9: (void)read_sphere_pairs(path); break;
    case 10: (void)read_capsule_pairs(path); break;
    case 11:
      if (auto w = read_world(path); w.ok()) check_world(w.value());
      break;
    case 12: (void)read_bullets_expected(path); break;
    case 13:
      if (auto p = read_polygons2d_pairs(path); p.ok()) (void)to_d2_pairs(p.value());
      break;
    case 14: (void)read_sprite_masks(path); break;
    case 15: (void)read_sprite_workload(path); break;
    case 16: (void)read_sprites_expected(path); break;
    default:
      if (auto w = read_world2d(path); w.ok()) check_world2d(w.value());
      break;
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  pf::start_target();
  if (size == 0) return 0;
  {
    std::ofstream out(input_path(), std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data + 1), static_cast<std::streamsize>(size - 1));
  }
  read_with(data[0], input_path());
  std::remove(input_path().c_str());
  return 0;
}
