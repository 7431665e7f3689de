#pragma once
/// @file mass_properties.hpp
/// Area, mass, centroid and rotational inertia of the 2D convex shapes (uniform density).

#include <proxima/d2/convex_shapes.hpp>

namespace proxima::d2 {

/// Mass properties of a uniform plate, in the shape's local frame.
struct MassProperties {
  Real area = Real(0);     ///< area (length^2); 0 for points and segments
  Real mass = Real(0);     ///< density * area
  Vec2 centroid{Real(0)};  ///< centre of mass, local frame (the middle of a segment, the point itself)
  Real inertia = Real(0);  ///< polar moment about the centroid (mass * length^2)
};

/// Exact mass properties of a rounded core of density `density` (mass per area): the core
/// polygon, a band of width `radius` along each edge and a disc sector at each vertex (the
/// sectors' angles add up to a full turn); a 2-vertex core is a rectangle plus two half
/// discs, a 1-vertex core a disc. Cores of zero area (point, segment) get area 0, mass 0,
/// inertia 0 and the centroid of their vertices.
MassProperties mass_properties(const ConvexCore& core, Real density = Real(1));

}  // namespace proxima::d2
