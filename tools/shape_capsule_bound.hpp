#pragma once
// A bounding capsule of a placed shape, for the query protocol's `bound` with volume
// "capsule" (the library's fit_shape.hpp offers boxes, spheres and k-DOPs of shapes).
#include <proxima/bounds/bounding_capsule.hpp>
#include <proxima/shapes/shape.hpp>

#include "json_values.hpp"

namespace proxima::tool {

/// A capsule (world frame) that contains the whole placed shape: exact for points,
/// segments, spheres and capsules; for the other bounded shapes, a capsule along the
/// longest axis of the shape's oriented box whose radius bounds the shape's distance from
/// that axis (from support points in 64 directions around it, divided by cos(pi/64) so that
/// no direction in between can stick out) and whose segment spans the shape's extent along
/// the axis. Throws FieldError on `field` for a half-space (unbounded).
BoundingCapsule bound_shape_capsule(const Shape& shape, const Transform& pose, const std::string& field);

}  // namespace proxima::tool
