// Cylinder queries, all solved in closed form.
//
// Steps:
//  - support: the rim point of the cap facing the direction (cap centre when the direction
//    is parallel to the axis); the direction is first scaled by its largest component so
//    that tiny or huge directions neither underflow nor overflow.
//  - world_aabb: a capped cylinder is the Minkowski sum of its axis segment and a disc; the
//    half extent of a disc of radius r and unit normal a on world axis i is
//    r sqrt(1 - a_i^2) = r sqrt(a_j^2 + a_k^2) (written without cancellation), plus h |a_i|
//    for the segment (Eberly, "Geometric Tools": bounding boxes of discs).
//  - closest_point: by rotational symmetry the nearest surface point lies in the half-plane
//    through the axis and the query point; there the solid is the rectangle
//    [0, r] x [-h, h] and the answer is the nearest point of its side or cap edge (Ericson,
//    Real-Time Collision Detection, 5.1.3, applied in 2-D). Points inside go to the nearest
//    face; the sign is taken from contains() so that the two queries always agree.
//  - raycast: geometry::ray_cylinder on the axis segment.
//  - mass_properties: the standard solid-cylinder formulas.
#include <proxima/geometry/raycast.hpp>
#include <proxima/shapes/cylinder.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

#include "shapes/far_point.hpp"
#include "shapes/radial.hpp"

namespace proxima {

using detail::radial_direction;
using detail::robust_hypot;

Result<Cylinder> Cylinder::create(Real radius, Real half_length) {
  if (auto e = detail::check_radius_half_length(radius, half_length)) return *e;
  return Cylinder(radius, half_length);
}

Vec3 Cylinder::support(const Vec3& direction) const {
  if (!is_finite(direction)) return {Real(0), Real(0), half_length_};
  const Real z = direction.z < Real(0) ? -half_length_ : half_length_;
  const Real m = std::max(std::abs(direction.x), std::abs(direction.y));
  if (!(m > Real(0))) return {Real(0), Real(0), z};
  const Real dx = direction.x / m;
  const Real dy = direction.y / m;
  const Real s = radius_ / std::sqrt(dx * dx + dy * dy);
  return {dx * s, dy * s, z};
}

Aabb Cylinder::local_aabb() const {
  const Vec3 e(radius_, radius_, half_length_);
  return {-e, e};
}

Aabb Cylinder::world_aabb(const Transform& pose) const {
  const Vec3 a = pose.apply_vector(Vec3(Real(0), Real(0), Real(1)));
  const Vec3 e(half_length_ * std::abs(a.x) + radius_ * std::sqrt(a.y * a.y + a.z * a.z),
               half_length_ * std::abs(a.y) + radius_ * std::sqrt(a.x * a.x + a.z * a.z),
               half_length_ * std::abs(a.z) + radius_ * std::sqrt(a.x * a.x + a.y * a.y));
  return {pose.position - e, pose.position + e};
}

std::optional<RayHit> Cylinder::raycast(const Ray& ray, Real max_t) const {
  return geometry::ray_cylinder(ray, max_t, Vec3(Real(0), Real(0), -half_length_), Vec3(Real(0), Real(0), half_length_),
                                radius_);
}

bool Cylinder::contains(const Vec3& point) const {
  return std::abs(point.z) <= half_length_ && point.x * point.x + point.y * point.y <= radius_ * radius_;
}

SurfacePoint Cylinder::closest_point(const Vec3& point) const {
  if (!is_finite(point)) return detail::far_top_point(half_length_);
  const Real r = radius_;
  const Real h = half_length_;
  // Radial unit vector of the half-plane holding the point (any one on the axis).
  Real ux;
  Real uy;
  const Real rho = radial_direction(point.x, point.y, ux, uy);
  const Real sz = point.z < Real(0) ? Real(-1) : Real(1);
  const Real dr = rho - r;                // > 0 beyond the side
  const Real dz = std::abs(point.z) - h;  // > 0 beyond the cap

  SurfacePoint sp;
  if (dr > Real(0) && dz > Real(0)) {
    // Beyond the rim: the nearest point is the rim circle.
    const Real d = robust_hypot(dr, dz);
    sp.point = Vec3(r * ux, r * uy, sz * h);
    sp.normal = Vec3(ux * (dr / d), uy * (dr / d), sz * (dz / d));
    sp.signed_distance = d;
  } else if (dr >= dz) {
    // Outside the side (dz <= 0), or inside with the side the nearest face.
    sp.point = Vec3(r * ux, r * uy, point.z);
    sp.normal = Vec3(ux, uy, Real(0));
    sp.signed_distance = dr;
  } else {
    // Outside a cap (dr <= 0), or inside with a cap the nearest face.
    sp.point = Vec3(point.x, point.y, sz * h);
    sp.normal = Vec3(Real(0), Real(0), sz);
    sp.signed_distance = dz;
  }
  // The sign follows contains() (they can differ only by rounding, on the surface).
  sp.signed_distance = contains(point) ? std::min(sp.signed_distance, Real(0)) : std::max(sp.signed_distance, Real(0));
  return sp;
}

MassProperties Cylinder::mass_properties(Real density) const {
  const Real r2 = radius_ * radius_;
  const Real h2 = half_length_ * half_length_;
  MassProperties m;
  m.volume = Real(2) * kPi * r2 * half_length_;
  m.mass = density * m.volume;
  // (3 r^2 + L^2) / 12 with L = 2h (divided before the mass multiplies: the product of
  // the mass and the sum alone can overflow where the inertia does not).
  const Real transverse = m.mass * ((Real(3) * r2 + Real(4) * h2) / Real(12));
  m.inertia = Mat3(Real(0));
  m.inertia[0][0] = transverse;
  m.inertia[1][1] = transverse;
  m.inertia[2][2] = Real(0.5) * m.mass * r2;
  return m;
}

}  // namespace proxima
