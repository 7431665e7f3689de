// `proxima bench broadphase`: one structure on one W1 workload (see bench_command.hpp).
// Steps: 1. read the W1 file; 2. insert every box of frame 0 (timed: build); 3. per frame:
// W1 motion (double), boxes rounded to Real, update(span) + find_pairs (timed), checksum;
// 4. reference checksums by a double-precision grid search of the same frames (exact
// boxes, and boxes rounded to Real as the structure stores them); 5. report.
#include "bench_command.hpp"

#include <proxima/broadphase/any_broadphase.hpp>
#include <proxima/core/executor.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iomanip>
#include <ostream>
#include <sstream>
#include <string_view>

#include "progress_bar.hpp"
#include "support/w1_grid_pairs.hpp"

namespace proxima::tool {

namespace {

std::uint64_t mix64(std::uint64_t x) {
  std::uint64_t z = x + 0x9E3779B97F4A7C15ull;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

struct BoxD {
  double lo[3];
  double hi[3];
};

void advance(std::vector<W1Box>& boxes, double dt, double lo, double hi) {
  for (W1Box& b : boxes) {
    for (int k = 0; k < 3; ++k) {
      double x = b.c[k] + b.v[k] * dt;
      if (x < lo) {
        x = 2 * lo - x;
        b.v[k] = -b.v[k];
      } else if (x > hi) {
        x = 2 * hi - x;
        b.v[k] = -b.v[k];
      }
      b.c[k] = x;
    }
  }
}

void boxes_of(const std::vector<W1Box>& boxes, bool rounded, std::vector<BoxD>& out) {
  out.resize(boxes.size());
  for (std::size_t i = 0; i < boxes.size(); ++i) {
    for (int k = 0; k < 3; ++k) {
      out[i].lo[k] = boxes[i].c[k] - boxes[i].h[k];
      out[i].hi[k] = boxes[i].c[k] + boxes[i].h[k];
      if (rounded) {
        out[i].lo[k] = double(Real(out[i].lo[k]));
        out[i].hi[k] = double(Real(out[i].hi[k]));
      }
    }
  }
}

std::string hex(std::uint64_t v) {
  char buffer[17];
  std::snprintf(buffer, sizeof buffer, "%016llx", static_cast<unsigned long long>(v));
  return buffer;
}

std::string describe(const W1Checksum& c) { return "pairs=" + std::to_string(c.pairs) + " hash=" + hex(c.hash); }

using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point t0) { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); }

}  // namespace

void W1Checksum::add(std::uint64_t i, std::uint64_t j, std::uint64_t n) {
  const std::uint64_t a = std::min(i, j);
  const std::uint64_t b = std::max(i, j);
  ++pairs;
  hash += mix64(a * n + b);
}

bool read_w1(const std::string& path, W1Workload& out, std::string& error) {
  std::ifstream in(path);
  if (!in) {
    error = path + ": cannot open";
    return false;
  }
  std::string line;
  int line_no = 0;
  std::size_t n = 0;
  bool have_header = false;
  out = {};
  const std::size_t slash = path.find_last_of('/');
  out.name = path.substr(slash == std::string::npos ? 0 : slash + 1);
  if (const std::size_t dot = out.name.rfind('.'); dot != std::string::npos) out.name.resize(dot);
  while (std::getline(in, line)) {
    ++line_no;
    const std::size_t first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos || line[first] == '#') continue;
    std::istringstream fields(line);
    if (!have_header) {
      std::string kind;
      int version = 0;
      fields >> kind >> version;
      if (kind != "broadphase" || version != 1) {
        error = path + ":" + std::to_string(line_no) + ": not a W1 file (header 'broadphase 1 ...' expected)";
        return false;
      }
      bool have_n = false;
      std::string token;
      while (fields >> token) {
        const std::size_t eq = token.find('=');
        if (eq == std::string::npos) continue;
        const std::string key = token.substr(0, eq);
        const std::string value = token.substr(eq + 1);
        try {
          if (key == "n") {
            n = std::stoull(value);
            have_n = true;
          } else if (key == "frames") {
            out.frames = std::stoi(value);
          } else if (key == "dt") {
            out.dt = std::stod(value);
          } else if (key == "lo") {
            out.lo = std::stod(value);
          } else if (key == "hi") {
            out.hi = std::stod(value);
          } else if (key == "name") {
            out.name = value;
          }
        } catch (const std::exception&) {
          error = path + ":" + std::to_string(line_no) + ": bad value of " + key;
          return false;
        }
      }
      if (!have_n) {
        error = path + ":" + std::to_string(line_no) + ": header lacks n=";
        return false;
      }
      if (!std::isfinite(out.dt) || out.dt < 0.0 || !std::isfinite(out.lo) || !std::isfinite(out.hi) ||
          !(out.lo <= out.hi) || out.frames < 0) {
        error =
            path + ":" + std::to_string(line_no) + ": dt (finite, >= 0), lo <= hi (finite) and frames >= 0 required";
        return false;
      }
      out.boxes.reserve(std::min<std::size_t>(n, std::size_t(1) << 20));  // n is checked against the records
      have_header = true;
      continue;
    }
    W1Box b{};
    if (!(fields >> b.c[0] >> b.c[1] >> b.c[2] >> b.h[0] >> b.h[1] >> b.h[2] >> b.v[0] >> b.v[1] >> b.v[2])) {
      error = path + ":" + std::to_string(line_no) + ": expected 9 numbers";
      return false;
    }
    bool finite = true;
    for (int k = 0; k < 3; ++k) finite = finite && std::isfinite(b.c[k]) && std::isfinite(b.v[k]) && b.h[k] >= 0.0;
    if (!finite || !std::all_of(b.h, b.h + 3, [](double h) { return std::isfinite(h); })) {
      error = path + ":" + std::to_string(line_no) + ": centre, half extents (>= 0) and velocity must be finite";
      return false;
    }
    out.boxes.push_back(b);
  }
  if (!have_header) {
    error = path + ": empty file";
    return false;
  }
  if (out.boxes.size() != n) {
    error = path + ": " + std::to_string(out.boxes.size()) + " records, header says n=" + std::to_string(n);
    return false;
  }
  return true;
}

