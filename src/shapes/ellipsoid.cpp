// Ellipsoid queries.
//
// Steps:
//  - support: R^2 d / |R d| with R = diag(radii) (the gradient of the support function
//    |R d|); d and then R d are scaled by their largest component so that nothing
//    overflows or underflows.
//  - world_aabb: the support function of the rotated ellipsoid M R on world axis e_i is
//    |R M^T e_i| = sqrt(sum_j (M_ij r_j)^2), exact.
//  - raycast: the scaling x -> x / R maps the ellipsoid to the unit sphere and the ray to a
//    ray with the same parameter t; geometry::ray_sphere finds t, and the normal at the hit
//    is the unit-sphere normal mapped by the inverse transpose of the scaling, R^-1.
//  - closest_point: D. Eberly, "Distance from a Point to an Ellipse, an Ellipsoid, or a
//    Hyperellipsoid" (Geometric Tools, 2013-2020). Radii sorted e0 >= e1 >= e2, query
//    folded into the first octant y >= 0. The closest point is x_i = e_i^2 y_i / (t + e_i^2)
//    where t > -e2^2 is the unique root of F(t) = sum (e_i y_i / (t + e_i^2))^2 - 1, found by
//    bisection. We bisect on u = (t + e2^2) / e2^2 > 0 and write each term as
//    z_i / ((1 - q_i) + u q_i) with z_i = y_i / e_i and q_i = (e2 / e_i)^2 in (0, 1]: no
//    term overflows for any ratio of radii, and u keeps full relative precision near 0
//    (points close to the plane of the two largest axes). Radii below 2^-59 (float) or
//    2^-507 (double) times the problem's scale are raised to that floor, which keeps z_i
//    and q_i clear of overflow and underflow for any ratio of radii at a cost far below
//    the precision of the coordinates. Bisection steps are geometric while the bracket
//    spans more than a factor 4, then arithmetic, and stop when the midpoint equals an
//    end: a bounded number of iterations. Points with y2 = 0 use Eberly's closed form when
//    they lie inside the evolute region of the minor plane and otherwise the 2-D ellipse
//    problem (same method one dimension down). The result is kept in normalised form
//    w = x / e, renormalised to |w| = 1 and mapped back with the true radii, so the point
//    lies on the surface to rounding. The sign of the distance comes from contains() so
//    that the two queries always agree.
//  - mass_properties: V = 4/3 pi abc, I_xx = m (b^2 + c^2) / 5 and cyclic.
#include <proxima/core/validate.hpp>
#include <proxima/geometry/raycast.hpp>
#include <proxima/shapes/ellipsoid.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "shapes/far_point.hpp"

namespace proxima {

namespace {

// The vector divided by its largest |component| (so that component is +-1); zero stays zero.
Vec3 scale_to_unit_max(const Vec3& v) {
  const Real m = std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)});
  return m > Real(0) ? v / m : v;
}

// Unit vector along v (zero gives zero), without overflow or underflow of the squares.
Vec3 robust_normalize(const Vec3& v) {
  const Vec3 s = scale_to_unit_max(v);
  const Real len2 = glm::dot(s, s);
  return len2 > Real(0) ? s / std::sqrt(len2) : s;
}

// Upper bound on the bisection iterations: the geometric phase needs at most
// log2(log2(max/min)) ~ 11 steps and the arithmetic phase one per mantissa bit.
constexpr int kMaxBisections = 256;

// Root u > 0 of sum_i (z[i] / ((1 - q[i]) + u q[i]))^2 = 1 for N terms, where q[N-1] = 1,
// z[N-1] > 0, z[i] >= 0 and 0 <= q[i] <= 1. `g` = sum z[i]^2 - 1 != 0 (the value at u = 1).
template <std::size_t N>
Real bisect_root(const std::array<Real, N>& z, const std::array<Real, N>& q, Real g) {
  Real u0;
  Real u1;
  if (g < Real(0)) {
    // Inside: the root lies in (z[N-1], 1).
    u0 = z[N - 1];
    u1 = Real(1);
  } else {
    // Outside: F(1) = g > 0, and F(sum z_i / q_i) <= 0 since each term is at most
    // (z_i / (u q_i))^2.
    u0 = std::max(Real(1), z[N - 1]);
    Real bound = Real(0);
    for (std::size_t i = 0; i < N; ++i) {
      bound += q[i] > Real(0) ? z[i] / q[i] : (z[i] > Real(0) ? kRealMax : Real(0));
    }
    u1 = std::max(u0, std::min(bound, kRealMax));
  }
  for (int iter = 0; iter < kMaxBisections; ++iter) {
    const Real u = u1 > Real(4) * u0 ? std::sqrt(u0) * std::sqrt(u1) : u0 + (u1 - u0) * Real(0.5);
    if (!(u > u0 && u < u1)) break;
    Real f = Real(-1);
    for (std::size_t i = 0; i < N; ++i) {
      const Real ratio = z[i] / ((Real(1) - q[i]) + u * q[i]);
      f += ratio * ratio;
    }
    if (f > Real(0)) {
      u0 = u;
    } else if (f < Real(0)) {
      u1 = u;
    } else {
      return u;
    }
  }
  return u0 + (u1 - u0) * Real(0.5);
}

