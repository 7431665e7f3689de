#include "query.hpp"

#include <string>

#include "query_operations.hpp"

namespace proxima::tool {

namespace {

Json run_operation(const Json& request) {
  const std::string name = read_op(request);
  const Operation* operation = find_operation(name);
  if (operation == nullptr) {
    throw FieldError("op", "unknown_op",
                     "unknown operation \"" + name + "\" (expected one of " + operation_names() + ")");
  }
  return operation->run(request);
}

}  // namespace

Json answer_request(const Json& request, bool& rejected) {
  return answer_request_with(request, rejected, &run_operation);
}

Json answer_line(std::string_view line, bool& rejected) { return answer_line_with(line, rejected, &run_operation); }

QuerySummary run_queries(std::istream& in, std::ostream& out) { return run_lines(in, out, &run_operation); }

}  // namespace proxima::tool
