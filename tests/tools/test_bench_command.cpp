// `proxima bench broadphase`: the W1 reader, the checksum against an O(n^2) loop written
// here, every registered structure agreeing on a small workload with exactly touching boxes,
// bad input, and one end-to-end run of the executable.
#include <gtest/gtest.h>

#include <proxima/broadphase/any_broadphase.hpp>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <unistd.h>

#include "bench_command.hpp"

namespace proxima::tool {
namespace test_bench_command {

// A small W1 file: 300 boxes on a 0.25 lattice (half extents multiples of 0.25, so many
// boxes touch exactly), velocities of +-0.25 so they stay on the lattice, 6 frames.
// The file name holds the test's name and the process id: ctest runs the tests of this file
// in parallel processes, which must not rewrite each other's input.
std::string write_workload() {
  const std::string test = ::testing::UnitTest::GetInstance()->current_test_info()->name();
  const auto path = std::filesystem::temp_directory_path() /
                    ("proxima_test_bench_w1_" + test + "_" + std::to_string(::getpid()) + ".txt");
  std::ofstream out(path);
  out << "broadphase 1 n=300 frames=6 dt=1 lo=0 hi=12.000 name=tiny_touching\n";
  std::uint64_t state = 12345;
  auto next = [&](int m) {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    return int((state >> 33) % std::uint64_t(m));
  };
  for (int i = 0; i < 300; ++i) {
    for (int k = 0; k < 3; ++k) out << double(next(48)) * 0.25 << " ";
    for (int k = 0; k < 3; ++k) out << 0.25 * double(1 + next(4)) << " ";
    for (int k = 0; k < 3; ++k) out << (next(2) == 0 ? -0.25 : 0.25) << (k == 2 ? "\n" : " ");
  }
  return path.string();
}

// The checksum by an O(n^2) loop over the frames (W1 motion written again here).
W1Checksum brute_checksum(const W1Workload& w, int frames) {
  std::vector<W1Box> boxes = w.boxes;
  W1Checksum sum;
  for (int f = 0; f < frames; ++f) {
    for (W1Box& b : boxes) {
      for (int k = 0; k < 3; ++k) {
        double x = b.c[k] + b.v[k] * w.dt;
        if (x < w.lo || x > w.hi) {
          x = x < w.lo ? 2 * w.lo - x : 2 * w.hi - x;
          b.v[k] = -b.v[k];
        }
        b.c[k] = x;
      }
    }
    for (std::size_t i = 0; i < boxes.size(); ++i) {
      for (std::size_t j = i + 1; j < boxes.size(); ++j) {
        bool overlap = true;
        for (int k = 0; k < 3; ++k) {
          overlap = overlap && boxes[i].c[k] - boxes[i].h[k] <= boxes[j].c[k] + boxes[j].h[k] &&
                    boxes[j].c[k] - boxes[j].h[k] <= boxes[i].c[k] + boxes[i].h[k];
        }
        if (overlap) sum.add(i, j, boxes.size());
      }
    }
  }
  return sum;
}

TEST(BenchCommand, ReadsW1) {
  const std::string path = write_workload();
  W1Workload w;
  std::string error;
  ASSERT_TRUE(read_w1(path, w, error)) << error;
  EXPECT_EQ(w.name, "tiny_touching");
  EXPECT_EQ(w.boxes.size(), 300u);
  EXPECT_EQ(w.frames, 6);
  EXPECT_EQ(w.hi, 12.0);
  EXPECT_FALSE(read_w1(path + ".missing", w, error));
  const auto bad =
      std::filesystem::temp_directory_path() / ("proxima_test_bench_bad_" + std::to_string(::getpid()) + ".txt");
  std::ofstream(bad) << "broadphase 1 n=2 frames=1\n1 2 3 4 5 6 7 8 9\n";
  EXPECT_FALSE(read_w1(bad.string(), w, error));
  EXPECT_NE(error.find("n=2"), std::string::npos) << error;
  // Non-finite header values and records are refused (a NaN dt once divided by zero), and a
  // huge n reserves nothing it cannot hold.
  std::ofstream(bad) << "broadphase 1 n=1 frames=1 dt=nan\n1 2 3 4 5 6 7 8 9\n";
  EXPECT_FALSE(read_w1(bad.string(), w, error));
  EXPECT_NE(error.find("dt (finite"), std::string::npos) << error;
  std::ofstream(bad) << "broadphase 1 n=1 frames=1 lo=5 hi=1\n1 2 3 4 5 6 7 8 9\n";
  EXPECT_FALSE(read_w1(bad.string(), w, error));
  std::ofstream(bad) << "broadphase 1 n=1 frames=1\n1 2 3 4 -5 6 7 8 9\n";
  EXPECT_FALSE(read_w1(bad.string(), w, error));
  EXPECT_NE(error.find("half extents (>= 0)"), std::string::npos) << error;
  std::ofstream(bad) << "broadphase 1 n=1 frames=1\n1 2 inf 4 5 6 7 8 9\n";
  EXPECT_FALSE(read_w1(bad.string(), w, error));
  std::ofstream(bad) << "broadphase 1 n=1000000000000000 frames=1\n1 2 3 4 5 6 7 8 9\n";
  EXPECT_FALSE(read_w1(bad.string(), w, error));
  EXPECT_NE(error.find("header says"), std::string::npos) << error;
  std::filesystem::remove(bad);
}

TEST(BenchCommand, EveryStructureAgrees) {
  const std::string path = write_workload();
  W1Workload w;
  std::string error;
  ASSERT_TRUE(read_w1(path, w, error)) << error;
  const W1Checksum expected = brute_checksum(w, 6);
  EXPECT_GT(expected.pairs, 300u);
  for (const std::string_view name : broadphase_names()) {
    for (const unsigned threads : {1u, 2u}) {
      BenchBroadphaseOptions options;
      options.structure = std::string(name);
      options.workload = path;
      options.threads = threads;
      std::ostringstream out;
      std::ostringstream err;
      BenchBroadphaseResult result;
      EXPECT_EQ(run_bench_broadphase(options, out, err, &result), 0) << name << "\n" << out.str() << err.str();
      // Lattice coordinates are exact in float: no rounding difference.
      EXPECT_EQ(result.reference, expected) << name;
      EXPECT_EQ(result.checksum, expected) << name;
      EXPECT_EQ(result.frames, 6);
      EXPECT_NE(out.str().find("agrees with the exact"), std::string::npos) << out.str();
    }
  }
}

TEST(BenchCommand, BadInput) {
  std::ostringstream out;
  std::ostringstream err;
  BenchBroadphaseOptions options;
  options.workload = write_workload();
  options.structure = "no_such_structure";
  EXPECT_EQ(run_bench_broadphase(options, out, err), 1);
  EXPECT_NE(err.str().find("unknown broad-phase structure"), std::string::npos);
  options.structure = "grid";
  options.workload = "/nonexistent/w1.txt";
  EXPECT_EQ(run_bench_broadphase(options, out, err), 1);
}

TEST(BenchCommand, EndToEnd) {
  const std::string command = std::string("'") + PROXIMA_CLI_PATH + "' bench broadphase --structure hash --workload '" +
                              write_workload() + "' --frames 3 2>&1";
  FILE* pipe = popen(command.c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  std::string text;
  char buffer[256];
  while (std::fgets(buffer, sizeof buffer, pipe) != nullptr) text += buffer;
  const int status = pclose(pipe);
  EXPECT_EQ(status, 0) << text;
  EXPECT_NE(text.find("per frame:"), std::string::npos) << text;
  EXPECT_NE(text.find("(300 boxes, 3 frames)"), std::string::npos) << text;
  EXPECT_NE(text.find("check:       agrees"), std::string::npos) << text;
  EXPECT_EQ(text.find('\r'), std::string::npos) << "a progress bar on a pipe";
}

}  // namespace test_bench_command
}  // namespace proxima::tool
