#pragma once
// Checks of the line protocols' answers shared by the query and world targets, and the rule
// that keeps fuzzed requests off the file system.
#include <cmath>
#include <string_view>

#include "fuzz_support.hpp"
#include "json_values.hpp"

namespace proxima::fuzz {

/// Aborts when a number of `answer` (at any depth) is NaN or infinite: the protocols answer
/// with finite numbers or an error.
inline void check_json_finite(const tool::Json& answer) {
  if (answer.is_number_float()) {
    check(std::isfinite(answer.get<double>()), "answer holds a NaN or infinite number");
  } else if (answer.is_structured()) {
    for (const tool::Json& member : answer) check_json_finite(member);
  }
}

/// Aborts unless `answer` is an object that is either an answer or an error with its
/// "error", "field" and "code" members.
inline void check_answer_shape(const tool::Json& answer, bool rejected) {
  check(answer.is_object(), "answer not an object");
  if (rejected) {
    check(answer.contains("error") && answer.contains("code"), "rejected request without error and code");
    // "internal": an exception the request's validation did not foresee (tool::answer_request_with).
    check(answer["code"] != "internal", "request answered with an internal error");
  } else {
    check(!answer.contains("error"), "answered request carries an error");
  }
}

/// True when a request line may name a file ("file": meshes, save and load; "png": sprite
/// masks) or spell a name by escapes: such lines would read or write the file system, and are
/// left to the file readers' own targets.
inline bool reaches_files(std::string_view line) {
  return line.find("file") != std::string_view::npos || line.find("png") != std::string_view::npos ||
         line.find('\\') != std::string_view::npos;
}

}  // namespace proxima::fuzz