// Closest point of the ellipse (x/e0)^2 + (y/e1)^2 = 1, e0 >= e1 > 0, to a point (y0, y1) >= 0
// given as z = (y0/e0, y1/e1) and q = (e1/e0)^2: returns the normalised coordinates
// (w0, w1) = (x0/e0, x1/e1) >= 0 of the nearest point.
void closest_on_ellipse(Real z0, Real z1, Real q, Real& w0, Real& w1) {
  if (z1 > Real(0)) {
    const Real g = z0 * z0 + z1 * z1 - Real(1);
    if (g == Real(0)) {
      w0 = z0;
      w1 = z1;
      return;
    }
    const Real u = bisect_root<2>({z0, z1}, {q, Real(1)}, g);
    w0 = z0 / ((Real(1) - q) + u * q);
    w1 = z1 / u;
    return;
  }
  // y1 = 0: on the major axis. Inside the evolute's reach the nearest point leaves the axis.
  const Real d = Real(1) - q;
  if (z0 < d) {
    w0 = z0 / d;
    w1 = std::sqrt(std::max(Real(0), Real(1) - w0 * w0));
  } else {
    w0 = Real(1);
    w1 = Real(0);
  }
}

}  // namespace

Result<Ellipsoid> Ellipsoid::create(const Vec3& radii) {
  if (auto e = validate::positive(radii.x, "radii.x")) return *e;
  if (auto e = validate::positive(radii.y, "radii.y")) return *e;
  if (auto e = validate::positive(radii.z, "radii.z")) return *e;
  return Ellipsoid(radii);
}

Vec3 Ellipsoid::support(const Vec3& direction) const {
  if (!is_finite(direction)) return {Real(0), Real(0), radii_.z};
  const Vec3 d = scale_to_unit_max(direction);
  const Vec3 rd = scale_to_unit_max(radii_ * d);
  const Real len2 = glm::dot(rd, rd);
  if (!(len2 > Real(0))) return {Real(0), Real(0), radii_.z};
  return radii_ * (rd / std::sqrt(len2));
}

Aabb Ellipsoid::local_aabb() const { return {-radii_, radii_}; }

Aabb Ellipsoid::world_aabb(const Transform& pose) const {
  const Mat3 m = pose.rotation_matrix();  // m[column][row]
  Vec3 e;
  for (int i = 0; i < 3; ++i) {
    const Real a = m[0][i] * radii_.x;
    const Real b = m[1][i] * radii_.y;
    const Real c = m[2][i] * radii_.z;
    e[i] = std::sqrt(a * a + b * b + c * c);
  }
  return {pose.position - e, pose.position + e};
}

std::optional<RayHit> Ellipsoid::raycast(const Ray& ray, Real max_t) const {
  // The checks of every ray cast: finite ray, max_t >= 0 (NaN never hits).
  if (!is_finite(ray.origin) || !is_finite(ray.direction) || !(max_t >= Real(0))) return std::nullopt;
  if (contains(ray.origin)) {
    RayHit hit;
    hit.t = Real(0);
    hit.point = ray.origin;
    // -direction / |direction|; a zero direction gets +z, as in every ray cast.
    const Vec3 back = -robust_normalize(ray.direction);
    hit.normal = glm::dot(back, back) > Real(0) ? back : Vec3(Real(0), Real(0), Real(1));
    return hit;
  }
  const Ray scaled{ray.origin / radii_, ray.direction / radii_};
  const auto unit_hit = geometry::ray_sphere(scaled, max_t, Vec3(Real(0)), Real(1));
  if (!unit_hit) return std::nullopt;
  RayHit hit;
  hit.t = unit_hit->t;
  hit.point = ray.at(hit.t);
  // Gradient of the implicit function at the hit: (p / R) / R with p / R on the unit
  // sphere, scaled by the smallest radius so that it cannot overflow.
  const Real r_min = std::min({radii_.x, radii_.y, radii_.z});
  hit.normal = robust_normalize(scaled.at(hit.t) * (r_min / radii_));
  if (!(glm::dot(hit.normal, hit.normal) > Real(0))) hit.normal = unit_hit->normal;
  return hit;
}

bool Ellipsoid::contains(const Vec3& point) const {
  const Vec3 z = point / radii_;
  return glm::dot(z, z) <= Real(1);
}

