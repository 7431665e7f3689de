#pragma once
// What the continuous operations of the query protocol share, in 3D (query_ccd_ops.cpp) and
// 2D (query_2d_ops.cpp): the search options target_distance, tolerance and max_iterations, and
// the library's field names of a rejected call mapped onto the request's members.
#include <proxima/core/result.hpp>

#include <algorithm>
#include <initializer_list>
#include <limits>
#include <string>
#include <string_view>

#include "json_values.hpp"

namespace proxima::tool {

/// A library field prefix ("motion_a.end", "options") and the request path that replaces it
/// ("a.pose_end"; "" for top-level members).
struct Rename {
  std::string_view from;  ///< library field prefix
  std::string to;         ///< request path that replaces it
};

/// Throws the library's Error with its field named as the request names it: the first rename
/// whose prefix is the whole field or a dotted prefix of it applies.
[[noreturn]] inline void throw_renamed(Error error, std::initializer_list<Rename> renames) {
  for (const Rename& r : renames) {
    const std::string& f = error.field;
    if (f.rfind(r.from, 0) != 0) continue;
    if (f.size() == r.from.size()) {
      error.field = r.to;
    } else if (f[r.from.size()] == '.') {
      error.field = join_path(r.to, f.substr(r.from.size() + 1));
    } else {
      continue;
    }
    break;
  }
  throw_library_error("", error);
}

/// "max_iterations": an integer at most INT_MAX (values below 1 go to the library, which
/// rejects them by name).
inline int read_max_iterations(const Json& value) {
  if (!value.is_number_integer()) throw FieldError("max_iterations", "wrong_type", "must be an integer");
  constexpr long long kMax = std::numeric_limits<int>::max();
  if (value.is_number_unsigned() ? value.get<unsigned long long>() > static_cast<unsigned long long>(kMax)
                                 : value.get<long long>() > kMax) {
    throw FieldError("max_iterations", "out_of_range", "must be at most " + std::to_string(kMax));
  }
  return static_cast<int>(std::max(value.get<long long>(), 0LL));
}

/// The members ToiOptions and CastOptions share: target_distance, tolerance, max_iterations.
template <class Options>
void read_search_options(const Json& request, Options& options) {
  if (const Json* d = find_member(request, "target_distance")) {
    options.target_distance = read_real(*d, "target_distance");
  }
  if (const Json* t = find_member(request, "tolerance")) options.tolerance = read_real(*t, "tolerance");
  if (const Json* m = find_member(request, "max_iterations")) options.max_iterations = read_max_iterations(*m);
}

}  // namespace proxima::tool
