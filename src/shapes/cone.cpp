// Cone queries, all solved in closed form.
//
// Steps:
//  - support: the larger of the apex and the base-rim point in the direction's radial
//    plane (van den Bergen, "Collision Detection in Interactive 3D Environments", 4.3.4,
//    support mapping of a cone); the direction is first scaled by its largest component so
//    that tiny or huge directions neither underflow nor overflow.
//  - world_aabb: the cone is the convex hull of its apex and its base disc; the half extent
//    of a disc of radius r and unit normal a on world axis i is r sqrt(a_j^2 + a_k^2)
//    (= r sqrt(1 - a_i^2), written without cancellation).
//  - closest_point: by rotational symmetry the nearest surface point lies in the half-plane
//    through the axis and the query point; there the surface is the profile made of the
//    slant edge apex-rim and the base edge centre-rim of the triangle
//    (0, h), (r, -h), (0, -h) (the axis edge is interior to the solid). The answer is the
//    nearer of the two segments' closest points (Ericson, Real-Time Collision Detection,
//    5.1.2, in 2-D); distances to an edge's interior are taken from its line equation and
//    distances to a vertex from the exact vertex, which keeps the normal accurate close to
//    the surface. Points inside take the normal of the nearer face; the sign is taken from
//    contains() so that the two queries always agree.
//  - raycast: geometry::ray_cone.
//  - mass_properties: the standard solid-cone formulas (centroid at a quarter of the height
//    above the base, inertia about the centroid).
#include <proxima/geometry/raycast.hpp>
#include <proxima/shapes/cone.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

#include "shapes/far_point.hpp"
#include "shapes/radial.hpp"

