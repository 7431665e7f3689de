#include "query_operations.hpp"

#include <array>

#include "line_protocol.hpp"
#include "query_2d_ops.hpp"
#include "query_bound_ops.hpp"
#include "query_broadphase_ops.hpp"
#include "query_ccd_ops.hpp"
#include "query_pair_ops.hpp"
#include "query_shape_ops.hpp"
#include "query_sprite_ops.hpp"

namespace proxima::tool {

namespace {

/// The 3D operation, or its 2D form when the request's shapes are 2D (query_2d_ops.hpp).
template <Json (*Op3)(const Json&), Json (*Op2)(const Json&)>
Json by_dimension(const Json& request) {
  return is_2d_request(request) ? Op2(request) : Op3(request);
}

const std::array kOperations = {
    Operation{"raycast", by_dimension<op_raycast, op_raycast_2d>,
              "target, origin, direction, max_t? -> hit, t, point, normal (world frame)"},
    Operation{"contains", by_dimension<op_contains, op_contains_2d>, "target, point -> inside"},
    Operation{"closest_point", by_dimension<op_closest_point, op_closest_point_2d>,
              "target, point -> point, normal, distance (signed)"},
    Operation{"bound", op_bound, "target, volume -> the bounding volume in the world frame"},
    Operation{"fit", op_fit, "points, volume -> the fitted volume and volume_m3"},
    Operation{"mass", by_dimension<op_mass, op_mass_2d>,
              "target, density? -> volume, mass, centroid, inertia (world axes)"},
    Operation{"pairs", op_pairs, pairs_synopsis()},
    Operation{"intersect", by_dimension<op_intersect, op_intersect_2d>,
              "a, b -> hit (the placed shapes touch or overlap)"},
    Operation{"distance", by_dimension<op_distance, op_distance_2d>,
              "a, b -> distance (signed), point_a, point_b, normal (a to b), status, method"},
    Operation{"collide", by_dimension<op_collide, op_collide_2d>,
              "a, b, max_contacts?, contact_distance? -> hit, normal, contacts[point_a, point_b, normal, depth], "
              "status, method"},
    Operation{"toi", by_dimension<op_toi, op_toi_2d>,
              "a, b (each shape, pose, pose_end?), target_distance?, tolerance?, max_iterations? -> hit, toi, "
              "toi_lower, toi_upper, point, normal, depth, status, iterations"},
    Operation{"cast", by_dimension<op_cast, op_cast_2d>,
              "a, translation, b, target_distance?, tolerance?, max_iterations?, cull_back_faces? -> hit, t, point, "
              "normal, depth, status, iterations"},
    Operation{"safe_step", op_safe_step,
              "a, b (each shape, pose, linear_velocity?, angular_velocity?), target_distance? -> dt (null: never)"},
    Operation{"sprite_overlap", op_sprite_overlap,
              "a (mask, position), b (mask, position, angle_degrees?, scale?) -> overlap, count, first (screen "
              "pixels, y down)"},
};

}  // namespace

std::span<const Operation> operations() { return kOperations; }

const Operation* find_operation(std::string_view name) {
  for (const Operation& op : kOperations) {
    if (op.name == name) return &op;
  }
  return nullptr;
}

std::string operation_names() { return joined_names(kOperations); }

}  // namespace proxima::tool
