#pragma once
// Query operations on two placed shapes (the narrow phase): intersect, distance, collide.
// Each takes the whole request and returns the answer's members; errors are FieldError.
#include "json_values.hpp"

namespace proxima::tool {

/// {"a", "b"} -> {"hit"}: the placed shapes a and b touch or overlap.
Json op_intersect(const Json& request);
/// {"a", "b"} -> {"distance", "point_a", "point_b", "normal", "status", "method"}: signed
/// distance (< 0 overlap), witness points on each surface and the unit normal from a to b,
/// world frame.
Json op_distance(const Json& request);
/// {"a", "b", "max_contacts"?, "contact_distance"?} -> {"hit", "normal", "contacts",
/// "status", "method"}: the contact manifold, each contact {"point_a", "point_b", "normal",
/// "depth"} in the world frame (depth < 0 for a speculative contact).
Json op_collide(const Json& request);

}  // namespace proxima::tool
