// Ray against a solid capped cone (apex, base centre, base radius R, height H).
//
// Steps:
//  1. Local frame: unit axis a from the apex to the base centre, two unit vectors
//     orthogonal to it; z is the height above the apex, rho the distance to the axis. The
//     solid is 0 <= z <= H and cos(alpha) rho <= sin(alpha) z, alpha the half angle
//     (cos, sin = H, R over sqrt(H^2 + R^2): no division by a small height).
//  2. Origin inside the closed solid: t = 0.
//  3. The origin is moved along the line to the point nearest the apex (and the shift
//     added back at the end), so that the quadratic's coefficients stay of the size of
//     the cone even for a far-away origin, and so that a line through the apex (where the
//     cone equation has a double root) has coefficients of the size of its distance to
//     the apex: its roots come out accurate instead of to sqrt(epsilon).
//  4. Slab 0 <= z <= H (the z = 0 "face" is the apex point, the z = H face the base disc).
//  5. Double cone Q(s) = cos^2 rho^2 - sin^2 z^2 <= 0: quadratic with coefficients written
//     as products of sums and differences, discriminant in wide precision; its solution
//     set is one interval (direction outside the opening angle), two half-lines (inside
//     the angle: one per nappe) or a half-line (parallel to a generator). Every piece is
//     clipped by the slab, which removes the mirror nappe (z < 0); the first non-empty
//     piece is the chord through the solid.
//  6. The later entry decides the face: base (normal +a), apex (normal -a, reached only
//     through the apex point) or lateral (normal cos * radial - sin * a).
//
// Sources: Eberly, "Intersection of a Line and a Cone", Geometric Tools (2000, rev. 2020);
// Ericson, Real-Time Collision Detection, 5.3 (slabs, convex pieces); Press et al.,
// Numerical Recipes, 5.6 (quadratic roots without cancellation).

#include <proxima/core/tolerance.hpp>
#include <proxima/geometry/raycast.hpp>

#include "geometry/raycast_detail.hpp"

namespace proxima::geometry {

namespace {

enum ConeFeature : int { ConeApex = 0, ConeBase = 1, ConeLateral = 2 };

/// Precision of the discriminant: double even in the float build.
using Wide = double;

}  // namespace

std::optional<RayHit> ray_cone(const Ray& ray, Real max_t, const Vec3& apex, const Vec3& base_center,
                               Real base_radius) noexcept {
  detail::UnitRay r;
  if (!detail::prepare(ray, max_t, r) || !is_finite(apex) || !is_finite(base_center) || !is_finite(base_radius) ||
      !(base_radius > Real(0))) {
    return std::nullopt;
  }
  const detail::AxisFrame frame = detail::axis_frame(apex, base_center);
  const Real height = frame.length;
  if (!(height > Real(0))) return std::nullopt;
  const Real slant = detail::safe_length(Vec3(height, base_radius, Real(0)));
  const Real cos_a = height / slant;
  const Real sin_a = base_radius / slant;

  // Containment of the true origin.
  {
    const Vec3 m = frame.local(ray.origin - apex);
    const Real rho = detail::safe_length(Vec3(m.x, m.y, Real(0)));
    if (m.z >= Real(0) && m.z <= height && cos_a * rho <= sin_a * m.z) return detail::inside_hit(ray, r);
  }
  if (r.length == Real(0)) return std::nullopt;

  // Shifted origin: the point of the line nearest the apex (all in vectors relative to
  // the apex, so that no sum is formed at the magnitude of the coordinates).
  const Vec3 m0 = ray.origin - apex;
  const Real shift = -glm::dot(m0, r.unit);
  const Vec3 m = frame.local(m0 + shift * r.unit);
  const Vec3 u = frame.local(r.unit);

  const detail::Interval slab = detail::slab_interval(m.z, u.z, Real(0), height, ConeApex, ConeBase);
  if (slab.empty()) return std::nullopt;

  const Real rho_m = detail::safe_length(Vec3(m.x, m.y, Real(0)));
  const Real rho_u = detail::safe_length(Vec3(u.x, u.y, Real(0)));
  const Real qa = (cos_a * rho_u - sin_a * std::abs(u.z)) * (cos_a * rho_u + sin_a * std::abs(u.z));
  const Real qb = cos_a * cos_a * (m.x * u.x + m.y * u.y) - sin_a * sin_a * (m.z * u.z);
  const Real qc = (cos_a * rho_m - sin_a * m.z) * (cos_a * rho_m + sin_a * m.z);
  const Wide disc = Wide(qb) * Wide(qb) - Wide(qa) * Wide(qc);
  const Real disc_r = disc > Wide(kRealMax) ? kRealMax : static_cast<Real>(disc);
  const detail::QuadraticSet set = detail::quadratic_nonpositive(qa, qb, qc, disc_r, ConeLateral);

  // Parameters below are relative to the shifted origin; the true origin is at -shift.
  const detail::Interval pieces[2] = {slab.clipped(set.first), slab.clipped(set.second)};
  const detail::Interval* chord = nullptr;
  for (const detail::Interval& piece : pieces) {
    if (piece.empty() || piece.hi < -shift) continue;
    if (chord == nullptr || piece.lo < chord->lo) chord = &piece;
  }
  if (chord == nullptr) return std::nullopt;
  // The origin tested outside: an entry before it is rounding at the surface.
  const Real s = std::max(chord->lo, -shift);
  if (!std::isfinite(s)) return std::nullopt;
  Vec3 normal;
  switch (chord->lo_feature) {
    case ConeApex: normal = -frame.axis; break;
    case ConeBase: normal = frame.axis; break;
    case ConeLateral: {
      const Real x = m.x + s * u.x;
      const Real y = m.y + s * u.y;
      const Real rho = detail::safe_length(Vec3(x, y, Real(0)));
      if (rho > kRelativeTolerance * height) {
        normal = frame.world(cos_a * x / rho, cos_a * y / rho, -sin_a);
      } else {
        // At the apex: the lateral normal on the generator facing the ray, which lies in
        // the apex's normal cone and points against the ray whether it enters or touches.
        const Real rho_dir = detail::safe_length(Vec3(u.x, u.y, Real(0)));
        normal = rho_dir > Real(0) ? frame.world(-cos_a * u.x / rho_dir, -cos_a * u.y / rho_dir, -sin_a) : -frame.axis;
      }
      break;
    }
    default: return detail::inside_hit(ray, r);
  }
  return detail::surface_hit(ray, max_t, (s + shift) / r.length, normal);
}

}  // namespace proxima::geometry
