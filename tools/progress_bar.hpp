#pragma once
// Progress bars of long command-line work (benchmarks, mesh hierarchies, long world runs):
// drawn on standard error when it is a terminal, silent otherwise (a pipe or a file gets
// nothing).
#include <cstddef>
#include <ostream>
#include <string>
#include <string_view>

namespace proxima::tool {

/// One bar: "\r[#####     ] 5/10 frames" (`width` cells; a total of 0 shows a full bar).
std::string progress_line(std::size_t done, std::size_t total, std::string_view unit, int width = 40);

/// True when standard error is a terminal (isatty): where progress bars are drawn.
bool stderr_is_terminal();

/// True when standard output is a terminal (a bar would interleave with what is printed).
bool stdout_is_terminal();

/// A progress bar on `out`, redrawn each time another thousandth of the total is done (so
/// at most about 1000 times, however many updates), and once at the end; writes nothing when
/// disabled.
class ProgressBar {
 public:
  /// A bar over `total` items named `unit`; `enabled` false: silent.
  ProgressBar(std::ostream& out, bool enabled, std::size_t total, std::string unit)
      : out_(out), enabled_(enabled), total_(total), unit_(std::move(unit)) {}
  /// Shows `done` items finished (a newline once done reaches the total; nothing after).
  void update(std::size_t done);

 private:
  std::ostream& out_;
  bool enabled_;
  std::size_t total_;
  std::string unit_;
  bool drawn_ = false;     ///< a line has been drawn
  bool finished_ = false;  ///< the last line (done >= total) has been drawn
  std::size_t step_ = 0;   ///< thousandths done at the last line drawn
};

}  // namespace proxima::tool
