#pragma once
// Query operations of continuous collision detection: toi (time of impact of two moving
// geometries), cast (a geometry swept along a translation against a still one) and safe_step
// (the longest time two bodies with constant velocities cannot come within a distance). Each
// takes the whole request and returns the answer's members; errors are FieldError, the
// library's errors renamed to the request's fields.
#include "json_values.hpp"

namespace proxima::tool {

/// {"a", "b", "target_distance"?, "tolerance"?, "max_iterations"?} -> {"hit", "toi",
/// "toi_lower", "toi_upper", "point"?, "normal"?, "depth"?, "status", "iterations"}: each side
/// {"shape", "pose", "pose_end"?} moves from pose (t = 0) to pose_end (t = 1); time_of_impact.
Json op_toi(const Json& request);
/// {"a", "translation", "b", "target_distance"?, "tolerance"?, "max_iterations"?,
/// "cull_back_faces"?} -> {"hit", "t", "point"?, "normal"?, "depth"?, "status", "iterations"}:
/// shape_cast of a along translation against b.
Json op_cast(const Json& request);
/// {"a", "b", "target_distance"?} -> {"dt"}: each side {"shape", "pose", "linear_velocity"?,
/// "angular_velocity"?}; safe_time_step, null when the bodies never approach.
Json op_safe_step(const Json& request);

}  // namespace proxima::tool