SurfacePoint Ellipsoid::closest_point(const Vec3& point) const {
  if (!is_finite(point)) return detail::far_top_point(radii_.z);
  const bool inside = contains(point);

  // Sort the axes by decreasing radius: axis[0] is the largest, axis[2] the smallest.
  std::array<int, 3> axis{0, 1, 2};
  std::sort(axis.begin(), axis.end(), [this](int a, int b) { return radii_[a] > radii_[b]; });
  std::array<Real, 3> e{};
  std::array<Real, 3> y{};
  for (int k = 0; k < 3; ++k) {
    e[k] = radii_[axis[k]];
    y[k] = std::abs(point[axis[k]]);
  }
  // Radii below radius_floor = 2^-59 (float) or 2^-507 (double) times the problem's scale are
  // raised to it: far below the precision of any coordinate at that scale, and it keeps
  // z = y / e and (e_i / e2)^2 clear of overflow and underflow for any ratio of radii.
  const Real radius_floor = Real(16) * std::sqrt(std::numeric_limits<Real>::min()) * std::max({e[0], y[0], y[1], y[2]});
  std::array<Real, 3> z{};
  std::array<Real, 3> q{};
  for (int k = 0; k < 3; ++k) z[k] = y[k] / std::max(e[k], radius_floor);
  const Real e2 = std::max(e[2], radius_floor);
  for (int k = 0; k < 3; ++k) {
    const Real ratio = e2 / std::max(e[k], radius_floor);
    q[k] = ratio * ratio;
  }
  q[2] = Real(1);

  // w = normalised coordinates x / e of the nearest point (first octant, sorted axes).
  std::array<Real, 3> w{};
  const Real g = z[0] * z[0] + z[1] * z[1] + z[2] * z[2] - Real(1);
  if (z[2] > Real(0)) {
    if (g == Real(0)) {
      w = z;
    } else {
      const Real u = bisect_root<3>(z, q, g);
      w[0] = z[0] / ((Real(1) - q[0]) + u * q[0]);
      w[1] = z[1] / ((Real(1) - q[1]) + u * q[1]);
      w[2] = z[2] / u;
    }
  } else {
    // y2 = 0: in the plane of the two largest axes. Inside the evolute region the nearest
    // point leaves the plane (closed form); otherwise it is the nearest point of the ellipse
    // in the plane.
    bool done = false;
    const Real d0 = Real(1) - q[0];
    const Real d1 = Real(1) - q[1];
    if (z[0] < d0 && z[1] < d1) {
      const Real w0 = z[0] / d0;
      const Real w1 = z[1] / d1;
      const Real discr = Real(1) - w0 * w0 - w1 * w1;
      if (discr > Real(0)) {
        w = {w0, w1, std::sqrt(discr)};
        done = true;
      }
    }
    if (!done) {
      const Real ratio = std::max(e[1], radius_floor) / std::max(e[0], radius_floor);
      closest_on_ellipse(z[0], z[1], ratio * ratio, w[0], w[1]);
      w[2] = Real(0);
    }
  }
  // |w| = 1 at the root; renormalising removes what the bisection left (which matters only
  // when w was computed from denormal inputs), so the point is on the surface to rounding.
  {
    const Real m = std::max({w[0], w[1], w[2]});
    if (m > Real(0)) {
      for (Real& c : w) c /= m;
      const Real len = std::sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
      for (Real& c : w) c /= len;
    } else {
      w = {Real(0), Real(0), Real(1)};
    }
  }

  SurfacePoint sp;
  Vec3 wv;
  for (int k = 0; k < 3; ++k) wv[axis[k]] = point[axis[k]] < Real(0) ? -w[k] : w[k];
  sp.point = radii_ * wv;
  // Outward normal: the gradient (x / R^2) = w / R, scaled by the smallest radius.
  const Real e_min = e[2];
  Vec3 n;
  for (int i = 0; i < 3; ++i) n[i] = wv[i] * (e_min / radii_[i]);
  n = robust_normalize(n);
  if (!(glm::dot(n, n) > Real(0))) {
    // Underflow for absurd ratios of radii: the axis of the largest |w_i|.
    const Vec3 aw = glm::abs(wv);
    const int k = aw.x >= aw.y ? (aw.x >= aw.z ? 0 : 2) : (aw.y >= aw.z ? 1 : 2);
    n = Vec3(Real(0));
    n[k] = wv[k] < Real(0) ? Real(-1) : Real(1);
  }
  sp.normal = n;
  const Real d = glm::length(point - sp.point);
  sp.signed_distance = inside ? -d : d;
  return sp;
}

MassProperties Ellipsoid::mass_properties(Real density) const {
  const Vec3 r2 = radii_ * radii_;
  MassProperties m;
  m.volume = Real(4) / Real(3) * kPi * radii_.x * radii_.y * radii_.z;
  m.mass = density * m.volume;
  m.inertia = Mat3(Real(0));
  m.inertia[0][0] = Real(0.2) * m.mass * (r2.y + r2.z);
  m.inertia[1][1] = Real(0.2) * m.mass * (r2.x + r2.z);
  m.inertia[2][2] = Real(0.2) * m.mass * (r2.x + r2.y);
  return m;
}

}  // namespace proxima
