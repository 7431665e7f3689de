#pragma once
// Internal helpers shared by the ray-cast files (src/geometry/raycast_*.cpp): input
// checks, overflow-safe lengths, the "origin inside" answer and the final hit assembly.
// Not installed; the public interface is include/proxima/geometry/raycast.hpp.

#include <proxima/core/math.hpp>
#include <proxima/geometry/ray.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

namespace proxima::geometry::detail {

/// Euclidean length without overflow or underflow of the squares: the vector is scaled
/// by its largest component first. 0 for the zero vector, +inf when a component is infinite.
inline Real safe_length(const Vec3& v) {
  const Real m = std::max(std::abs(v.x), std::max(std::abs(v.y), std::abs(v.z)));
  if (!(m > Real(0))) return Real(0);
  if (!std::isfinite(m)) return m;
  const Vec3 s = v / m;
  return m * std::sqrt(glm::dot(s, s));
}

/// Splits v into |v| and v / |v| (both computed from v scaled by its largest component,
/// so that a denormal or huge v still gives a unit direction). Returns false (and leaves
/// the outputs alone) when v is zero or not finite.
inline bool length_and_direction(const Vec3& v, Real& length, Vec3& unit) {
  const Real m = std::max(std::abs(v.x), std::max(std::abs(v.y), std::abs(v.z)));
  if (!(m > Real(0)) || !std::isfinite(m)) return false;
  const Vec3 s = v / m;
  const Real ls = std::sqrt(glm::dot(s, s));  // in [1, sqrt(3)]
  length = m * ls;
  unit = s / ls;
  return true;
}

/// v / |v|, or `fallback` when v is zero (or not finite).
inline Vec3 safe_normalize(const Vec3& v, const Vec3& fallback) {
  Real length;
  Vec3 unit;
  return length_and_direction(v, length, unit) ? unit : fallback;
}

/// The unit normal reported for an inside hit made by a zero direction (any fixed unit
/// vector would do; this one keeps the answer defined).
inline constexpr Vec3 kZeroDirectionNormal{Real(0), Real(0), Real(1)};

/// A ray reduced to a unit direction: point(s) = origin + s * unit, where the distance s
/// relates to the caller's parameter by t = s / length.
struct UnitRay {
  Vec3 origin{Real(0)};   ///< the ray's origin
  Vec3 unit{Real(0)};     ///< direction / |direction|, zero for a zero direction
  Real length = Real(0);  ///< |direction| (0 for a zero direction)
};

/// Checks the query (finite origin and direction, max_t >= 0 and not NaN; +inf allowed)
/// and builds the unit ray. Returns false when the query can never hit.
inline bool prepare(const Ray& ray, Real max_t, UnitRay& out) {
  // A quiet comparison: a NaN max_t is refused without raising the invalid flag.
  if (!is_finite(ray.origin) || !is_finite(ray.direction) || !std::isgreaterequal(max_t, Real(0))) return false;
  out.origin = ray.origin;
  if (!length_and_direction(ray.direction, out.length, out.unit)) {
    out.length = Real(0);
    out.unit = Vec3(Real(0));
  }
  return true;
}

/// The answer for an origin inside a solid: t = 0, point = origin, normal = -unit
/// direction (kZeroDirectionNormal for a zero direction).
inline RayHit inside_hit(const Ray& ray, const UnitRay& r) {
  return {Real(0), ray.origin, r.length > Real(0) ? -r.unit : kZeroDirectionNormal};
}

/// A surface hit at parameter t (units of |direction|) with the (not necessarily unit)
/// normal `n`; nullopt when t is not finite or outside [0, max_t].
inline std::optional<RayHit> surface_hit(const Ray& ray, Real max_t, Real t, const Vec3& n) {
  if (!std::isfinite(t) || t < Real(0) || t > max_t) return std::nullopt;
  const Vec3 p = ray.at(t);
  if (!is_finite(p)) return std::nullopt;
  return RayHit{t, p, safe_normalize(n, kZeroDirectionNormal)};
}

/// A parameter interval [lo, hi] on a line, with the feature that bounds it from below
/// (an index the caller interprets). Empty when lo > hi. Infinite ends are allowed; no
/// arithmetic is done on them.
struct Interval {
  Real lo = -std::numeric_limits<Real>::infinity();  ///< entry parameter
  Real hi = std::numeric_limits<Real>::infinity();   ///< exit parameter
  int lo_feature = -1;                               ///< feature of the entry (-1: none)

