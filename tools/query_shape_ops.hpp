#pragma once
// Query operations on one placed shape: raycast, contains, closest_point, mass. Each takes
// the whole request and returns the answer's members; errors are FieldError.
#include "json_values.hpp"

namespace proxima::tool {

/// {"target", "origin", "direction", "max_t"?} -> {"hit": false} or {"hit": true, "t",
/// "point", "normal"}, world frame; t in units of |direction|.
Json op_raycast(const Json& request);
/// {"target", "point"} -> {"inside"}: the point lies in the solid or on its surface.
Json op_contains(const Json& request);
/// {"target", "point"} -> {"point", "normal", "distance"}: nearest surface point (world),
/// unit outward normal there, signed distance (< 0 inside).
Json op_closest_point(const Json& request);
/// {"target", "density"?} -> {"volume", "mass", "centroid", "inertia"}: centroid in the
/// world frame, inertia about the centroid in world axes (rows of a 3x3 matrix).
Json op_mass(const Json& request);

}  // namespace proxima::tool
