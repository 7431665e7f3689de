#pragma once
// 2D shapes and poses of the query protocol (docs/query-protocol.md, "2D"): a shape
// {"type":"circle","radius":1}, a pose {"position":[x,y],"angle":radians} and a placed shape
// {"shape":S,"pose":P}. Types: circle (radius, center?), point2d (position?), segment2d
// (vertices: 2 points), capsule2d (vertices: 2 points, radius), polygon (points: >= 3, their
// convex hull; radius? default 0), box2d (half_extents: [x, y]; center?, angle?, radius?) and
// chain (points, loop?).
#include <proxima/d2/shape.hpp>

#include <string>

#include "json_values.hpp"

namespace proxima::tool {

/// A 2D shape with its placement in the world plane.
struct PlacedShape2d {
  d2::Shape shape;                       ///< the shape, in its local frame
  d2::Pose pose = d2::Pose::identity();  ///< local-to-world placement
};

/// True when `name` is the type name of a 2D shape.
bool is_2d_type_name(std::string_view name);
/// The protocol names of the 2D types ("circle, point2d, ...").
std::string shape_2d_type_names();

/// A JSON array [x, y] of numbers; a bad component is named path.x / path.y.
Vec2 read_vec2(const Json& value, const std::string& path);
/// A 2D vector as [x, y].
Json to_json(const Vec2& v);

/// Parses a 2D shape object; errors name the field under `path` ("a.shape.radius").
d2::Shape read_shape_2d(const Json& value, const std::string& path);
/// Parses a 2D pose {"position":[x,y],"angle":radians} (both optional).
d2::Pose read_pose_2d(const Json& value, const std::string& path);
/// Parses a placed 2D shape {"shape":S,"pose":P}, or a bare shape object at the identity.
PlacedShape2d read_placed_shape_2d(const Json& value, const std::string& path);

}  // namespace proxima::tool
