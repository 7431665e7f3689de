// The replay main of a fuzz target in ordinary builds: runs LLVMFuzzerTestOneInput once on
// every file named on the command line and every file of every folder named there (sorted by
// name), the way libFuzzer runs a corpus with -runs=0. A target reports a violation by
// aborting, so reaching the end means every input passed. The floating-point "invalid"
// trap is on (fuzz_support.hpp), as in the tests.
//
// With `--mutate-runs=N` and/or `--mutate-seconds=S` (before the paths) it then mutates the
// inputs for N runs or S seconds of wall-clock time, whichever ends first, without coverage
// feedback (the bounded run CI makes in the sanitizer build, by runs so that it is the same
// on any machine; campaigns use libFuzzer, docs/validation.md): each round takes a random input and
// applies one to eight of libFuzzer's simpler mutations (flip a bit, set a byte to a random
// or boundary value, insert or erase bytes, copy a run within the input, splice another
// input's tail, change an ASCII digit), at most 4,096 bytes. The seed is `--seed=N` or the
// clock's, printed first. Before a violation aborts (SIGABRT), a crash (SIGSEGV, SIGFPE,
// SIGILL, SIGBUS) or a sanitizer ends the run (its death callback), the input at hand is
// printed in hex, so that the log reproduces it.
#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <string>
#include <unistd.h>
#include <vector>

#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);
// The sanitizers' hook called before they end the process (present only in sanitizer builds).
extern "C" void __sanitizer_set_death_callback(void (*callback)()) __attribute__((weak));

namespace {

constexpr std::size_t kMaxMutatedBytes = 4096;

std::vector<std::filesystem::path> input_files(const std::vector<std::string>& paths) {
  std::vector<std::filesystem::path> files;
  for (const std::string& p : paths) {
    const std::filesystem::path path(p);
    if (std::filesystem::is_directory(path)) {
      std::vector<std::filesystem::path> inside;
      for (const auto& entry : std::filesystem::directory_iterator(path)) {
        if (entry.is_regular_file()) inside.push_back(entry.path());
      }
      std::sort(inside.begin(), inside.end());
      files.insert(files.end(), inside.begin(), inside.end());
    } else {
      files.push_back(path);
    }
  }
  return files;
}

// The mutated input being run, for the signal handler (written before each run).
std::uint8_t g_current[kMaxMutatedBytes];
std::size_t g_current_size = 0;
volatile std::sig_atomic_t g_mutating = 0;

// Async-signal-safe: the input at hand in hex on stderr.
void print_current() {
  if (g_mutating) {
    static const char kHex[] = "0123456789abcdef";
    const char head[] = "\nmutated input that failed (hex):\n";
    (void)!::write(2, head, sizeof(head) - 1);
    char line[2 * 64 + 1];
    for (std::size_t i = 0; i < g_current_size; i += 64) {
      std::size_t n = 0;
      for (std::size_t k = i; k < std::min(g_current_size, i + 64); ++k) {
        line[n++] = kHex[g_current[k] >> 4];
        line[n++] = kHex[g_current[k] & 15];
      }
      line[n++] = '\n';
      (void)!::write(2, line, n);
    }
  }
}

// A violation (abort) or a crash without a sanitizer: the input, then the default action.
void print_current_and_die(int signal) {
  print_current();
  std::signal(signal, SIG_DFL);
  std::raise(signal);
}

// One of libFuzzer's simpler mutations, applied in place (`other` for splicing).
void mutate_once(std::vector<std::uint8_t>& d, const std::vector<std::uint8_t>& other, std::mt19937_64& rng) {
  auto pick = [&](std::size_t n) { return n == 0 ? std::size_t(0) : std::size_t(rng() % n); };
  static const std::uint8_t kBoundary[] = {0x00, 0x01, 0x7f, 0x80, 0xff, 0xfe, 0x20, 0x2d};
  switch (rng() % 8) {
    case 0:
      if (!d.empty()) d[pick(d.size())] ^= std::uint8_t(1u << (rng() % 8));
      break;
    case 1:
      if (!d.empty()) d[pick(d.size())] = std::uint8_t(rng());
      break;
    case 2:
      if (!d.empty()) d[pick(d.size())] = kBoundary[pick(sizeof(kBoundary))];
      break;
    case 3: {
      const std::size_t at = pick(d.size() + 1);
      d.insert(d.begin() + std::ptrdiff_t(at), 1 + pick(8), std::uint8_t(rng()));
      break;
    }
    case 4:
      if (!d.empty()) {
        const std::size_t at = pick(d.size());
        const std::size_t n = std::min(d.size() - at, 1 + pick(16));
        d.erase(d.begin() + std::ptrdiff_t(at), d.begin() + std::ptrdiff_t(at + n));
      }
      break;
    case 5:
      if (!d.empty()) {
        const std::size_t from = pick(d.size());
        const std::size_t n = std::min(d.size() - from, 1 + pick(32));
        const std::vector<std::uint8_t> run(d.begin() + std::ptrdiff_t(from), d.begin() + std::ptrdiff_t(from + n));
        d.insert(d.begin() + std::ptrdiff_t(pick(d.size() + 1)), run.begin(), run.end());
      }
      break;
    case 6:
      if (!other.empty()) {
        d.resize(pick(d.size() + 1));
        const std::size_t from = pick(other.size());
        d.insert(d.end(), other.begin() + std::ptrdiff_t(from), other.end());
      }
      break;
    default:
      for (std::size_t k = 0, at = pick(d.size()); k < d.size(); ++k, at = (at + 1) % d.size()) {
        if (d[at] >= '0' && d[at] <= '9') {
          d[at] = std::uint8_t('0' + rng() % 10);
          break;
        }
      }
      break;
  }
  if (d.size() > kMaxMutatedBytes) d.resize(kMaxMutatedBytes);
}

// Mutates the corpus for at most `max_runs` runs and `seconds` of wall-clock time (0: no
// bound of that kind); returns the number of runs.
std::size_t mutate_for(const std::vector<std::vector<std::uint8_t>>& corpus, std::size_t max_runs, double seconds,
                       std::uint64_t seed) {
  // Under a sanitizer its own handlers report crashes (then call the death callback); a
  // target's violation aborts either way.
  if (__sanitizer_set_death_callback != nullptr) {
    __sanitizer_set_death_callback(print_current);
    std::signal(SIGABRT, print_current_and_die);
  } else {
    for (const int s : {SIGABRT, SIGSEGV, SIGFPE, SIGILL, SIGBUS}) std::signal(s, print_current_and_die);
  }
  std::mt19937_64 rng(seed);
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  std::size_t runs = 0;
  g_mutating = 1;
  while ((max_runs == 0 || runs < max_runs) && (seconds == 0 || std::chrono::steady_clock::now() < end)) {
    std::vector<std::uint8_t> d = corpus[rng() % corpus.size()];
    const std::vector<std::uint8_t>& other = corpus[rng() % corpus.size()];
    for (std::size_t m = 1 + rng() % 8; m > 0; --m) mutate_once(d, other, rng);
    g_current_size = d.size();
    if (!d.empty()) std::memcpy(g_current, d.data(), d.size());
    LLVMFuzzerTestOneInput(d.data(), d.size());
    ++runs;
  }
  g_mutating = 0;
  return runs;
}

}  // namespace

