// Progress bars (progress_bar.hpp).
#include "progress_bar.hpp"

#include <algorithm>
#include <unistd.h>

namespace proxima::tool {

std::string progress_line(std::size_t done, std::size_t total, std::string_view unit, int width) {
  const std::size_t cells = static_cast<std::size_t>(std::max(width, 1));
  const std::size_t filled = total == 0 ? cells : std::min(done, total) * cells / total;
  std::string line = "\r[";
  line.append(filled, '#').append(cells - filled, ' ').append("] ");
  line.append(std::to_string(done)).append("/").append(std::to_string(total)).append(" ").append(unit);
  return line;
}

bool stderr_is_terminal() { return isatty(STDERR_FILENO) != 0; }

bool stdout_is_terminal() { return isatty(STDOUT_FILENO) != 0; }

void ProgressBar::update(std::size_t done) {
  if (!enabled_ || finished_) return;
  constexpr std::size_t kSteps = 1000;
  const std::size_t step = total_ == 0 ? kSteps : std::min(done, total_) * kSteps / total_;
  if (drawn_ && step == step_ && done < total_) return;
  out_ << progress_line(done, total_, unit_) << std::flush;
  drawn_ = true;
  step_ = step;
  if (done >= total_) {
    out_ << "\n";
    finished_ = true;
  }
}

}  // namespace proxima::tool
