// Watertight ray-triangle intersection (two-sided).
//
// Steps (Woop, Benthin, Wald 2013):
//  1. Per ray: kz = the axis of the largest |direction| component, kx and ky the next two
//     (swapped when direction[kz] < 0 to keep the winding); the direction is scaled by a
//     power of two (exact) so that its largest component lies in [0.5, 1), then the shear
//     constants Sx = dx/dz, Sy = dy/dz, Sz = 1/dz map it to +z.
//  2. Per triangle: vertices relative to the origin, permuted and sheared into the ray's
//     2-D frame: x = v[kx] - Sx v[kz], y = v[ky] - Sy v[kz]. A vertex shared by several
//     triangles gets bit-identical coordinates in each.
//  3. Edge functions U, V, W (2x2 determinants of the sheared vertices) with an exact
//     sign: in the float build the products of two floats are exact in double, so the
//     double difference is rounded once and keeps the sign (the paper's fallback, applied
//     always); in the double build the plain difference is used when it exceeds its
//     rounding-error bound, and otherwise Kahan's fused-multiply-add determinant, whose
//     relative error is below 2 ulp (Jeannerod, Louvet, Muller 2013), decides. Exact signs
//     make the test watertight: the edge shared by two triangles has opposite signs in
//     them, so a ray through it is inside at least one.
//  4. Mixed signs: miss. All zero (ray parallel to the plane, or a degenerate triangle in
//     the ray's view): miss.
//  5. t = (U Az + V Bz + W Cz) / det with Az = Sz a[kz]..., evaluated as barycentric
//     weights U/det... times the heights (no overflow), scaled back by the power of two.
//  6. Degenerate triangles (|(b - a) x (c - a)| <= 16 eps |b - a| |c - a|) never hit; the
//     normal is the face normal turned towards the ray origin.
//
// Sources: Woop, Benthin, Wald, "Watertight Ray/Triangle Intersection", JCGT 2(1), 2013;
// Kahan's 2x2 determinant with FMA, analysed by Jeannerod, Louvet, Muller, "Further
// analysis of Kahan's algorithm for the accurate computation of 2x2 determinants",
// Mathematics of Computation 82 (2013).

#include <proxima/core/tolerance.hpp>
#include <proxima/geometry/raycast.hpp>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <type_traits>

#include "geometry/raycast_detail.hpp"

