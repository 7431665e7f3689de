#pragma once
/// @file raycast.hpp
/// Ray (and segment) intersection with geometric primitives, in the primitives' frame.
///
/// All functions follow the conventions of ray.hpp: points origin + t*direction with
/// 0 <= t <= max_t; direction need not be unit; a ray starting inside a solid primitive
/// hits at t = 0 with normal -direction/|direction|; the returned normal is unit.
/// A segment pq is the ray {p, q - p} with max_t = 1. Degenerate rays (zero direction)
/// and rays parallel to a face give a defined answer, never NaN.
///
/// Details shared by every function here:
///  - Solids are closed: an origin on the surface counts as inside (t = 0), and a ray that
///    only touches the surface (tangent, along a face) hits.
///  - With a zero direction, an inside origin hits at t = 0 with normal +z (any unit
///    vector would do; this one is fixed); an outside origin misses.
///  - max_t may be +infinity (an unbounded ray); a negative or NaN max_t, a non-finite
///    origin or direction, and primitive parameters that are not finite or out of their
///    domain (radius <= 0, negative half extent, empty box, zero plane normal, p0 == p1
///    for the cylinder, apex == base for the cone) never hit.
///  - Accuracy: t is found from differences of nearby coordinates first (origin minus
///    centre, vertex minus origin...), so a primitive far from the world origin costs no
///    more than rounding at its own size; grazing rays are as well-conditioned as their
///    geometry allows (discriminants in the form (r - f)(r + f), stable quadratic roots).
/// Each query is O(1), allocates nothing and never throws (declared noexcept).

#include <proxima/core/math.hpp>
#include <proxima/geometry/aabb.hpp>
#include <proxima/geometry/ray.hpp>

#include <optional>

namespace proxima::geometry {

/// Solid sphere (centre, radius > 0). Analytic quadratic, cancellation-safe form; the
/// normal is (hit point - centre) / radius.
std::optional<RayHit> ray_sphere(const Ray& ray, Real max_t, const Vec3& center, Real radius) noexcept;

/// Solid axis-aligned box, slab method (Kay-Kajiya / Williams et al.); robust to direction
/// components of +-0 and to flat boxes. The normal is the entry face's (one of them when
/// entering through an edge or corner) and the point lies exactly on that face.
std::optional<RayHit> ray_aabb(const Ray& ray, Real max_t, const Aabb& box) noexcept;

/// Solid oriented box: centre, `axes` (columns = unit, orthogonal box axes in this
/// frame), half extents >= 0. The normal is +-the entry face's axis.
std::optional<RayHit> ray_obb(const Ray& ray, Real max_t, const Vec3& center, const Mat3& axes,
                              const Vec3& half_extents) noexcept;

/// Solid capsule: the points within `radius` of segment p0p1 (p0 == p1 gives a sphere).
/// The normal is (hit point - nearest point of the segment) / radius.
std::optional<RayHit> ray_capsule(const Ray& ray, Real max_t, const Vec3& p0, const Vec3& p1, Real radius) noexcept;

/// Solid capped cylinder with axis p0p1 (p0 != p1) and `radius` > 0. The normal is
/// radial on the side, -+(p1 - p0)/|p1 - p0| on the caps at p0 / p1.
std::optional<RayHit> ray_cylinder(const Ray& ray, Real max_t, const Vec3& p0, const Vec3& p1, Real radius) noexcept;

/// Solid capped cone: `apex`, the centre of its base disc `base_center` (!= apex) and
/// the base radius > 0. The normal is the slant surface's on the side, the axis direction
/// (base_center - apex, normalised) on the base, and its opposite at the apex itself.
std::optional<RayHit> ray_cone(const Ray& ray, Real max_t, const Vec3& apex, const Vec3& base_center,
                               Real base_radius) noexcept;

/// The plane n.x = d as a two-sided surface (`normal` unit; a non-unit normal describes
/// the plane n.x = d all the same). An origin on the plane (e.g. a ray lying in it) hits
/// at t = 0. The returned normal faces the ray origin (for an origin on the plane: faces
/// against the direction).
std::optional<RayHit> ray_plane(const Ray& ray, Real max_t, const Vec3& normal, Real offset) noexcept;

/// The solid half-space n.x <= d (`normal` unit, or any non-zero vector); inside origin
/// hits at t = 0; the normal of a surface hit is n / |n|.
std::optional<RayHit> ray_halfspace(const Ray& ray, Real max_t, const Vec3& normal, Real offset) noexcept;

/// Two-sided triangle abc, watertight (Woop, Benthin, Wald, "Watertight Ray/Triangle
/// Intersection", JCGT 2013): a ray through a shared edge or vertex of a closed mesh hits
/// at least one of the triangles. Degenerate triangles are never hit. The normal faces
/// the ray origin.
///
/// Edge and vertex hits count (the triangle is closed). Degenerate means collinear or
/// coincident vertices, and also slivers whose smallest angle has a sine below about
/// 16 epsilon of Real. A ray parallel to the triangle's plane (including one lying in it)
/// misses, and a zero direction never hits. For many triangles against one ray (a mesh),
/// prepare the ray once with TriangleRay. O(1).
std::optional<RayHit> ray_triangle(const Ray& ray, Real max_t, const Vec3& a, const Vec3& b, const Vec3& c) noexcept;

/// A ray prepared for the watertight triangle test: the axis permutation and shear that
/// map the direction to +z, with the direction scaled by a power of two so that the shear
/// never overflows. Building it once per ray saves that work in mesh traversals; the
/// answers are bit-identical to the plain ray_triangle.
struct TriangleRay {
  Ray ray;                     ///< the original ray (hit points are computed from it)
  Vec3 shear{Real(0)};         ///< (Sx, Sy, Sz) of the paper, for the scaled direction
  int kx = 0, ky = 1, kz = 2;  ///< axis permutation: kz is the dominant direction axis
  int exponent = 0;            ///< direction = scaled direction * 2^exponent
  bool valid = false;          ///< false for a zero or non-finite ray: nothing is hit

  /// An invalid prepared ray (declared so that TriangleRay is not an aggregate: a braced
  /// {origin, direction} argument then always means a Ray).
  TriangleRay() = default;

  /// Prepares `ray` (any direction; zero or non-finite ones give valid == false).
  static TriangleRay prepare(const Ray& ray) noexcept;
};

/// Watertight ray-triangle test with a prepared ray; same answer as the overload above.
std::optional<RayHit> ray_triangle(const TriangleRay& ray, Real max_t, const Vec3& a, const Vec3& b,
                                   const Vec3& c) noexcept;

}  // namespace proxima::geometry
