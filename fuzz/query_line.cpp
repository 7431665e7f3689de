// Fuzz target: one line of the query protocol (`proxima query`, docs/query-protocol.md),
// answered in-process by tool::answer_line as the tool answers each input line. Every line
// gets an answer object that is either an answer or an error with a field and a code (never
// an exception, a crash or a hang), and no number of the answer is NaN or infinite.
// The input is the line (up to its first newline); lines that could name files are skipped
// (json_checks.hpp).
#include <string>
#include <string_view>

#include "fuzz_support.hpp"
#include "json_checks.hpp"
#include "query.hpp"

namespace pf = proxima::fuzz;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  pf::start_target();
  std::string_view line(reinterpret_cast<const char*>(data), size);
  line = line.substr(0, line.find('\n'));
  if (pf::reaches_files(line)) return 0;
  bool rejected = false;
  const proxima::tool::Json answer = proxima::tool::answer_line(line, rejected);
  pf::check_answer_shape(answer, rejected);
  pf::check_json_finite(answer);
  // Written as the tool writes it (invalid UTF-8 of the request, quoted in an error, replaced).
  (void)answer.dump(-1, ' ', false, proxima::tool::Json::error_handler_t::replace);
  return 0;
}
