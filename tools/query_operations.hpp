#pragma once
// The table of query operations: the one place where an operation of the protocol is
// registered. Adding one (intersect, distance, collide, pairs, cast, toi, ...) is a function
// `Json op_name(const Json& request)` plus one row in operations().
#include <span>
#include <string>
#include <string_view>

#include "json_values.hpp"

namespace proxima::tool {

/// Answers a request of one operation: returns the answer's members (without "id"), or
/// throws FieldError naming the bad field.
using OperationFunction = Json (*)(const Json& request);

/// One operation of the protocol.
struct Operation {
  std::string_view name;      ///< value of the request's "op"
  OperationFunction run;      ///< the handler
  std::string_view synopsis;  ///< one line for --help: fields in, fields out
};

/// Every operation, in the order the help lists them.
std::span<const Operation> operations();

/// The operation called `name`, or nullptr.
const Operation* find_operation(std::string_view name);

/// The operation names, comma-separated (for error messages and help).
std::string operation_names();

}  // namespace proxima::tool