int main(int argc, char** argv) {
  proxima::fuzz::enable_traps();
  double mutate_seconds = 0;
  std::size_t mutate_runs = 0;
  std::uint64_t seed = static_cast<std::uint64_t>(std::chrono::system_clock::now().time_since_epoch().count());
  std::vector<std::string> paths;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg.rfind("--mutate-runs=", 0) == 0) {
      mutate_runs = static_cast<std::size_t>(std::strtoull(arg.c_str() + 14, nullptr, 10));
    } else if (arg.rfind("--mutate-seconds=", 0) == 0) {
      mutate_seconds = std::strtod(arg.c_str() + 17, nullptr);
    } else if (arg.rfind("--seed=", 0) == 0) {
      seed = std::strtoull(arg.c_str() + 7, nullptr, 10);
    } else {
      paths.push_back(arg);
    }
  }
  const std::vector<std::filesystem::path> files = input_files(paths);
  if (files.empty() || !(mutate_seconds >= 0)) {
    std::fprintf(
        stderr, "usage: %s [--mutate-runs=N] [--mutate-seconds=S] [--seed=N] CORPUS_DIR_OR_FILE...  (no input found)\n",
        argv[0]);
    return 2;
  }
  std::vector<std::vector<std::uint8_t>> corpus;
  for (const std::filesystem::path& file : files) {
    std::ifstream in(file, std::ios::binary);
    if (!in) {
      std::fprintf(stderr, "cannot read %s\n", file.c_str());
      return 2;
    }
    const std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::fprintf(stderr, "%s\n", file.c_str());
    corpus.emplace_back(bytes.begin(), bytes.end());
    LLVMFuzzerTestOneInput(corpus.back().data(), corpus.back().size());
  }
  std::fprintf(stderr, "replayed %zu inputs\n", files.size());
  if (mutate_seconds > 0 || mutate_runs > 0) {
    std::fprintf(stderr, "mutating for %zu runs (0: any) and %g s (0: any), seed %llu\n", mutate_runs, mutate_seconds,
                 static_cast<unsigned long long>(seed));
    const std::size_t runs = mutate_for(corpus, mutate_runs, mutate_seconds, seed);
    std::fprintf(stderr, "ran %zu mutated inputs, no violation\n", runs);
  }
  return 0;
}
