#pragma once
// Shapes and poses of the query protocol: {"type":"sphere","radius":1}, a pose
// {"position":[x,y,z],"rotation":[x,y,z,w]} and a placed shape {"shape":S,"pose":P}.
#include <proxima/core/transform.hpp>
#include <proxima/shapes/shape.hpp>

#include <string>

#include "json_values.hpp"

namespace proxima::tool {

/// A shape with its placement in the world frame.
struct PlacedShape {
  Shape shape;                             ///< the shape, in its local frame
  Transform pose = Transform::identity();  ///< local-to-world placement
};

/// Parses a shape object ("type" plus the fields of that type, validated by the shape's
/// create()). Errors name the field under `path` ("target.shape.radius").
Shape read_shape(const Json& value, const std::string& path);

/// Parses a pose object {"position":[x,y,z],"rotation":[x,y,z,w]} (both optional; identity
/// when absent), validated by Transform::create (errors "path.position.y", "path.rotation").
Transform read_pose(const Json& value, const std::string& path);

/// Parses a placed shape {"shape":S,"pose":P} (pose optional). A bare shape object (one that
/// has a "type" member) is accepted too and placed at the identity.
PlacedShape read_placed_shape(const Json& value, const std::string& path);

/// The protocol name of every shape type, in ShapeType order ("point", ..., "halfspace").
std::string shape_type_names();

}  // namespace proxima::tool