namespace proxima::geometry {

namespace {

/// q.x p.y - q.y p.x with the exact sign (and exactly 0 only when the true value is 0).
double edge_function(const Vec2& p, const Vec2& q) {
#if PROXIMA_DOUBLE
  const double ab = q.x * p.y;
  const double cd = q.y * p.x;
  const double fast = ab - cd;
  // Error of `fast` (even if the compiler fuses one product into the subtraction) is at
  // most 2 ulp of the larger product; beyond 4 ulp of their sum its sign is certain.
  if (std::abs(fast) > 4.0 * kEpsilon * (std::abs(ab) + std::abs(cd))) return fast;
  const double err = std::fma(-q.y, p.x, cd);   // cd - q.y p.x, exactly
  const double main = std::fma(q.x, p.y, -cd);  // q.x p.y - cd, rounded once
  return main + err;
#else
  return static_cast<double>(q.x) * static_cast<double>(p.y) - static_cast<double>(q.y) * static_cast<double>(p.x);
#endif
}

}  // namespace

TriangleRay TriangleRay::prepare(const Ray& ray) noexcept {
  TriangleRay p;
  p.ray = ray;
  if (!is_finite(ray.origin) || !is_finite(ray.direction)) return p;
  const Vec3 ad = glm::abs(ray.direction);
  const int kz = ad.x >= ad.y ? (ad.x >= ad.z ? 0 : 2) : (ad.y >= ad.z ? 1 : 2);
  if (!(ad[kz] > Real(0))) return p;
  int exponent = 0;
  Vec3 d;
  // ad[kz] = f 2^exponent, f in [0.5, 1); the direction scaled by 2^-exponent (exact but for
  // components that fall below the normal range, rounded as ldexp rounds them).
  constexpr Real kFastLow = std::numeric_limits<Real>::min() * Real(4);
  constexpr Real kFastHigh = std::numeric_limits<Real>::max() / Real(8);
  if (ad[kz] >= kFastLow && ad[kz] <= kFastHigh) {
    // A normal number: frexp's exponent is the biased exponent minus (bias - 1), and 2^-exponent
    // is a normal number too, so one multiplication replaces the libm calls.
    using Bits = std::conditional_t<sizeof(Real) == 4, std::uint32_t, std::uint64_t>;
    constexpr int mantissa = std::numeric_limits<Real>::digits - 1;
    constexpr int bias = std::numeric_limits<Real>::max_exponent - 1;
    const Bits bits = std::bit_cast<Bits>(ad[kz]);
    exponent = static_cast<int>(bits >> mantissa) - (bias - 1);
    d = ray.direction * std::bit_cast<Real>(static_cast<Bits>(bias - exponent) << mantissa);
  } else {
    (void)std::frexp(ad[kz], &exponent);
    d = Vec3(std::ldexp(ray.direction.x, -exponent), std::ldexp(ray.direction.y, -exponent),
             std::ldexp(ray.direction.z, -exponent));
  }
  p.kz = kz;
  p.kx = (kz + 1) % 3;
  p.ky = (p.kx + 1) % 3;
  if (d[kz] < Real(0)) std::swap(p.kx, p.ky);
  p.shear = Vec3(d[p.kx] / d[kz], d[p.ky] / d[kz], Real(1) / d[kz]);
  p.exponent = exponent;
  p.valid = true;
  return p;
}

std::optional<RayHit> ray_triangle(const TriangleRay& pr, Real max_t, const Vec3& a, const Vec3& b,
                                   const Vec3& c) noexcept {
  if (!pr.valid || !(max_t >= Real(0)) || !is_finite(a) || !is_finite(b) || !is_finite(c)) return std::nullopt;
  const Vec3 ra = a - pr.ray.origin;
  const Vec3 rb = b - pr.ray.origin;
  const Vec3 rc = c - pr.ray.origin;
  const int kx = pr.kx;
  const int ky = pr.ky;
  const int kz = pr.kz;
  const Vec2 a2(ra[kx] - pr.shear.x * ra[kz], ra[ky] - pr.shear.y * ra[kz]);
  const Vec2 b2(rb[kx] - pr.shear.x * rb[kz], rb[ky] - pr.shear.y * rb[kz]);
  const Vec2 c2(rc[kx] - pr.shear.x * rc[kz], rc[ky] - pr.shear.y * rc[kz]);

  const double u = edge_function(b2, c2);
  const double v = edge_function(c2, a2);
  const double w = edge_function(a2, b2);
  if ((u < 0.0 || v < 0.0 || w < 0.0) && (u > 0.0 || v > 0.0 || w > 0.0)) return std::nullopt;
  const double det = u + v + w;  // all of one sign: no cancellation; 0 only if all are 0
  if (det == 0.0) return std::nullopt;
  // Heights along the (scaled) direction, weighted by the barycentric coordinates.
  const double t_scaled = u / det * static_cast<double>(pr.shear.z * ra[kz]) +
                          v / det * static_cast<double>(pr.shear.z * rb[kz]) +
                          w / det * static_cast<double>(pr.shear.z * rc[kz]);
  if (!(t_scaled >= 0.0)) return std::nullopt;
  const double t_wide = std::ldexp(t_scaled, -pr.exponent);
  if (!(t_wide <= static_cast<double>(max_t)) || t_wide > static_cast<double>(kRealMax)) return std::nullopt;

  const Vec3 e1 = b - a;
  const Vec3 e2 = c - a;
  const Vec3 n = glm::cross(e1, e2);
  const Real n_len = detail::safe_length(n);
  if (!(n_len > Real(16) * kEpsilon * detail::safe_length(e1) * detail::safe_length(e2))) return std::nullopt;
  // Unit normal first: n . direction itself could overflow for huge coordinates.
  const Vec3 unit = detail::safe_normalize(n, detail::kZeroDirectionNormal);
  const Vec3 facing = glm::dot(unit, pr.ray.direction) > Real(0) ? -unit : unit;
  return detail::surface_hit(pr.ray, max_t, static_cast<Real>(t_wide), facing);
}

std::optional<RayHit> ray_triangle(const Ray& ray, Real max_t, const Vec3& a, const Vec3& b, const Vec3& c) noexcept {
  return ray_triangle(TriangleRay::prepare(ray), max_t, a, b, c);
}

}  // namespace proxima::geometry
