#include "query.hpp"

#include <exception>
#include <istream>
#include <ostream>
#include <string>

#include "query_operations.hpp"

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

}  // namespace

Json answer_request(const Json& request, bool& rejected) {
  rejected = true;
  if (!request.is_object()) return error_answer(nullptr, "the request must be a JSON object", "", "wrong_type");
  const Json* id = find_member(request, "id");
  try {
    const std::string name = read_string(require_member(request, "", "op"), "op");
    const Operation* operation = find_operation(name);
    if (operation == nullptr) {
      throw FieldError("op", "unknown_op",
                       "unknown operation \"" + name + "\" (expected one of " + operation_names() + ")");
    }
    Json result = operation->run(request);
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

Json answer_line(std::string_view line, bool& rejected) {
  Json request;
  try {
    request = Json::parse(line);
  } catch (const Json::exception& e) {
    rejected = true;
    return error_answer(nullptr, "invalid JSON: " + without_exception_tag(e.what()), "", "bad_json");
  }
  return answer_request(request, rejected);
}

QuerySummary run_queries(std::istream& in, std::ostream& out) {
  QuerySummary summary;
  std::string line;
  while (std::getline(in, line)) {
    if (line.find_first_not_of(" \t\r\n") == std::string::npos) continue;
    bool rejected = false;
    const Json answer = answer_line(line, rejected);
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