namespace proxima {

using detail::radial_direction;
using detail::robust_hypot;

Result<Cone> Cone::create(Real radius, Real half_length) {
  if (auto e = detail::check_radius_half_length(radius, half_length)) return *e;
  return Cone(radius, half_length);
}

Vec3 Cone::support(const Vec3& direction) const {
  const Vec3 apex(Real(0), Real(0), half_length_);
  if (!is_finite(direction)) return apex;
  const Real m = std::max({std::abs(direction.x), std::abs(direction.y), std::abs(direction.z)});
  if (!(m > Real(0))) return apex;
  const Vec3 d = direction / m;  // largest component +-1: no overflow, no underflow to 0
  const Real rho = std::sqrt(d.x * d.x + d.y * d.y);
  // Apex: h d.z; rim: r rho - h d.z.
  if (Real(2) * half_length_ * d.z >= radius_ * rho) return apex;
  if (!(rho > Real(0))) return {Real(0), Real(0), -half_length_};
  const Real s = radius_ / rho;
  return {d.x * s, d.y * s, -half_length_};
}

Aabb Cone::local_aabb() const {
  const Vec3 e(radius_, radius_, half_length_);
  return {-e, e};
}

Aabb Cone::world_aabb(const Transform& pose) const {
  const Vec3 a = pose.apply_vector(Vec3(Real(0), Real(0), Real(1)));
  const Vec3 apex = pose.position + half_length_ * a;
  const Vec3 base = pose.position - half_length_ * a;
  const Vec3 e(radius_ * std::sqrt(a.y * a.y + a.z * a.z), radius_ * std::sqrt(a.x * a.x + a.z * a.z),
               radius_ * std::sqrt(a.x * a.x + a.y * a.y));
  return {glm::min(apex, base - e), glm::max(apex, base + e)};
}

std::optional<RayHit> Cone::raycast(const Ray& ray, Real max_t) const {
  return geometry::ray_cone(ray, max_t, Vec3(Real(0), Real(0), half_length_), Vec3(Real(0), Real(0), -half_length_),
                            radius_);
}

bool Cone::contains(const Vec3& point) const {
  const Real h = half_length_;
  if (!(point.z >= -h && point.z <= h)) return false;
  const Real rho2 = point.x * point.x + point.y * point.y;
  if (rho2 > radius_ * radius_) return false;
  // rho 2h <= r (h - z). With rho <= r no product overflows, and the boundary points that
  // are exact in floating point (apex, rim, base, slant midpoints) test as inside:
  // sqrt(r * r) == r and h - (-h) == 2h exactly.
  return std::sqrt(rho2) * (Real(2) * h) <= radius_ * (h - point.z);
}

SurfacePoint Cone::closest_point(const Vec3& point) const {
  if (!is_finite(point)) return detail::far_top_point(half_length_);
  const Real r = radius_;
  const Real h = half_length_;
  // The half-plane through the axis and the point: radial unit (ux, uy) (any one on the axis).
  Real ux;
  Real uy;
  const Real rho = radial_direction(point.x, point.y, ux, uy);
  const Real z = point.z;

  // Slant edge from the apex A = (0, h) to the rim B = (r, -h): length len, unit tangent
  // (tx, tz) from A, unit outward normal (sx, sz).
  const Real len = robust_hypot(Real(2) * h, r);
  const Real tx = r / len;
  const Real tz = Real(-2) * h / len;
  const Real sx = Real(2) * h / len;
  const Real sz = r / len;
  const Real along = rho * tx + (z - h) * tz;  // coordinate along the edge from A

  // Nearest point of the slant edge: the apex, the rim or an interior point. Face-interior
  // distances come from the face planes, vertex distances from the exact vertices, so that
  // neither loses accuracy when the point is close to the surface.
  enum class Feature { Face, Apex, Rim };
  Real p1x;
  Real p1z;
  Real d1;
  Feature f1;
  if (along <= Real(0)) {
    p1x = Real(0);
    p1z = h;
    d1 = robust_hypot(rho, z - h);
    f1 = Feature::Apex;
  } else if (along >= len) {
    p1x = r;
    p1z = -h;
    d1 = robust_hypot(rho - r, z + h);
    f1 = Feature::Rim;
  } else {
    p1x = along * tx;
    p1z = h + along * tz;
    d1 = std::abs(rho * sx + (z - h) * sz);
    f1 = Feature::Face;
  }
  // Nearest point of the base edge from the centre C = (0, -h) to the rim B.
  const bool base_face = rho <= r;
  const Real p2x = base_face ? rho : r;
  const Real d2 = base_face ? std::abs(z + h) : robust_hypot(rho - r, z + h);

  const bool inside = contains(point);
  const bool slant = d1 <= d2;
  const Real px = slant ? p1x : p2x;
  const Real pz = slant ? p1z : -h;
  const Real d = slant ? d1 : d2;
  const bool at_vertex = slant ? f1 != Feature::Face : !base_face;

  SurfacePoint sp;
  sp.point = Vec3(px * ux, px * uy, pz);
  // Face normal of the chosen edge; from a vertex, outside, the direction to the point.
  Real nx = slant ? sx : Real(0);
  Real nz = slant ? sz : Real(-1);
  if (!inside && at_vertex && d > Real(0)) {
    nx = (rho - px) / d;
    nz = (z - pz) / d;
  }
  sp.normal = Vec3(nx * ux, nx * uy, nz);
  sp.signed_distance = inside ? -d : d;
  return sp;
}

MassProperties Cone::mass_properties(Real density) const {
  const Real r2 = radius_ * radius_;
  const Real h2 = half_length_ * half_length_;
  MassProperties m;
  m.volume = Real(2) / Real(3) * kPi * r2 * half_length_;
  m.mass = density * m.volume;
  m.centroid = Vec3(Real(0), Real(0), Real(-0.5) * half_length_);
  // About the centroid: 3/20 m r^2 + 3/80 m H^2 with H = 2h, i.e. 3/20 m (r^2 + h^2).
  const Real transverse = Real(3) / Real(20) * m.mass * (r2 + h2);
  m.inertia = Mat3(Real(0));
  m.inertia[0][0] = transverse;
  m.inertia[1][1] = transverse;
  m.inertia[2][2] = Real(0.3) * m.mass * r2;
  return m;
}

}  // namespace proxima