  /// True when no parameter lies in the interval.
  bool empty() const { return !(lo <= hi); }
  /// Intersection with another interval; the entry feature follows the later entry
  /// (ties keep this one's).
  Interval clipped(const Interval& o) const {
    Interval r = *this;
    if (o.lo > r.lo) {
      r.lo = o.lo;
      r.lo_feature = o.lo_feature;
    }
    r.hi = std::min(r.hi, o.hi);
    return r;
  }
};

/// The parameters where a line enters and leaves the slab lo <= origin + s * dir <= hi
/// (1-D). A zero `dir` gives the whole line or nothing. Never divides by zero.
inline Interval slab_interval(Real origin, Real dir, Real lo, Real hi, int lo_feature, int hi_feature) {
  Interval r;
  if (dir == Real(0)) {
    if (origin < lo || origin > hi) {
      r.lo = std::numeric_limits<Real>::infinity();
      r.hi = -r.lo;
    }
    return r;
  }
  const Real t_lo = (lo - origin) / dir;
  const Real t_hi = (hi - origin) / dir;
  if (dir > Real(0)) {
    r.lo = t_lo;
    r.hi = t_hi;
    r.lo_feature = lo_feature;
  } else {
    r.lo = t_hi;
    r.hi = t_lo;
    r.lo_feature = hi_feature;
  }
  return r;
}

/// The set {s : A s^2 + 2 B s + C <= 0} of a quadratic given with half its linear term,
/// when it is one interval, or the two half-lines (-inf, r1] and [r2, +inf) when A < 0.
/// The roots come from the cancellation-free form q = -(B + sign(B) sqrt(B^2 - AC)),
/// r = q / A and C / q (Press et al., Numerical Recipes, 5.6). `disc` is B^2 - AC,
/// computed by the caller in whatever well-conditioned form its geometry allows.
struct QuadraticSet {
  Interval first;   ///< [r1, r2] (A > 0), (-inf, r1] (A < 0), or the whole/half line (A = 0)
  Interval second;  ///< [r2, +inf) when A < 0, otherwise empty
};

/// Solves the set where the quadratic is <= 0; `lateral` tags the finite root ends.
inline QuadraticSet quadratic_nonpositive(Real a, Real b, Real c, Real disc, int lateral) {
  constexpr Real kInf = std::numeric_limits<Real>::infinity();
  QuadraticSet s;
  s.second.lo = kInf;
  s.second.hi = -kInf;
  if (a == Real(0)) {
    // Linear 2 B s + C <= 0.
    if (b > Real(0)) {
      s.first.hi = -c / (Real(2) * b);
    } else if (b < Real(0)) {
      s.first.lo = -c / (Real(2) * b);
      s.first.lo_feature = lateral;
    } else if (c > Real(0)) {
      s.first.lo = kInf;
      s.first.hi = -kInf;
    }
    return s;
  }
  if (disc < Real(0)) {
    if (a > Real(0)) {
      s.first.lo = kInf;
      s.first.hi = -kInf;
    }
    // a < 0 and no real root: the quadratic is negative everywhere (only reachable by
    // rounding); the whole line is kept.
    return s;
  }
  const Real root = std::sqrt(disc);
  const Real q = -(b + std::copysign(root, b));
  Real r1;
  Real r2;
  if (q == Real(0)) {
    r1 = r2 = Real(0);  // b = 0 and disc = 0: double root at 0 (then c = 0 too)
  } else {
    r1 = q / a;
    r2 = c / q;
    if (r1 > r2) std::swap(r1, r2);
  }
  if (a > Real(0)) {
    s.first.lo = r1;
    s.first.hi = r2;
    s.first.lo_feature = lateral;
  } else {
    s.first.hi = r1;
    s.second.lo = r2;
    s.second.hi = kInf;
    s.second.lo_feature = lateral;
  }
  return s;
}

/// An orthonormal frame (e1, e2, axis) along segment p0p1, with its length: the local
/// frame of the capsule, cylinder and cone casts.
struct AxisFrame {
  Vec3 e1{Real(1), Real(0), Real(0)};    ///< first unit vector orthogonal to the axis
  Vec3 e2{Real(0), Real(1), Real(0)};    ///< second unit vector orthogonal to the axis
  Vec3 axis{Real(0), Real(0), Real(1)};  ///< (p1 - p0) / |p1 - p0|
  Real length = Real(0);                 ///< |p1 - p0|; 0 when p0 == p1 (axis then +z)

  /// Coordinates of a vector in this frame (e1, e2, axis components).
  Vec3 local(const Vec3& v) const { return {glm::dot(v, e1), glm::dot(v, e2), glm::dot(v, axis)}; }
  /// The vector whose coordinates in this frame are (x, y, z).
  Vec3 world(Real x, Real y, Real z) const { return x * e1 + y * e2 + z * axis; }
};

/// The frame of segment p0p1 (finite points); a zero-length segment keeps the default axes.
inline AxisFrame axis_frame(const Vec3& p0, const Vec3& p1) {
  AxisFrame f;
  if (length_and_direction(p1 - p0, f.length, f.axis)) orthonormal_basis(f.axis, f.e1, f.e2);
  return f;
}

/// Where a line (unit direction) enters a solid, and the outward normal there.
struct Entry {
  Real s = Real(0);      ///< distance along the unit direction
  Vec3 normal{Real(0)};  ///< outward normal (not necessarily unit)
};

/// Entry of the line m + s u (u unit, m relative to the centre) into the ball of `radius`
/// for s >= 0, assuming m is outside (a value 0 is returned if rounding puts it inside).
/// Defined in raycast_sphere.cpp; the capsule uses it for its end caps.
std::optional<Entry> ball_entry(const Vec3& m, const Vec3& u, Real radius);

/// The parameters where the 2-D line m + s u lies in the disc |x| <= r (u need not be
/// unit; u = 0 gives the whole line or nothing). The finite entry carries `feature`.
/// Defined in raycast_cylinder.cpp; the capsule uses it for its body.
Interval disc_interval(const Vec2& m, const Vec2& u, Real r, int feature);

}  // namespace proxima::geometry::detail
