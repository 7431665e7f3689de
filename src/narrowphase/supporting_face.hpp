#pragma once
/// @file supporting_face.hpp
/// The supporting feature of a shape in a direction, as a small polygon in the world frame:
/// the face, edge or point of the shape (of its core, for rounded shapes) that lies farthest
/// along the direction. Contact manifolds clip one such feature against the other
/// (face_clipping.hpp).
///
///   box            the face whose normal is nearest the direction (4 points)
///   convex hull    the face whose normal is nearest the direction (its loop, <= kMaxFacePoints)
///   triangle       the triangle, normal turned towards the direction (3 points)
///   segment        the segment (2 points)
///   capsule        its core segment (2 points; core radius added by the caller)
///   cylinder       a cap (the rim sampled at kRimPoints points) when the direction is near
///                  the axis, the side line (2 points) when it is near the radial plane, else
///                  the support point
///   cone           the base (rim sampled) near -axis, the slant line (apex to rim) near a
///                  slant normal, else the support point
///   point, sphere, ellipsoid, half-space   the support point (1 point)
///
/// Every function is O(1) except the hull's (O(F) over its faces) and allocates nothing.

#include <proxima/core/math.hpp>
#include <proxima/core/transform.hpp>
#include <proxima/shapes/shape.hpp>

#include <array>
#include <cstdint>

namespace proxima::narrow {

/// Largest number of points of a supporting feature; hull faces with more vertices are
/// reported as their support point only.
inline constexpr int kMaxFacePoints = 32;

/// Number of points sampled on a cylinder's or cone's rim (a regular polygon inscribed in
/// the circle, so every point lies on the surface).
inline constexpr int kRimPoints = 8;

/// Cosine of the largest angle between a direction and a curved shape's face normal (cap,
/// base, side) for which that face is reported rather than the single support point.
inline constexpr Real kCurvedFaceCosine = Real(0.99);

/// A supporting feature: a convex polygon (count >= 3), a segment (count == 2) or a point
/// (count == 1), in the world frame.
struct SupportingFace {
  /// The feature's points, world frame. Polygons are counter-clockwise seen from the side
  /// `normal` points to.
  /// Left uninitialised beyond `count` (the struct is built on every manifold query).
  std::array<Vec3, kMaxFacePoints> points;
  /// A stable index for each point (vertex index on polyhedra; rim sample index on curved
  /// shapes), used in feature ids.
  std::array<std::uint32_t, kMaxFacePoints> ids;
  int count = 0;  ///< number of valid points (1..kMaxFacePoints)
  /// Unit normal of the feature, world frame: the polygon's outward plane normal; for a
  /// segment or a point, the query direction (normalised).
  Vec3 normal{Real(0), Real(0), Real(1)};
  /// Index of the feature on its shape (face index on polyhedra, 0 or 1 for caps, ...).
  std::uint32_t index = 0;
  /// Radius added around this feature (the shape's core radius: capsule, sphere).
  Real radius = Real(0);
};

/// Supporting feature of a point (its position).
SupportingFace supporting_face(const Point& shape, const Transform& pose, const Vec3& direction);
/// Supporting feature of a segment (the segment itself).
SupportingFace supporting_face(const Segment& shape, const Transform& pose, const Vec3& direction);
/// Supporting feature of a triangle (the triangle, normal turned towards `direction`).
SupportingFace supporting_face(const Triangle& shape, const Transform& pose, const Vec3& direction);
/// Supporting feature of a sphere's core (its centre) with radius = the sphere's radius.
SupportingFace supporting_face(const Sphere& shape, const Transform& pose, const Vec3& direction);
/// Supporting feature of a capsule's core (its segment) with radius = the capsule's radius.
SupportingFace supporting_face(const Capsule& shape, const Transform& pose, const Vec3& direction);
/// Supporting face of a box (the face whose outward normal has the largest dot product
/// with `direction`; face index 2 axis + (1 if the + face), vertex ids 0..7 by sign bits).
SupportingFace supporting_face(const Box& shape, const Transform& pose, const Vec3& direction);
/// Supporting feature of a cylinder: cap, side line or support point (see the file notes).
SupportingFace supporting_face(const Cylinder& shape, const Transform& pose, const Vec3& direction);
/// Supporting feature of a cone: base, slant line or support point (see the file notes).
SupportingFace supporting_face(const Cone& shape, const Transform& pose, const Vec3& direction);
/// Supporting feature of an ellipsoid (its support point).
SupportingFace supporting_face(const Ellipsoid& shape, const Transform& pose, const Vec3& direction);
/// Supporting face of a convex hull: the face whose normal has the largest dot product with
/// `direction` (O(F)); the support vertex when that face has more than kMaxFacePoints
/// vertices.
SupportingFace supporting_face(const ConvexHull& shape, const Transform& pose, const Vec3& direction);
/// Supporting feature of a half-space (a point of its boundary plane: the point nearest the
/// local origin).
SupportingFace supporting_face(const HalfSpace& shape, const Transform& pose, const Vec3& direction);

}  // namespace proxima::narrow
