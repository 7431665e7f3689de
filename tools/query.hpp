#pragma once
// The query protocol driver: one JSON request per input line, one JSON answer per output
// line, in order. See docs/query-protocol.md.
#include <cstddef>
#include <iosfwd>
#include <string_view>

#include "json_values.hpp"

namespace proxima::tool {

/// What a run of the protocol did.
struct QuerySummary {
  std::size_t answered = 0;  ///< requests answered without error
  std::size_t rejected = 0;  ///< lines answered with an error
};

/// Answers one parsed request. Never throws: a bad request gives {"id":…,"error":…,
/// "field":…,"code":…} and sets `rejected`.
Json answer_request(const Json& request, bool& rejected);

/// Parses and answers one input line (invalid JSON is answered with an error).
Json answer_line(std::string_view line, bool& rejected);

/// Reads requests from `in` line by line (blank lines are skipped) and writes one compact
/// JSON answer per line to `out`, flushed after each so that the protocol can be driven
/// interactively through a pipe.
QuerySummary run_queries(std::istream& in, std::ostream& out);

/// The process exit status for a run: 2 when any line was rejected, else 0.
int exit_status(const QuerySummary& summary);

}  // namespace proxima::tool
