#pragma once
/// @file bench_main.hpp
/// The shared entry point of the benchmark programs (header-only, for programs that link
/// Google Benchmark): finds the workload folder, initialises Google Benchmark, lets the
/// program register its benchmarks on the loaded workloads, and runs them.

#include <benchmark/benchmark.h>

#include <cstdint>
#include <iostream>
#include <string>

#include "support/workloads.hpp"

namespace proxima::bench {

/// Runs a benchmark program: strips `--workloads=DIR` (see workload_dir), initialises
/// Google Benchmark with the remaining arguments, calls `register_benchmarks(dir)`, which
/// loads what it needs and registers benchmarks (returning false, after printing why, when
/// a workload cannot be read), and runs them. Returns the process exit status.
template <class Register>
int run_benchmarks(int argc, char** argv, Register register_benchmarks) {
  const std::string dir = workload_dir(argc, argv);
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::AddCustomContext("workloads", dir);
  benchmark::AddCustomContext("proxima_real", sizeof(Real) == 4 ? "float" : "double");
  if (!register_benchmarks(dir)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}

/// Prints a reader error and returns false (for register functions).
inline bool report_load_error(const Error& error) {
  std::cerr << "cannot load a workload: " << error.what()
            << "\n(set the folder with --workloads=DIR or the PROXIMA_WORKLOADS environment variable)\n";
  return false;
}

/// A counter of the time per item, `items` per iteration (an inverted rate: Google
/// Benchmark prints it with an SI prefix, e.g. "47.2ns"; the JSON value is in seconds).
inline benchmark::Counter time_per_item(std::uint64_t items) {
  return benchmark::Counter(static_cast<double>(items),
                            benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

}  // namespace proxima::bench
