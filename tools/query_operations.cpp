#include "query_operations.hpp"

#include <array>

#include "line_protocol.hpp"
#include "query_bound_ops.hpp"
#include "query_broadphase_ops.hpp"
#include "query_ccd_ops.hpp"
#include "query_pair_ops.hpp"
#include "query_shape_ops.hpp"
#include "query_sprite_ops.hpp"

namespace proxima::tool {

namespace {

const std::array kOperations = {
    Operation{"raycast", op_raycast, "target, origin, direction, max_t? -> hit, t, point, normal (world frame)"},
    Operation{"contains", op_contains, "target, point -> inside"},
    Operation{"closest_point", op_closest_point, "target, point -> point, normal, distance (signed)"},
    Operation{"bound", op_bound, "target, volume -> the bounding volume in the world frame"},
    Operation{"fit", op_fit, "points, volume -> the fitted volume and volume_m3"},
    Operation{"mass", op_mass, "target, density? -> volume, mass, centroid, inertia (world axes)"},
    Operation{"pairs", op_pairs, pairs_synopsis()},
    Operation{"intersect", op_intersect, "a, b -> hit (the placed shapes touch or overlap)"},
    Operation{"distance", op_distance, "a, b -> distance (signed), point_a, point_b, normal (a to b), status, method"},
    Operation{"collide", op_collide,
              "a, b, max_contacts?, contact_distance? -> hit, normal, contacts[point_a, point_b, normal, depth], "
              "status, method"},
    Operation{"toi", op_toi,
              "a, b (each shape, pose, pose_end?), target_distance?, tolerance?, max_iterations? -> hit, toi, "
              "toi_lower, toi_upper, point, normal, depth, status, iterations"},
    Operation{"cast", op_cast,
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
