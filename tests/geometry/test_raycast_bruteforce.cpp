// Ray casts against solid primitives checked by brute force: the reference marches along
// the ray in fine steps evaluating a point-containment function written here (in double),
// then bisects the first outside-to-inside step. Seeded random sweeps at unit, huge
// (1e4) and tiny (1e-4) scales and far from the origin (1e4).
//
// Each solid is {p : f(p) <= 0} where f is the maximum of the signed distances of the
// pieces bounding it (planes, a cylinder, a cone...). Outside, f never exceeds the true
// distance; inside, f is the true signed distance or deeper. So:
//   - a sample with f <= -delta proves the ray passes at least delta deep: it must hit,
//     at the bisected entry, with the normal of a piece active there;
//   - no sample with f <= delta, samples spaced delta / 2 apart, proves the ray stays more
//     than delta away from the solid: it must miss;
//   - anything between is grazing and is not judged (counted, and kept rare).
#include <gtest/gtest.h>

#include <proxima/core/tolerance.hpp>
#include <proxima/geometry/raycast.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <sstream>
#include <string>

#include "support/random.hpp"

namespace proxima::geometry {
namespace test_raycast_bruteforce {

using D3 = glm::dvec3;

D3 wide(const Vec3& v) { return D3(v); }

/// One piece of a solid's boundary at a point: its signed distance, unit outward
/// gradient, and radius of curvature (for the normal's tolerance; huge for planes).
struct Piece {
  double value = 0;
  D3 gradient{0, 0, 1};
  double curvature_radius = 1e300;
};

/// Bounding sphere of a solid (reference side, double).
struct Bound {
  D3 center{0};
  double radius = 0;
};

// ---------------------------------------------------------------------------------------
// The solids: containment pieces (reference) and the cast under test. The pieces are
// evaluated at the ray point o + t d through (o - anchor) + t d, so that a solid far from
// the origin costs the reference no accuracy (o - anchor is exact or nearly so).

/// (o - anchor) + t d: a point of the ray relative to `anchor`.
D3 rel(const D3& o, double t, const D3& d, const Vec3& anchor) { return (o - wide(anchor)) + t * d; }

struct SphereSolid {
  Vec3 center;
  Real radius;
  int pieces(const D3& o, double t, const D3& d, Piece* out) const {
    const D3 v = rel(o, t, d, center);
    const double len = glm::length(v);
    out[0] = {len - double(radius), len > 0 ? v / len : D3(0, 0, 1), double(radius)};
    return 1;
  }
  Bound bound() const { return {wide(center), double(radius)}; }
  bool singular(const D3&, double) const { return false; }
  double location_error(const Ray&) const { return 0; }
  std::optional<RayHit> cast(const Ray& ray, Real max_t) const { return ray_sphere(ray, max_t, center, radius); }
};

struct AabbSolid {
  Aabb box;
  int pieces(const D3& o, double t, const D3& d, Piece* out) const {
    const D3 hi = rel(o, t, d, box.max);
    const D3 lo = rel(o, t, d, box.min);
    for (int j = 0; j < 3; ++j) {
      D3 a(0);
      a[j] = 1;
      out[2 * j] = {hi[j], a};
      out[2 * j + 1] = {-lo[j], -a};
    }
    return 6;
  }
  Bound bound() const {
    return {(wide(box.min) + wide(box.max)) * 0.5, glm::length(wide(box.max) - wide(box.min)) * 0.5};
  }
  bool singular(const D3&, double) const { return false; }
  double location_error(const Ray&) const { return 0; }
  std::optional<RayHit> cast(const Ray& ray, Real max_t) const { return ray_aabb(ray, max_t, box); }
};

struct ObbSolid {
  Vec3 center;
  Mat3 axes;
  Vec3 half;
  int pieces(const D3& o, double t, const D3& d, Piece* out) const {
    const D3 v = rel(o, t, d, center);
    for (int j = 0; j < 3; ++j) {
      const D3 a = wide(axes[j]);
      const double q = glm::dot(v, a);
      out[2 * j] = {q - double(half[j]), a};
      out[2 * j + 1] = {-q - double(half[j]), -a};
    }
    return 6;
  }
  Bound bound() const { return {wide(center), glm::length(wide(half))}; }
  bool singular(const D3&, double) const { return false; }
  double location_error(const Ray&) const { return 0; }
  std::optional<RayHit> cast(const Ray& ray, Real max_t) const { return ray_obb(ray, max_t, center, axes, half); }
};

struct CapsuleSolid {
  Vec3 p0, p1;
  Real radius;
  int pieces(const D3& o, double t, const D3& d, Piece* out) const {
    const D3 ab = wide(p1) - wide(p0);
    const D3 pa = rel(o, t, d, p0);
    const double l2 = glm::dot(ab, ab);
    const double s = l2 > 0 ? std::clamp(glm::dot(pa, ab) / l2, 0.0, 1.0) : 0.0;
    const D3 v = pa - s * ab;
    const double len = glm::length(v);
    out[0] = {len - double(radius), len > 0 ? v / len : D3(0, 0, 1), double(radius)};
    return 1;
  }
  Bound bound() const { return {(wide(p0) + wide(p1)) * 0.5, glm::length(wide(p1) - wide(p0)) * 0.5 + double(radius)}; }
  bool singular(const D3&, double) const { return false; }
  double location_error(const Ray&) const { return 0; }
  std::optional<RayHit> cast(const Ray& ray, Real max_t) const { return ray_capsule(ray, max_t, p0, p1, radius); }
};

struct CylinderSolid {
  Vec3 p0, p1;
  Real radius;
  int pieces(const D3& o, double t, const D3& d, Piece* out) const {
    const D3 a0 = wide(p0);
    const double len = glm::length(wide(p1) - a0);
    const D3 axis = (wide(p1) - a0) / len;
    const D3 pa = rel(o, t, d, p0);
    const double z = glm::dot(pa, axis);
    const D3 w = pa - z * axis;
    const double rho = glm::length(w);
    out[0] = {rho - double(radius), rho > 0 ? w / rho : D3(0, 0, 1), double(radius)};
    out[1] = {-z, -axis};
    out[2] = {z - len, axis};
    return 3;
  }
  Bound bound() const {
    const double h = glm::length(wide(p1) - wide(p0)) * 0.5;
    return {(wide(p0) + wide(p1)) * 0.5, std::sqrt(h * h + double(radius) * double(radius))};
  }
  bool singular(const D3&, double) const { return false; }
  double location_error(const Ray&) const { return 0; }
  std::optional<RayHit> cast(const Ray& ray, Real max_t) const { return ray_cylinder(ray, max_t, p0, p1, radius); }
};

struct ConeSolid {
  Vec3 apex, base;
  Real radius;
  int pieces(const D3& o, double t, const D3& d, Piece* out) const {
    const D3 a0 = wide(apex);
    const double height = glm::length(wide(base) - a0);
    const D3 axis = (wide(base) - a0) / height;
    const double slant = std::hypot(height, double(radius));
    const double cos_a = height / slant;
    const double sin_a = double(radius) / slant;
    const D3 pa = rel(o, t, d, apex);
    const double z = glm::dot(pa, axis);
    const D3 w = pa - z * axis;
    const double rho = glm::length(w);
    const D3 radial = rho > 0 ? w / rho : D3(0);
    out[0] = {cos_a * rho - sin_a * z, cos_a * radial - sin_a * axis, std::max(rho, 1e-300) / cos_a};
    out[1] = {z - height, axis};
    return 2;
  }
  Bound bound() const {
    const double h = glm::length(wide(base) - wide(apex)) * 0.5;
    return {(wide(apex) + wide(base)) * 0.5, std::sqrt(h * h + double(radius) * double(radius))};
  }
  // Near the apex the lateral normal turns fast; any normal of the apex's normal cone is
  // right there.
  bool singular(const D3& p, double act) const { return glm::length(p - wide(apex)) < act; }
  double location_error(const Ray&) const { return 0; }
  std::optional<RayHit> cast(const Ray& ray, Real max_t) const { return ray_cone(ray, max_t, apex, base, radius); }
};

struct HalfspaceSolid {
  Vec3 normal;
  Real offset;
  Vec3 center;  // a point near which rays are aimed
  int pieces(const D3& o, double t, const D3& d, Piece* out) const {
    // n.p - offset in long double: the offset is a large number far from the origin.
    using L = long double;
    const L dist = L(normal.x) * (L(o.x) + L(t) * L(d.x)) + L(normal.y) * (L(o.y) + L(t) * L(d.y)) +
                   L(normal.z) * (L(o.z) + L(t) * L(d.z)) - L(offset);
    const D3 n = glm::normalize(wide(normal));
    out[0] = {double(dist) / glm::length(wide(normal)), n};
    return 1;
  }
  Bound bound() const { return {wide(center), 1e300}; }  // unbounded
  bool singular(const D3&, double) const { return false; }
  // The cast forms n.origin - offset in double: a few roundings at the magnitude of the
  // coordinates (nothing else of the solid is that large).
  double location_error(const Ray& ray) const {
    const double eps = std::numeric_limits<double>::epsilon();
    return 4 * eps * (glm::length(wide(normal)) * glm::length(wide(ray.origin)) + std::abs(double(offset))) /
           glm::length(wide(normal));
  }
  std::optional<RayHit> cast(const Ray& ray, Real max_t) const { return ray_halfspace(ray, max_t, normal, offset); }
};

template <class S>
double containment(const S& solid, const D3& o, double t, const D3& d) {
  std::array<Piece, 6> pieces;
  const int n = solid.pieces(o, t, d, pieces.data());
  double f = -1e300;
  for (int i = 0; i < n; ++i) f = std::max(f, pieces[i].value);
  return f;
}

// ---------------------------------------------------------------------------------------
// The sweep.

/// A placement of the random geometry: size and distance from the origin.
struct Setting {
  Real scale;
  Vec3 offset;
};

struct Stats {
  int hits = 0, misses = 0, inside = 0, grazing = 0;
  int total() const { return hits + misses + inside + grazing; }
};

/// Judges one ray against the reference. Returns false (after reporting) on a mismatch.
template <class S>
bool check_ray(const S& solid, const Ray& ray, Real max_t, const Setting& setting, Stats& stats) {
  const double scale = double(setting.scale);
  const double eps = double(kEpsilon);
  // Rounding of the cast, relative to the primitive's size (the casts form differences of
  // nearby coordinates first, so the distance from the origin does not enter).
  const double tol = 1000 * eps * scale;
  const double delta = std::max(2e-3 * scale, 8 * tol);
  const D3 o = wide(ray.origin);
  const D3 d = wide(ray.direction);
  const double dlen = glm::length(d);
  const auto hit = solid.cast(ray, max_t);
  auto describe = [&] {
    std::ostringstream s;
    s.precision(17);
    s << "origin (" << o.x << ", " << o.y << ", " << o.z << ") direction (" << d.x << ", " << d.y << ", " << d.z
      << ") max_t " << max_t;
    if (hit)
      s << " -> hit t " << hit->t << " normal (" << hit->normal.x << ", " << hit->normal.y << ", " << hit->normal.z
        << ")";
    else
      s << " -> miss";
    return s.str();
  };

  const double f0 = containment(solid, o, 0, d);
  if (f0 <= -delta) {
    ++stats.inside;
    EXPECT_TRUE(hit && hit->t == Real(0) && hit->point == ray.origin) << describe();
    if (!hit) return false;
    EXPECT_LT(glm::length(wide(hit->normal) + d / dlen), 1e-6) << describe();
    return !::testing::Test::HasFailure();
  }
  if (f0 < delta) {
    ++stats.grazing;
    return true;
  }

  // The part of the ray inside the bounding sphere (grown by 4 delta).
  const Bound b = solid.bound();
  double ta = 0;
  double tb = double(max_t);
  if (b.radius < 1e299) {
    const double r = b.radius + 4 * delta;
    const D3 m = o - b.center;
    const double qa = glm::dot(d, d);
    const double qb = glm::dot(m, d);
    const double qc = glm::dot(m, m) - r * r;
    const double disc = qb * qb - qa * qc;
    if (disc <= 0) {
      ta = 1;
      tb = 0;
    } else {
      const double root = std::sqrt(disc);
      ta = std::max(ta, (-qb - root) / qa);
      tb = std::min(tb, (-qb + root) / qa);
    }
  } else {
    tb = std::min(tb, 12 * scale / dlen);  // half-space: the caller keeps max_t below this
  }

  bool deep = false;
  bool near = false;
  double t_out = 0;
  double t_in = 0;
  bool entered = false;
  if (ta <= tb) {
    const double step = 0.5 * delta / dlen;
    const auto n = static_cast<long>(std::ceil((tb - ta) / step));
    double t_prev = ta;
    for (long k = 0; k <= n; ++k) {
      const double t = k == n ? tb : ta + (tb - ta) * double(k) / double(n);
      const double f = containment(solid, o, t, d);
      near = near || f <= delta;
      if (f <= -delta) deep = true;
      if (!entered && f <= 0) {
        entered = true;
        t_out = t_prev;
        t_in = t;
      } else if (entered && f > 0) {
        break;  // left the (convex) solid
      }
      if (entered && deep) break;
      t_prev = t;
    }
  }

  if (deep) {
    ++stats.hits;
    // Bisect the entry between the last outside and the first inside sample.
    for (int i = 0; i < 80; ++i) {
      const double mid = 0.5 * (t_out + t_in);
      (containment(solid, o, mid, d) <= 0 ? t_in : t_out) = mid;
    }
    EXPECT_TRUE(hit.has_value()) << describe() << " reference entry t " << t_in;
    if (!hit) return false;
    // A boundary known only to `location_error` moves the entry by that over the cosine.
    std::array<Piece, 6> at_entry;
    const int entry_count = solid.pieces(o, t_in, d, at_entry.data());
    double cosine = 1;
    for (int i = 0; i < entry_count; ++i) {
      if (at_entry[i].value >= -tol) cosine = std::min(cosine, std::abs(glm::dot(at_entry[i].gradient, d)) / dlen);
    }
    const double tol_t = tol + solid.location_error(ray) / std::max(cosine, 1e-3);
    EXPECT_NEAR(double(hit->t) * dlen, t_in * dlen, tol_t) << describe() << " reference entry t " << t_in;
    EXPECT_NEAR(glm::length(wide(hit->normal)), 1.0, 4 * eps) << describe();
    const D3 p = o + t_in * d;
    const double act = 100 * tol;
    if (!solid.singular(p, 100 * act)) {
      std::array<Piece, 6> pieces;
      const int count = solid.pieces(o, t_in, d, pieces.data());
      bool matched = false;
      double best = 1e300;
      for (int i = 0; i < count; ++i) {
        if (pieces[i].value < -act) continue;
        const double err = glm::length(wide(hit->normal) - pieces[i].gradient);
        best = std::min(best, err);
        if (err <= 2000 * eps + 10 * tol / pieces[i].curvature_radius) matched = true;
      }
      EXPECT_TRUE(matched) << describe() << " normal error " << best;
    }
    return !::testing::Test::HasFailure();
  }
  if (!near) {
    ++stats.misses;
    EXPECT_FALSE(hit.has_value()) << describe();
    return !hit.has_value();
  }
  ++stats.grazing;
  return true;
}

/// Random ray aimed near `target_center` (size `scale`), sometimes along `special`
/// directions (the solid's axes), sometimes starting inside.
Ray random_ray(test::Random& rng, const Vec3& target_center, Real scale, const Vec3* special, int special_count,
               Real& max_t) {
  const Vec3 target = target_center + scale * rng.in_ball(Real(1.3));
  Vec3 origin;
  Vec3 dir;
  const int mode = rng.integer(0, 99);
  if (mode < 15 && special_count > 0) {
    const Real sign = rng.integer(0, 1) != 0 ? Real(1) : Real(-1);
    dir = special[rng.integer(0, special_count - 1)] * sign;
    origin = target - dir * (scale * rng.uniform(Real(0.5), Real(4)));
  } else {
    origin = mode < 25 ? target_center + scale * rng.in_ball(Real(0.4)) : target_center + scale * rng.in_ball(Real(4));
    dir = target - origin;
    if (!(glm::length(dir) > Real(1e-3) * scale)) dir = scale * rng.unit_vector();
  }
  dir *= rng.uniform(Real(0.1), Real(5)) / glm::length(dir) * scale;
  const Real reach = glm::length(target - origin) / glm::length(dir);
  max_t = rng.integer(0, 2) == 0 ? std::numeric_limits<Real>::infinity() : reach * rng.uniform(Real(0), Real(2.5));
  return {origin, dir};
}

// Built at run time: GCC 12 with -frounding-math (CGAL's flag) miscompiles the static
// initialisation of an aggregate holding an inexact constant such as Real(1e-4); this
// keeps the file correct whichever executable it is compiled into.
std::array<Setting, 4> settings() {
  return {{{Real(1), Vec3(0)},
           {Real(1e4), Vec3(0)},
           {Real(1e-4), Vec3(0)},
           {Real(1), Vec3(Real(1e4), Real(-1e4), Real(1e4))}}};
}

/// Runs `count` random cases (fewer at the extra settings) and checks the coverage.
template <class Make>
void sweep(std::uint64_t seed, int count, Make make) {
  for (const Setting& setting : settings()) {
    test::Random rng(seed);
    Stats stats;
    const int n = setting.scale == Real(1) && setting.offset == Vec3(0) ? count : count / 3;
    for (int i = 0; i < n; ++i) {
      if (!make(rng, setting, stats)) {
        ADD_FAILURE() << "case " << i << " at scale " << setting.scale << " offset " << setting.offset.x;
        return;
      }
    }
    SCOPED_TRACE(::testing::Message() << "scale " << setting.scale << " offset " << setting.offset.x);
    // The sweep must exercise every outcome and judge almost every case.
    EXPECT_GT(stats.hits, n / 5);
    EXPECT_GT(stats.misses, n / 10);
    EXPECT_GT(stats.inside, n / 50);
    EXPECT_LT(stats.grazing, n / 10);
    const std::string key = "scale_" + std::to_string(setting.scale) + "_offset_" + std::to_string(setting.offset.x);
    ::testing::Test::RecordProperty(key, std::to_string(stats.hits) + " hits, " + std::to_string(stats.misses) +
                                             " misses, " + std::to_string(stats.inside) + " inside, " +
                                             std::to_string(stats.grazing) + " grazing");
  }
}

Vec3 place(const Setting& s, test::Random& rng) { return s.offset + s.scale * rng.in_ball(Real(0.5)); }

TEST(RayCastBruteForce, Sphere) {
  sweep(101, 4000, [](test::Random& rng, const Setting& s, Stats& stats) {
    const SphereSolid solid{place(s, rng), s.scale * rng.uniform(Real(0.2), Real(1.5))};
    Real max_t;
    const Ray ray = random_ray(rng, solid.center, s.scale, nullptr, 0, max_t);
    return check_ray(solid, ray, max_t, s, stats);
  });
}

TEST(RayCastBruteForce, AxisAlignedBox) {
  const Vec3 axes[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  sweep(102, 4000, [&](test::Random& rng, const Setting& s, Stats& stats) {
    const Vec3 c = place(s, rng);
    const Vec3 half = s.scale * rng.vec3(Real(0.05), Real(1.5));
    const AabbSolid solid{Aabb{c - half, c + half}};
    Real max_t;
    const Ray ray = random_ray(rng, c, s.scale, axes, 3, max_t);
    return check_ray(solid, ray, max_t, s, stats);
  });
}

TEST(RayCastBruteForce, OrientedBox) {
  sweep(103, 4000, [](test::Random& rng, const Setting& s, Stats& stats) {
    const Mat3 axes = glm::mat3_cast(rng.rotation());
    const ObbSolid solid{place(s, rng), axes, s.scale * rng.vec3(Real(0.05), Real(1.5))};
    Real max_t;
    const Ray ray = random_ray(rng, solid.center, s.scale, &axes[0], 3, max_t);
    return check_ray(solid, ray, max_t, s, stats);
  });
}

TEST(RayCastBruteForce, Capsule) {
  sweep(104, 4000, [](test::Random& rng, const Setting& s, Stats& stats) {
    const Vec3 c = place(s, rng);
    const Vec3 axis = rng.unit_vector();
    const Real half = rng.integer(0, 9) == 0 ? Real(0) : s.scale * rng.uniform(Real(0.05), Real(1.2));
    const CapsuleSolid solid{c - half * axis, c + half * axis, s.scale * rng.uniform(Real(0.1), Real(1))};
    Real max_t;
    const Ray ray = random_ray(rng, c, s.scale, &axis, 1, max_t);
    return check_ray(solid, ray, max_t, s, stats);
  });
}

TEST(RayCastBruteForce, Cylinder) {
  sweep(105, 4000, [](test::Random& rng, const Setting& s, Stats& stats) {
    const Vec3 c = place(s, rng);
    const Vec3 axis = rng.unit_vector();
    const Real half = s.scale * rng.uniform(Real(0.05), Real(1.2));
    const CylinderSolid solid{c - half * axis, c + half * axis, s.scale * rng.uniform(Real(0.1), Real(1))};
    Real max_t;
    const Ray ray = random_ray(rng, c, s.scale, &axis, 1, max_t);
    return check_ray(solid, ray, max_t, s, stats);
  });
}

TEST(RayCastBruteForce, Cone) {
  sweep(106, 4000, [](test::Random& rng, const Setting& s, Stats& stats) {
    const Vec3 c = place(s, rng);
    const Vec3 axis = rng.unit_vector();
    const Real half = s.scale * rng.uniform(Real(0.1), Real(1.2));
    const ConeSolid solid{c + half * axis, c - half * axis, s.scale * rng.uniform(Real(0.1), Real(1.5))};
    // Special directions: the axis and a generator line.
    const Vec3 e = glm::normalize(glm::cross(axis, rng.unit_vector()));
    const Vec3 special[2] = {axis, glm::normalize((solid.base + solid.radius * e) - solid.apex)};
    Real max_t;
    const Ray ray = random_ray(rng, c, s.scale, special, 2, max_t);
    return check_ray(solid, ray, max_t, s, stats);
  });
}

TEST(RayCastBruteForce, Halfspace) {
  sweep(107, 3000, [](test::Random& rng, const Setting& s, Stats& stats) {
    const Vec3 c = place(s, rng);
    const Vec3 n = rng.vector_of_length(Real(0.5), Real(2));
    const HalfspaceSolid solid{n, glm::dot(n, c), c};
    Real max_t;
    const Vec3 unit = glm::normalize(n);
    const Ray ray = random_ray(rng, c, s.scale, &unit, 1, max_t);
    // The reference marches a bounded stretch: keep the ray within it.
    max_t = std::min(max_t, Real(10) * s.scale / glm::length(ray.direction));
    return check_ray(solid, ray, max_t, s, stats);
  });
}

// The plane is a surface without inside: checked against the closed-form crossing of the
// segment's end points' signed distances, computed in double.
TEST(RayCastBruteForce, Plane) {
  for (const Setting& s : settings()) {
    test::Random rng(108);
    int hits = 0;
    for (int i = 0; i < 2000; ++i) {
      const Vec3 c = place(s, rng);
      const Vec3 n = rng.unit_vector();
      const Real offset = glm::dot(n, c);
      Real max_t;
      const Ray ray = random_ray(rng, c, s.scale, &n, 1, max_t);
      const D3 nd = wide(n);
      const double d0 = glm::dot(nd, wide(ray.origin)) - double(offset);
      const double rate = glm::dot(nd, wide(ray.direction));
      const double tol = 1000 * double(kEpsilon) * (double(s.scale) + double(glm::length(s.offset)));
      const auto hit = ray_plane(ray, max_t, n, offset);
      const double dlen = glm::length(wide(ray.direction));
      // Distance travelled before crossing, and how far the crossing is from the end.
      const double t_ref = -d0 / rate;
      const bool crosses = rate != 0 && t_ref >= 0 && t_ref <= double(max_t);
      const bool clear = std::abs(d0) > tol && (std::isinf(max_t) || std::abs(t_ref - double(max_t)) * dlen > tol) &&
                         std::abs(rate) > 1e-3 * dlen;
      if (!clear) continue;
      ASSERT_EQ(hit.has_value(), crosses) << i;
      if (!hit) continue;
      ++hits;
      EXPECT_NEAR(double(hit->t) * dlen, t_ref * dlen, tol) << i;
      EXPECT_NEAR(glm::dot(wide(hit->normal), nd), d0 > 0 ? 1.0 : -1.0, 1e-6) << i;
    }
    EXPECT_GT(hits, 250);
  }
}

}  // namespace test_raycast_bruteforce
}  // namespace proxima::geometry
