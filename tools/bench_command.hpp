#pragma once
// `proxima bench broadphase`: runs one broad-phase structure (by registry name) on a W1
// workload file (shared/bench FORMATS.md): builds it on frame 0, then for every frame moves
// the boxes by the W1 rule, updates the structure and enumerates the pairs; prints the build
// time, ms per frame, pairs per frame and whether the W1 pair checksum agrees with an
// independent double-precision sort-and-sweep of the same frames.
#include <cstdint>
#include <iosfwd>
#include <string>
#include <vector>

namespace proxima::tool {

/// Options of `proxima bench broadphase`.
struct BenchBroadphaseOptions {
  std::string structure = "grid";  ///< registry name (make_broadphase)
  std::string workload;            ///< W1 file
  int frames = 0;                  ///< frames to run; 0: the file's frames= value
  unsigned threads = 1;            ///< threads of the ThreadPool running find_pairs (parallel structures)
  bool progress = false;           ///< draw a progress bar on `err` (the CLI: when it is a terminal)
  bool check = true;               ///< compute the reference checksum
};

/// One box of a W1 workload: centre, half extents, velocity (double, as read).
struct W1Box {
  double c[3];  ///< centre at frame 0
  double h[3];  ///< half extents
  double v[3];  ///< velocity per frame
};

/// A W1 workload as read by the tool.
struct W1Workload {
  std::string name;          ///< header name=, or the file stem
  int frames = 0;            ///< header frames=
  double dt = 1;             ///< header dt=
  double lo = 0;             ///< header lo=
  double hi = 0;             ///< header hi=
  std::vector<W1Box> boxes;  ///< records in order
};

/// Reads a W1 file; on failure returns false and sets `error` ("<path>:<line>: <what>").
bool read_w1(const std::string& path, W1Workload& out, std::string& error);

/// W1 checksum: pair count and the wrapping sum of splitmix64(i N + j) over pairs i < j.
struct W1Checksum {
  std::uint64_t pairs = 0;  ///< pairs summed over frames
  std::uint64_t hash = 0;   ///< sum of mix64(i N + j) modulo 2^64
  /// Adds the pair {i, j} of an n-box workload.
  void add(std::uint64_t i, std::uint64_t j, std::uint64_t n);
  /// Exact equality.
  bool operator==(const W1Checksum&) const = default;
};

/// What a run measured.
struct BenchBroadphaseResult {
  double build_ms = 0;           ///< insert of every box (frame 0) and rebuild()
  double ms_per_frame = 0;       ///< update of every box + find_pairs, mean over frames
  double pairs_per_frame = 0;    ///< mean pairs per frame
  int frames = 0;                ///< frames run
  W1Checksum checksum;           ///< of the structure's pairs
  W1Checksum reference;          ///< exact boxes (double), when checked
  W1Checksum reference_rounded;  ///< boxes rounded to proxima::Real, when checked
};

/// Runs the benchmark; writes the report to `out`, progress and errors to `err`. Returns
/// the exit status: 0 when the checksum agrees (with the exact or the Real-rounded
/// reference) or was not checked, 2 when it disagrees, 1 on bad input.
int run_bench_broadphase(const BenchBroadphaseOptions& options, std::ostream& out, std::ostream& err,
                         BenchBroadphaseResult* result = nullptr);

}  // namespace proxima::tool
