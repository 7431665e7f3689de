#pragma once
// Query operation on many boxes at once: pairs (the broad phase). Takes the whole request
// and returns the answer's members; errors are FieldError.
#include <string>

#include "json_values.hpp"

namespace proxima::tool {

/// {"boxes": [[minx, miny, minz, maxx, maxy, maxz], ...], "structure"?} -> {"pairs": [[i, j],
/// ...]}: every pair of boxes that overlap or touch, i < j (indices into "boxes"), sorted;
/// found by the named broad-phase structure (default "brute").
Json op_pairs(const Json& request);

/// The "pairs" line of the help: its fields and the structure names.
std::string_view pairs_synopsis();

}  // namespace proxima::tool