int run_bench_broadphase(const BenchBroadphaseOptions& options, std::ostream& out, std::ostream& err,
                         BenchBroadphaseResult* result) {
  W1Workload w;
  std::string error;
  if (!read_w1(options.workload, w, error)) {
    err << "proxima bench: " << error << "\n";
    return 1;
  }
  auto made = make_broadphase(options.structure);
  if (!made) {
    err << "proxima bench: " << made.error().what() << "\n";
    return 1;
  }
  std::unique_ptr<AnyBroadPhase> s = std::move(made).value();
  const int frames = options.frames > 0 ? options.frames : std::max(1, w.frames);
  const std::size_t n = w.boxes.size();

  BenchBroadphaseResult r;
  r.frames = frames;
  std::vector<W1Box> state = w.boxes;
  std::vector<BoxD> boxes;
  boxes_of(state, false, boxes);
  auto to_aabb = [](const BoxD& b) {
    return Aabb{Vec3(Real(b.lo[0]), Real(b.lo[1]), Real(b.lo[2])), Vec3(Real(b.hi[0]), Real(b.hi[1]), Real(b.hi[2]))};
  };
  const auto build_start = Clock::now();
  for (std::size_t i = 0; i < n; ++i) {
    if (s->insert(ProxyId(i), to_aabb(boxes[i]), ProxyKind::Moving, {}) != BroadPhaseStatus::Ok) {
      err << "proxima bench: box " << i << " rejected\n";
      return 1;
    }
  }
  s->rebuild();
  r.build_ms = ms_since(build_start);

  std::vector<ProxyUpdate> updates(n);
  std::vector<ProxyPair> pairs;
  ThreadPool pool(options.threads);  // the executor of find_pairs (started before the timing)
  double frame_ms = 0;
  ProgressBar progress(err, options.progress && frames >= 2, std::size_t(frames), "frames");
  for (int f = 0; f < frames; ++f) {
    advance(state, w.dt, w.lo, w.hi);
    boxes_of(state, false, boxes);
    const auto t0 = Clock::now();
    for (std::size_t i = 0; i < n; ++i) updates[i] = {ProxyId(i), to_aabb(boxes[i])};
    s->update(std::span<const ProxyUpdate>(updates));
    s->find_pairs(pairs, pool);
    frame_ms += ms_since(t0);
    for (const ProxyPair& p : pairs) r.checksum.add(p.lo, p.hi, n);
    progress.update(std::size_t(f) + 1);
  }
  r.ms_per_frame = frame_ms / frames;
  r.pairs_per_frame = double(r.checksum.pairs) / frames;

  int status = 0;
  std::string verdict = "not checked";
  if (options.check) {
    std::vector<W1Box> ref_state = w.boxes;
    std::vector<BoxD> exact;
    std::vector<BoxD> rounded;
    for (int f = 0; f < frames; ++f) {
      advance(ref_state, w.dt, w.lo, w.hi);
      boxes_of(ref_state, false, exact);
      boxes_of(ref_state, true, rounded);
      bench::w1_grid_pairs(exact, r.reference);
      bench::w1_grid_pairs(rounded, r.reference_rounded);
    }
    if (r.checksum == r.reference) {
      verdict = "agrees with the exact (double) reference";
    } else if (r.checksum == r.reference_rounded) {
      verdict = "agrees with the reference of the boxes rounded to " +
                std::string(sizeof(Real) == 4 ? "float" : "double") + " (rounding makes " +
                std::to_string(r.reference_rounded.pairs - r.reference.pairs) + " more touching pairs)";
    } else {
      verdict = "DISAGREES with the reference";
      status = 2;
    }
  }

  out << std::fixed;
  out << "workload:    " << w.name << " (" << n << " boxes, " << frames << " frames)\n";
  out << "structure:   " << options.structure << " (" << options.threads << " thread"
      << (options.threads == 1 ? "" : "s") << (s->parallel() || options.threads == 1 ? "" : "; serial structure")
      << ")\n";
  out << "build:       " << std::setprecision(3) << r.build_ms << " ms\n";
  out << "per frame:   " << std::setprecision(3) << r.ms_per_frame << " ms (update every box + find pairs)\n";
  out << "pairs/frame: " << std::setprecision(1) << r.pairs_per_frame << "\n";
  out << "checksum:    " << describe(r.checksum) << "\n";
  if (options.check) {
    out << "reference:   " << describe(r.reference) << " (exact), " << describe(r.reference_rounded) << " (rounded)\n";
  }
  out << "check:       " << verdict << "\n";
  if (result != nullptr) *result = r;
  return status;
}

}  // namespace proxima::tool
