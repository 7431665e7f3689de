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
//    5.1.2, in 2-D). Points inside take the normal of the nearer face; the sign is taken
//    from contains() so that the two queries always agree.
//  - raycast: geometry::ray_cone.
//  - mass_properties: the standard solid-cone formulas (centroid at a quarter of the height
//    above the base, inertia about the centroid).
#include <proxima/core/validate.hpp>
#include <proxima/geometry/raycast.hpp>
#include <proxima/shapes/cone.hpp>

#include <algorithm>
#include <cmath>

namespace proxima {

namespace {

// sqrt(a^2 + b^2) without overflow or underflow of the squares.
Real robust_hypot(Real a, Real b) {
  const Real m = std::max(std::abs(a), std::abs(b));
  if (!(m > Real(0))) return Real(0);
  const Real sa = a / m;
  const Real sb = b / m;
  return m * std::sqrt(sa * sa + sb * sb);
}

// The distance rho of (x, y) from the axis and the unit radial direction (ux, uy) towards
// it ((1, 0) on the axis), computed from the scaled components so that denormal or huge
// coordinates still give a unit direction.
Real radial_direction(Real x, Real y, Real& ux, Real& uy) {
  const Real m = std::max(std::abs(x), std::abs(y));
  if (!(m > Real(0))) {
    ux = Real(1);
    uy = Real(0);
    return Real(0);
  }
  const Real sx = x / m;
  const Real sy = y / m;
  const Real len = std::sqrt(sx * sx + sy * sy);
  ux = sx / len;
  uy = sy / len;
  return m * len;
}

}  // namespace

Result<Cone> Cone::create(Real radius, Real half_length) {
  if (auto e = validate::positive(radius, "radius")) return *e;
  if (auto e = validate::positive(half_length, "half_length")) return *e;
  return Cone(radius, half_length);
}

Vec3 Cone::support(const Vec3& direction) const {
  const Vec3 apex(Real(0), Real(0), half_length_);
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
  // rho 2h <= r (h - z), squared (both sides >= 0) after dividing both factors by
  // max(2h, r) so that no product overflows whatever the aspect ratio.
  const Real s = std::max(Real(2) * h, radius_);
  const Real a = Real(2) * h / s;
  const Real b = radius_ / s * (h - point.z);
  return rho2 * (a * a) <= b * b;
}

SurfacePoint Cone::closest_point(const Vec3& point) const {
  const Real r = radius_;
  const Real h = half_length_;
  // The half-plane through the axis and the point: radial unit (ux, uy) (any one on the axis).
  Real ux;
  Real uy;
  const Real rho = radial_direction(point.x, point.y, ux, uy);
  const Real z = point.z;

  // Slant edge from the apex A = (0, h) to the rim B = (r, -h): E = (r, -2h).
  const Real ex = r;
  const Real ez = Real(-2) * h;
  const Real t = std::clamp((rho * ex + (z - h) * ez) / (ex * ex + ez * ez), Real(0), Real(1));
  const Real p1x = t * r;
  const Real p1z = h + t * ez;
  const Real d1 = robust_hypot(rho - p1x, z - p1z);
  // Base edge from the centre C = (0, -h) to the rim B.
  const Real p2x = std::min(rho, r);
  const Real p2z = -h;
  const Real d2 = robust_hypot(rho - p2x, z - p2z);

  const bool inside = contains(point);
  const bool slant = d1 <= d2;
  const Real px = slant ? p1x : p2x;
  const Real pz = slant ? p1z : p2z;
  const Real d = slant ? d1 : d2;

  SurfacePoint sp;
  sp.point = Vec3(px * ux, px * uy, pz);
  Real nx;
  Real nz;
  if (!inside && d > Real(0)) {
    nx = (rho - px) / d;
    nz = (z - pz) / d;
  } else if (slant) {
    // Outward normal of the slant face: (2h, r) / |(2h, r)|.
    const Real len = robust_hypot(Real(2) * h, r);
    nx = Real(2) * h / len;
    nz = r / len;
  } else {
    nx = Real(0);
    nz = Real(-1);
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
