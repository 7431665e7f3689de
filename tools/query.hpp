#pragma once
// The query protocol driver: one JSON request per input line, one JSON answer per output
// line, in order. See docs/query-protocol.md.
#include <iosfwd>
#include <string_view>

#include "json_values.hpp"
#include "line_protocol.hpp"

namespace proxima::tool {

/// Answers one parsed request. Never throws: a bad request gives {"id":…,"error":…,
/// "field":…,"code":…} and sets `rejected`.
Json answer_request(const Json& request, bool& rejected);

/// Parses and answers one input line (invalid JSON is answered with an error).
Json answer_line(std::string_view line, bool& rejected);

/// Reads requests from `in` line by line (blank lines are skipped) and writes one compact
/// JSON answer per line to `out`, flushed after each so that the protocol can be driven
/// interactively through a pipe.
QuerySummary run_queries(std::istream& in, std::ostream& out);

}  // namespace proxima::tool
