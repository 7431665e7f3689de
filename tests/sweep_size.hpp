#pragma once
/// @file sweep_size.hpp
/// The number of cases a long seeded sweep runs. The release and double builds run every
/// sweep in full; the sanitizer build sets PROXIMA_TEST_SWEEP (a fraction in (0, 1]) in its
/// test preset, so that its slowest sweeps run a seeded prefix of the same cases. A factor
/// above 1 (at most 1000) runs longer sweeps for figures taken by hand (docs/validation.md),
/// whose first cases are the full sweep's.
#include <algorithm>
#include <cstdlib>

namespace proxima::test {

/// The share of each long sweep to run: PROXIMA_TEST_SWEEP when it is a number in (0, 1000],
/// else 1.
inline double sweep_fraction() {
  static const double fraction = [] {
    const char* text = std::getenv("PROXIMA_TEST_SWEEP");
    if (text == nullptr) return 1.0;
    const double f = std::strtod(text, nullptr);
    return f > 0.0 && f <= 1000.0 ? f : 1.0;
  }();
  return fraction;
}

/// `full` cases scaled by sweep_fraction(), never fewer than min(full, 8).
inline int sweep_size(int full) {
  const int scaled = static_cast<int>(full * sweep_fraction());
  return std::max(scaled, std::min(full, 8));
}

/// A count that a full sweep must exceed, scaled like the sweep: `full` x sweep_fraction().
inline int sweep_share(int full) { return static_cast<int>(full * sweep_fraction()); }

}  // namespace proxima::test
