// Fuzz target: a session of the world protocol (`proxima world`, docs/world-protocol.md):
// the input's lines (at most 64) answered in order by one tool::WorldSession, as the tool
// answers a request file. Every line gets an answer object that is either an answer or an
// error with a field and a code, and no number of an answer is NaN or infinite.
// Lines that could name files (save, load, mesh files) are skipped (json_checks.hpp).
#include <string_view>

#include "fuzz_support.hpp"
#include "json_checks.hpp"
#include "world_session.hpp"

namespace pf = proxima::fuzz;
using proxima::tool::Json;
using proxima::tool::WorldSession;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  pf::start_target();
  std::string_view rest(reinterpret_cast<const char*>(data), size);
  proxima::Result<WorldSession> made = WorldSession::create();
  pf::check(made.ok(), "WorldSession::create failed");
  WorldSession& session = made.value();
  for (int count = 0; count < 64 && !rest.empty(); ++count) {
    const std::size_t end = rest.find('\n');
    const std::string_view line = rest.substr(0, end);
    rest = end == std::string_view::npos ? std::string_view() : rest.substr(end + 1);
    if (line.find_first_not_of(" \t\r") == std::string_view::npos || pf::reaches_files(line)) continue;
    bool rejected = false;
    const Json answer = session.answer_line(line, rejected);
    pf::check_answer_shape(answer, rejected);
    pf::check_json_finite(answer);
  }
  return 0;
}
