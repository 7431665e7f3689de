#pragma once
// The driver shared by the line protocols (`proxima query`, `proxima world`): one JSON request
// per input line, one JSON answer per output line, in order; the request's "id" echoed first;
// a rejected request answered {"id":…,"error":…,"field":…,"code":…}.
#include <proxima/core/function_ref.hpp>

#include <cstddef>
#include <iosfwd>
#include <string>
#include <string_view>

#include "json_values.hpp"

namespace proxima::tool {

class ProgressBar;

/// What a run of a line protocol did.
struct QuerySummary {
  std::size_t answered = 0;  ///< requests answered without error
  std::size_t rejected = 0;  ///< lines answered with an error
};

/// Answers the request object (its "op" already known to be present or not): returns the
/// answer's members without "id", or throws FieldError naming the bad field.
using RequestHandler = FunctionRef<Json(const Json& request)>;

/// The "op" member of a request (error "missing" or "wrong_type" on "op").
std::string read_op(const Json& request);

/// Answers one parsed request with `handler`. Never throws: a request that is not an object,
/// a FieldError or any other exception gives an error answer and sets `rejected`.
Json answer_request_with(const Json& request, bool& rejected, RequestHandler handler);

/// Deepest nesting of arrays and objects a request line may have (deeper: a "bad_json" error,
/// refused while parsing).
inline constexpr int kMaxJsonNesting = 64;

/// Most members one object of a request line may have (more: a "bad_json" error, refused
/// while parsing). The parsed objects keep their members in order and look keys up one by
/// one, so a line's parsing costs at most its member count times this limit.
inline constexpr std::size_t kMaxJsonObjectMembers = 1024;

/// Parses one input line and answers it with `handler` (invalid JSON, nested deeper than
/// kMaxJsonNesting or an object of more than kMaxJsonObjectMembers members: a "bad_json"
/// error).
Json answer_line_with(std::string_view line, bool& rejected, RequestHandler handler);

/// Reads requests from `in` line by line (blank lines are skipped) and writes one compact
/// JSON answer per line to `out`, flushed after each so that the protocol can be driven
/// interactively through a pipe. `progress` (may be null) is told the bytes read so far
/// (each line and its newline) after each line.
QuerySummary run_lines(std::istream& in, std::ostream& out, RequestHandler handler, ProgressBar* progress = nullptr);

/// The names of a protocol's operation table (elements with a `name`), comma-separated, in
/// table order (for error messages and --help).
template <class Operations>
std::string joined_names(const Operations& operations) {
  std::string names;
  for (const auto& op : operations) {
    if (!names.empty()) names += ", ";
    names += op.name;
  }
  return names;
}

/// The process exit status for a run: 2 when any line was rejected, else 0.
int exit_status(const QuerySummary& summary);

}  // namespace proxima::tool
