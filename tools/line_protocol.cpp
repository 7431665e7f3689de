#include "line_protocol.hpp"

#include <exception>
#include <istream>
#include <ostream>

#include "progress_bar.hpp"

namespace proxima::tool {

namespace {

Json error_answer(const Json* id, const std::string& message, const std::string& field, const std::string& code) {
  Json answer = Json::object();
  if (id != nullptr) answer["id"] = *id;
  answer["error"] = message;
  answer["field"] = field;
  answer["code"] = code;
  return answer;
}

// nlohmann's messages start with "[json.exception.parse_error.101] "; the tag says nothing
// to a user of the protocol.
std::string without_exception_tag(const std::string& what) {
  const auto close = what.find("] ");
  return what.rfind("[json.exception.", 0) == 0 && close != std::string::npos ? what.substr(close + 2) : what;
}

// Thrown by the parser callback at the nesting limit.
struct TooDeep {};

// Thrown by the parser callback at the member limit.
struct TooManyMembers {};

}  // namespace

std::string read_op(const Json& request) { return read_string(require_member(request, "", "op"), "op"); }

Json answer_request_with(const Json& request, bool& rejected, RequestHandler handler) {
  rejected = true;
  if (!request.is_object()) return error_answer(nullptr, "the request must be a JSON object", "", "wrong_type");
  const Json* id = find_member(request, "id");
  try {
    Json result = handler(request);
    Json answer = Json::object();
    if (id != nullptr) answer["id"] = *id;
    for (auto it = result.begin(); it != result.end(); ++it) answer[it.key()] = std::move(it.value());
    rejected = false;
    return answer;
  } catch (const FieldError& e) {
    return error_answer(id, e.what(), e.field(), e.code());
  } catch (const std::exception& e) {
    return error_answer(id, std::string("internal error: ") + e.what(), "", "internal");
  }
}

Json answer_line_with(std::string_view line, bool& rejected, RequestHandler handler) {
  Json request;
  try {
    // Arrays and objects nested deeper than kMaxJsonNesting are refused while parsing, so
    // that nothing after (copies, echoes, destruction, the readers) recurses that deep.
    // Objects of more than kMaxJsonObjectMembers members are refused too: inserting a
    // member searches the object's earlier members, so a large object parses in quadratic
    // time. members[d] counts the keys of the open object at depth d.
    std::size_t members[kMaxJsonNesting + 2] = {};
    request = Json::parse(line, [&members](int depth, Json::parse_event_t event, Json&) {
      if (depth > kMaxJsonNesting) throw TooDeep{};
      if (event == Json::parse_event_t::object_start) members[depth + 1] = 0;
      if (event == Json::parse_event_t::key && ++members[depth] > kMaxJsonObjectMembers) throw TooManyMembers{};
      return true;
    });
  } catch (const Json::exception& e) {
    rejected = true;
    return error_answer(nullptr, "invalid JSON: " + without_exception_tag(e.what()), "", "bad_json");
  } catch (const TooDeep&) {
    rejected = true;
    return error_answer(
        nullptr, "invalid JSON: arrays and objects nested deeper than " + std::to_string(kMaxJsonNesting) + " levels",
        "", "bad_json");
  } catch (const TooManyMembers&) {
    rejected = true;
    return error_answer(nullptr,
                        "invalid JSON: an object has more than " + std::to_string(kMaxJsonObjectMembers) + " members",
                        "", "bad_json");
  }
  return answer_request_with(request, rejected, handler);
}

QuerySummary run_lines(std::istream& in, std::ostream& out, RequestHandler handler, ProgressBar* progress) {
  QuerySummary summary;
  std::string line;
  std::size_t bytes = 0;
  while (std::getline(in, line)) {
    bytes += line.size() + 1;
    if (progress) progress->update(bytes);
    if (line.find_first_not_of(" \t\r\n") == std::string::npos) continue;
    bool rejected = false;
    const Json answer = answer_line_with(line, rejected, handler);
    // Replace invalid UTF-8 that a request might echo (in "id" or a type name) rather
    // than throw while printing.
    out << answer.dump(-1, ' ', false, Json::error_handler_t::replace) << '\n' << std::flush;
    if (rejected) {
      ++summary.rejected;
    } else {
      ++summary.answered;
    }
  }
  return summary;
}

int exit_status(const QuerySummary& summary) { return summary.rejected > 0 ? 2 : 0; }

}  // namespace proxima::tool
