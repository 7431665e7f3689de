#pragma once
// The query protocol's operations on 2D shapes (docs/query-protocol.md, "2D"): the same op
// names and members as in 3D, with 2D type names, 2D vectors and 2D poses. A request is 2D
// when the shape under "a" (or "target") has a 2D type name.
#include "json_values.hpp"

namespace proxima::tool {

/// True when the request's "a" or "target" member holds a 2D shape (by its type name).
bool is_2d_request(const Json& request);

/// a, b -> hit.
Json op_intersect_2d(const Json& request);
/// a, b -> distance (signed), point_a, point_b, normal, status, method, part_a?, part_b?.
Json op_distance_2d(const Json& request);
/// a, b, contact_distance? -> hit, normal, contacts[point_a, point_b, normal, depth, feature_id],
/// method, part_a?, part_b? (with a chain side: the segment with the deepest point).
Json op_collide_2d(const Json& request);
/// target, origin, direction, max_t? -> hit, t, point, normal, part?.
Json op_raycast_2d(const Json& request);
/// target, point -> inside.
Json op_contains_2d(const Json& request);
/// target, point -> point, normal, distance (signed).
Json op_closest_point_2d(const Json& request);
/// target, density? -> area, mass, centroid, inertia (about the centroid).
Json op_mass_2d(const Json& request);
/// a, b (each shape, pose, pose_end?), target_distance?, tolerance?, max_iterations? -> hit,
/// toi, toi_lower, toi_upper, point, normal, depth, status, iterations. The turn is
/// pose_end.angle - pose.angle, so several turns can be asked for.
Json op_toi_2d(const Json& request);
/// a, translation, b, target_distance?, tolerance?, max_iterations? -> hit, t, point, normal,
/// depth, status, iterations.
Json op_cast_2d(const Json& request);

}  // namespace proxima::tool
