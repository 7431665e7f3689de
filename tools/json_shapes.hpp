#pragma once
// Shapes and poses of the query protocol: {"type":"sphere","radius":1}, a pose
// {"position":[x,y,z],"rotation":[x,y,z,w]} and a placed shape {"shape":S,"pose":P}; and the
// geometries beyond convex shapes: {"type":"mesh","file":F} or {"type":"mesh","vertices":
// [[x,y,z],...],"triangles":[[i,j,k],...]}, and {"type":"compound","children":[{"shape":G,
// "pose":P},...]} (children any geometry, nested compounds allowed).
#include <proxima/core/transform.hpp>
#include <proxima/shapes/compound.hpp>
#include <proxima/shapes/shape.hpp>

#include <string>

#include "json_values.hpp"

namespace proxima::tool {

/// A shape (any kind) with its placement in the world frame.
struct PlacedShape {
  Shape shape;                             ///< the shape, in its local frame
  Transform pose = Transform::identity();  ///< local-to-world placement
};

/// Parses a convex shape object ("type" plus the fields of that type, validated by the
/// shape's create()). Errors name the field under `path` ("target.shape.radius"); a mesh or
/// compound is rejected ("unsupported_geometry": this operation takes convex shapes only).
Shape read_shape(const Json& value, const std::string& path);

/// Parses any geometry: a shape object as read_shape, a mesh (from "file", read through
/// assimp relative to the current directory and cached by path, or from "vertices" and
/// "triangles"; "repair" (default true) runs repair_mesh first) or a compound ("children":
/// [{"shape":G,"pose":P},...]). Errors name the field ("target.shape.triangles[4][2]",
/// "a.shape.children[1].shape.radius", "target.shape.file").
Shape read_geometry(const Json& value, const std::string& path);

/// Parses a placed shape of any kind {"shape":G,"pose":P} (or a bare shape object at
/// identity).
PlacedShape read_placed_geometry(const Json& value, const std::string& path);

/// Parses a pose object {"position":[x,y,z],"rotation":[x,y,z,w]} (both optional; identity
/// when absent), validated by Transform::create (errors "path.position.y", "path.rotation").
Transform read_pose(const Json& value, const std::string& path);

/// Parses a placed shape {"shape":S,"pose":P} (pose optional). A bare shape object (one that
/// has a "type" member) is accepted too and placed at the identity.
PlacedShape read_placed_shape(const Json& value, const std::string& path);

/// The protocol name of every shape type, in ShapeType order ("point", ..., "halfspace").
std::string shape_type_names();

/// shape_type_names() followed by "mesh, compound".
std::string geometry_type_names();

}  // namespace proxima::tool
