#pragma once
// Shared helpers for the shape tests. The references here never call the code under test:
// they work from dense samples of a surface (written in the test from the shape's
// parametric description), from an implicit inside test written in the test, or from
// exhaustive search. Each check takes the sampling resolution so that its tolerance is the
// sampling error plus a precision term that scales with Real.
//
// Vocabulary:
//  - samples: points of the shape's surface, local frame;
//  - resolution: an upper bound of the distance from any surface point to its nearest
//    sample (the covering radius of the samples);
//  - inside: a callable bool(const Vec3&) true for points of the solid (the test's own
//    implicit function).
#include <gtest/gtest.h>

#include <proxima/core/math.hpp>
#include <proxima/core/result.hpp>
#include <proxima/core/tolerance.hpp>
#include <proxima/core/transform.hpp>
#include <proxima/geometry/aabb.hpp>
#include <proxima/geometry/ray.hpp>
#include <proxima/shapes/mass_properties.hpp>
#include <proxima/shapes/surface_point.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "support/random.hpp"

namespace proxima::test {

/// True for the float build (tolerances of tests are often chosen per precision).
inline constexpr bool kFloat = sizeof(Real) == 4;

/// Precision part of a test tolerance at length scale `scale` (the magnitude of the
/// coordinates involved): `factor` units of Real's epsilon relative to that scale.
inline Real precision_tolerance(Real scale, Real factor = Real(64)) { return factor * kEpsilon * std::abs(scale); }

/// The length scales every sweep runs at: tiny, unit and huge shapes.
///
/// A function, not a namespace-scope array: GCC 12 with -frounding-math (which CGAL adds to
/// every test target) miscompiles namespace-scope float arrays initialised from double
/// literals such as `const float k[] = {float(1e-4)}` (the elements read back as garbage).
inline std::array<Real, 3> scales() { return {Real(1e-4), Real(1), Real(1e4)}; }

/// A NaN of Real (for validation tests; wrap them in ScopedNoFpTraps).
inline Real nan_value() { return std::numeric_limits<Real>::quiet_NaN(); }
/// +infinity of Real.
inline Real inf_value() { return std::numeric_limits<Real>::infinity(); }

/// Largest absolute coordinate.
inline Real max_abs(const Vec3& v) { return std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)}); }

/// Component-wise closeness of two vectors.
inline void expect_vec_near(const Vec3& a, const Vec3& b, Real tol, const std::string& what = "") {
  EXPECT_NEAR(a.x, b.x, tol) << what;
  EXPECT_NEAR(a.y, b.y, tol) << what;
  EXPECT_NEAR(a.z, b.z, tol) << what;
}

/// True when every component of the vector is finite.
inline bool all_finite(const Vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

/// Expects a failed Result with the given code and field.
template <class T>
void expect_error(const Result<T>& r, ErrorCode code, const std::string& field) {
  ASSERT_FALSE(r.ok()) << "expected an error on field " << field;
  EXPECT_EQ(r.error().code, code) << "field " << r.error().field << ": " << r.error().message;
  EXPECT_EQ(r.error().field, field);
  EXPECT_FALSE(r.error().message.empty());
}

/// The four validation failures of a scalar that must be finite and > 0 (NaN, +inf, 0,
/// negative), fed through `make` (a callable Result<T>(Real)) and checked for `field`.
template <class Make>
void expect_positive_field_validated(Make make, const std::string& field) {
  ScopedNoFpTraps no_traps;
  expect_error(make(nan_value()), ErrorCode::NotFinite, field);
  expect_error(make(inf_value()), ErrorCode::NotFinite, field);
  expect_error(make(-inf_value()), ErrorCode::NotFinite, field);
  expect_error(make(Real(0)), ErrorCode::NonPositive, field);
  expect_error(make(Real(-1)), ErrorCode::NonPositive, field);
  expect_error(make(kMaxCoordinate * Real(2)), ErrorCode::OutOfRange, field);
}

/// Non-finite components of a vector field: `make` is a callable Result<T>(Vec3) and
/// `field` the vector's name; each component gets NaN and +-inf in turn, and the error must
/// name "field.x", "field.y" or "field.z". `base` is a valid value.
template <class Make>
void expect_vector_field_finite_validated(Make make, const Vec3& base, const std::string& field) {
  ScopedNoFpTraps no_traps;
  static const char* const kAxis[] = {".x", ".y", ".z"};
  for (int i = 0; i < 3; ++i) {
    for (const Real bad : {nan_value(), inf_value(), -inf_value()}) {
      Vec3 v = base;
      v[i] = bad;
      expect_error(make(v), ErrorCode::NotFinite, field + kAxis[i]);
    }
    Vec3 v = base;
    v[i] = kMaxCoordinate * Real(4);
    expect_error(make(v), ErrorCode::OutOfRange, field + kAxis[i]);
  }
}

/// Calls every query of `shape` with NaN and infinite inputs (points, directions, rays,
/// max_t, poses) with the invalid-operation trap off. Every call must return (no crash, no
/// hang, no sanitizer report). With `defined_answers`, the answers must also follow the
/// shapes' convention for non-finite input: support is finite, contains is false,
/// closest_point gives a finite point and unit normal at distance +infinity, and a ray with
/// a non-finite origin or direction, or a NaN max_t, hits nothing.
template <class S>
void exercise_queries_with_non_finite_input(const S& shape, bool defined_answers = true) {
  ScopedNoFpTraps no_traps;
  const Real nan = nan_value();
  const Real inf = inf_value();
  const Vec3 bad_vectors[] = {Vec3(nan), Vec3(nan, 0, 0), Vec3(0, inf, 0), Vec3(-inf, inf, 0), Vec3(0, 0, -inf)};
  for (const Vec3& v : bad_vectors) {
    const Vec3 s = shape.support(v);
    const Vec3 cs = shape.core_support(v);
    const bool in = shape.contains(v);
    const SurfacePoint sp = shape.closest_point(v);
    const auto from_bad = shape.raycast(Ray{v, Vec3(1, 0, 0)}, Real(10));
    const auto along_bad = shape.raycast(Ray{Vec3(0, 0, 5), v}, Real(10));
    static_cast<void>(shape.world_aabb(Transform{v, kIdentityQuat}));
    if (!defined_answers) continue;
    EXPECT_TRUE(all_finite(s) && all_finite(cs));
    EXPECT_FALSE(in);
    EXPECT_TRUE(all_finite(sp.point) && all_finite(sp.normal));
    EXPECT_NEAR(glm::length(sp.normal), Real(1), Real(64) * kEpsilon);
    EXPECT_EQ(sp.signed_distance, inf);
    EXPECT_FALSE(from_bad.has_value());
    EXPECT_FALSE(along_bad.has_value());
  }
  const auto nan_max_t = shape.raycast(Ray{Vec3(0, 0, 5), Vec3(0, 0, -1)}, nan);
  const auto negative_max_t = shape.raycast(Ray{Vec3(0, 0, 5), Vec3(0, 0, -1)}, -inf);
  static_cast<void>(shape.world_aabb(Transform{Vec3(nan), Quat(nan, 0, 0, 0)}));
  if (defined_answers) {
    EXPECT_FALSE(nan_max_t.has_value());
    EXPECT_FALSE(negative_max_t.has_value());
  }
}

// ---------------------------------------------------------------------------------------
// Surface samplers (unit size; scale and shift them in the test)

/// `n` points of the unit sphere, Fibonacci lattice (nearly uniform).
inline std::vector<Vec3> fibonacci_sphere(int n) {
  std::vector<Vec3> out;
  out.reserve(static_cast<std::size_t>(n));
  const double golden = 3.14159265358979323846 * (3.0 - std::sqrt(5.0));
  for (int i = 0; i < n; ++i) {
    const double z = 1.0 - (2.0 * i + 1.0) / n;
    const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
    const double phi = golden * i;
    out.emplace_back(static_cast<Real>(r * std::cos(phi)), static_cast<Real>(r * std::sin(phi)), static_cast<Real>(z));
  }
  return out;
}

/// Covering radius (bound) of fibonacci_sphere(n) on the unit sphere.
inline Real fibonacci_resolution(int n) { return static_cast<Real>(1.5 * std::sqrt(4.0 * 3.14159265358979 / n)); }

/// Grid samples of the parallelogram origin + u * e0 + v * e1, u, v in [0, 1], with n + 1
/// points per side (covering radius: grid_resolution).
inline void append_parallelogram(std::vector<Vec3>& out, const Vec3& origin, const Vec3& e0, const Vec3& e1, int n) {
  for (int i = 0; i <= n; ++i) {
    for (int j = 0; j <= n; ++j) {
      const Real u = static_cast<Real>(i) / static_cast<Real>(n);
      const Real v = static_cast<Real>(j) / static_cast<Real>(n);
      out.push_back(origin + u * e0 + v * e1);
    }
  }
}

/// Covering radius of append_parallelogram's grid: half the longer cell diagonal.
inline Real grid_resolution(const Vec3& e0, const Vec3& e1, int n) {
  return Real(0.5) * std::max(glm::length(e0 + e1), glm::length(e0 - e1)) / static_cast<Real>(n);
}

/// Samples of the six faces of the box [-h, h] with n cells per face side, and their
/// covering radius in `resolution`.
inline std::vector<Vec3> box_surface_samples(const Vec3& h, int n, Real& resolution) {
  std::vector<Vec3> out;
  resolution = Real(0);
  for (int axis = 0; axis < 3; ++axis) {
    const int j = (axis + 1) % 3;
    const int k = (axis + 2) % 3;
    Vec3 e0(Real(0));
    Vec3 e1(Real(0));
    e0[j] = Real(2) * h[j];
    e1[k] = Real(2) * h[k];
    for (const Real side : {Real(-1), Real(1)}) {
      Vec3 origin = -h;
      origin[axis] = side * h[axis];
      append_parallelogram(out, origin, e0, e1, n);
    }
    resolution = std::max(resolution, grid_resolution(e0, e1, n));
  }
  return out;
}

// ---------------------------------------------------------------------------------------
// Brute-force references over samples

/// max over samples of dot(s, d).
inline Real max_dot(const std::vector<Vec3>& samples, const Vec3& d) {
  Real best = -std::numeric_limits<Real>::max();
  for (const Vec3& s : samples) best = std::max(best, glm::dot(s, d));
  return best;
}

/// Distance from p to the nearest sample (exhaustive search).
inline Real nearest_sample_distance(const std::vector<Vec3>& samples, const Vec3& p) {
  Real best = std::numeric_limits<Real>::max();
  for (const Vec3& s : samples) best = std::min(best, length_squared(s - p));
  return std::sqrt(best);
}

/// Box of the samples after `pose`.
inline Aabb transformed_sample_box(const std::vector<Vec3>& samples, const Transform& pose) {
  Aabb box = Aabb::empty();
  for (const Vec3& s : samples) box.grow(pose.apply(s));
  return box;
}

/// Support check: for `count` random unit directions, dot(support(d), d) must lie in
/// [brute - tol, brute + gap + tol], where brute is the sample maximum and `gap` bounds how
/// far the true maximum can exceed the sample maximum (0 when the samples contain the
/// vertices; resolution^2 / (2 R) on a curved surface of radius R). Also checks that a
/// scaled direction gives the same support value.
template <class S>
void check_support_against_samples(const S& shape, const std::vector<Vec3>& samples, Real gap, Real tol, Random& rng,
                                   int count) {
  for (int i = 0; i < count; ++i) {
    const Vec3 d = rng.unit_vector();
    const Vec3 s = shape.support(d);
    ASSERT_TRUE(all_finite(s));
    const Real got = glm::dot(s, d);
    const Real brute = max_dot(samples, d);
    EXPECT_GE(got, brute - tol) << "direction " << d.x << " " << d.y << " " << d.z;
    EXPECT_LE(got, brute + gap + tol) << "direction " << d.x << " " << d.y << " " << d.z;
    const Real scaled = glm::dot(shape.support(d * Real(1000)), d);
    EXPECT_NEAR(scaled, got, tol);
  }
}

/// World box check: for `count` random poses (positions in [-extent, extent]^3), the
/// shape's world box must contain every transformed sample (within tol) and be tight: each
/// face within `resolution + tol` of the samples' box.
template <class S>
void check_world_aabb_against_samples(const S& shape, const std::vector<Vec3>& samples, Real resolution, Real tol,
                                      Random& rng, int count, Real extent) {
  for (int i = 0; i < count; ++i) {
    const Transform pose = rng.pose(extent);
    const Aabb box = shape.world_aabb(pose);
    const Aabb ref = transformed_sample_box(samples, pose);
    ASSERT_TRUE(box.is_valid());
    for (int a = 0; a < 3; ++a) {
      EXPECT_LE(box.min[a], ref.min[a] + tol) << "pose " << i << " axis " << a;
      EXPECT_GE(box.max[a], ref.max[a] - tol) << "pose " << i << " axis " << a;
      EXPECT_GE(box.min[a], ref.min[a] - resolution - tol) << "not tight: pose " << i << " axis " << a;
      EXPECT_LE(box.max[a], ref.max[a] + resolution + tol) << "not tight: pose " << i << " axis " << a;
    }
  }
}

/// Closest-point check of a solid against surface samples and the test's inside function,
/// for `count` query points drawn uniformly from `region`:
///  - |signed distance| never exceeds the nearest-sample distance (+ tol) and falls short of
///    it by at most resolution (+ tol);
///  - |q - point| == |signed distance|; the point lies on the sampled surface;
///  - the sign agrees with `inside` and with shape.contains (checked away from the surface);
///  - the normal is unit, and for q outside it is (q - point) / distance.
template <class S, class Inside>
void check_closest_point_solid(const S& shape, const std::vector<Vec3>& samples, Real resolution, Real tol,
                               Inside inside, const Aabb& region, Random& rng, int count) {
  const Vec3 lo = region.min;
  const Vec3 hi = region.max;
  for (int i = 0; i < count; ++i) {
    const Vec3 q = rng.in_box(lo, hi);
    const SurfacePoint sp = shape.closest_point(q);
    ASSERT_TRUE(all_finite(sp.point) && all_finite(sp.normal) && std::isfinite(sp.signed_distance));
    const Real brute = nearest_sample_distance(samples, q);
    const Real dist = std::abs(sp.signed_distance);
    EXPECT_LE(dist, brute + tol) << "query " << q.x << " " << q.y << " " << q.z;
    EXPECT_GE(dist, brute - resolution - tol) << "query " << q.x << " " << q.y << " " << q.z;
    EXPECT_NEAR(glm::length(q - sp.point), dist, tol);
    EXPECT_LE(nearest_sample_distance(samples, sp.point), resolution + tol);
    EXPECT_NEAR(glm::length(sp.normal), Real(1), precision_tolerance(Real(1)));
    if (brute > resolution + tol) {
      EXPECT_EQ(shape.contains(q), inside(q)) << "query " << q.x << " " << q.y << " " << q.z;
      if (inside(q)) {
        EXPECT_LT(sp.signed_distance, Real(0)) << "query " << q.x << " " << q.y << " " << q.z;
      } else {
        EXPECT_GT(sp.signed_distance, Real(0)) << "query " << q.x << " " << q.y << " " << q.z;
        expect_vec_near(sp.normal, (q - sp.point) / dist, tol / std::max(dist, tol) + precision_tolerance(Real(1)),
                        "outside normal");
      }
    }
  }
}

/// Reference ray cast by marching: the first t in [0, max_t] where `inside(ray.at(t))`,
/// sampled at `steps` uniform steps and refined by bisection to the precision of Real.
/// nullopt when no sample is inside (a graze thinner than a step is missed).
template <class Inside>
std::optional<Real> march_ray(Inside inside, const Ray& ray, Real max_t, int steps) {
  if (inside(ray.origin)) return Real(0);
  Real prev = Real(0);
  for (int i = 1; i <= steps; ++i) {
    const Real t = max_t * static_cast<Real>(i) / static_cast<Real>(steps);
    if (inside(ray.at(t))) {
      Real lo = prev;
      Real hi = t;
      for (int k = 0; k < 80 && lo < hi; ++k) {
        const Real mid = lo + (hi - lo) * Real(0.5);
        if (mid <= lo || mid >= hi) break;
        if (inside(ray.at(mid))) {
          hi = mid;
        } else {
          lo = mid;
        }
      }
      return hi;
    }
    prev = t;
  }
  return std::nullopt;
}

/// The order of the three coordinate draws of a random point in a box: z first (the sweeps'
/// order, Random::in_box) or x first (the order clang evaluated the former one-call form
/// `Vec3(uniform(x), uniform(y), uniform(z))` in; the named regressions of the cases the
/// sanitizer build drew with it use this order).
enum class DrawOrder { ZFirst, XFirst };

/// A point uniform in the box [lo, hi], its coordinates drawn in `order`.
inline Vec3 draw_in_box(Random& rng, const Vec3& lo, const Vec3& hi, DrawOrder order) {
  if (order == DrawOrder::ZFirst) return rng.in_box(lo, hi);
  const Real x = rng.uniform(lo.x, hi.x);
  const Real y = rng.uniform(lo.y, hi.y);
  const Real z = rng.uniform(lo.z, hi.z);
  return {x, y, z};
}

/// Rays of a ray-cast sweep that hit and that missed (by the march).
struct RaycastCounts {
  int hits = 0;
  int misses = 0;
};

/// Ray-cast check of a solid against march_ray on the test's `inside`: same hit or miss,
/// same t within t_tol (in units of t), the hit point on the surface (|signed distance| of
/// closest_point within tol), a unit normal facing the ray (outward at t > 0). A hit the
/// march misses must be a graze: its point on the surface. Rays: origins in `region`,
/// random directions of length in [0.5, 2] (half of them aimed at the middle 40% of
/// `region`, which should be centred on the shape), max_t in [0, 2 * |region| / speed].
/// `order` is the order of the coordinate draws of a point in the box (DrawOrder); the counts
/// of rays that hit and missed by the march are added to `counts`.
template <class S, class Inside>
void raycast_against_marching(const S& shape, Inside inside, const Aabb& region, Real tol, Random& rng, int count,
                              DrawOrder order, RaycastCounts& counts) {
  const Vec3 lo = region.min;
  const Vec3 hi = region.max;
  const Real span = glm::length(hi - lo);
  int& hits = counts.hits;
  int& misses = counts.misses;
  for (int i = 0; i < count; ++i) {
    const Vec3 o = draw_in_box(rng, lo, hi, order);
    // Aim at a random point near the shape half the time, else a random direction.
    Vec3 dir = rng.unit_vector();
    if (i % 2 == 0) {
      const Vec3 target = draw_in_box(rng, lo, hi, order) * Real(0.4);
      if (glm::length(target - o) > Real(0)) dir = glm::normalize(target - o);
    }
    const Real speed = rng.uniform(Real(0.5), Real(2));
    const Ray ray{o, dir * speed};
    const Real max_t = rng.uniform(Real(0), Real(2) * span / speed);
    const auto hit = shape.raycast(ray, max_t);
    const auto ref = march_ray(inside, ray, max_t, 4000);
    const Real t_tol = tol / speed;
    if (ref) {
      ++hits;
      ASSERT_TRUE(hit.has_value()) << "missed: ray " << i << " ref t " << *ref;
      EXPECT_LE(hit->t, *ref + t_tol) << "ray " << i;
      if (hit->t < *ref - t_tol) {
        // An earlier graze the march stepped over: it must lie on the surface.
        EXPECT_LE(std::abs(shape.closest_point(hit->point).signed_distance), tol) << "ray " << i;
      }
    } else {
      ++misses;
      if (hit) {
        EXPECT_LE(std::abs(shape.closest_point(hit->point).signed_distance), tol) << "graze, ray " << i;
      }
    }
    if (hit) {
      EXPECT_GE(hit->t, Real(0));
      EXPECT_LE(hit->t, max_t);
      expect_vec_near(hit->point, ray.at(hit->t), tol, "hit point");
      EXPECT_NEAR(glm::length(hit->normal), Real(1), precision_tolerance(Real(1), Real(256)));
      if (hit->t == Real(0)) {
        expect_vec_near(hit->normal, -dir, precision_tolerance(Real(1), Real(256)), "inside normal");
      } else {
        EXPECT_LE(glm::dot(hit->normal, dir), precision_tolerance(Real(1), Real(256)));
        EXPECT_LE(std::abs(shape.closest_point(hit->point).signed_distance), tol) << "ray " << i;
      }
    }
  }
}

/// raycast_against_marching on `count` rays drawn in the sweeps' order; the sweep must
/// exercise both outcomes (more than a tenth of the rays each).
template <class S, class Inside>
void check_raycast_solid(const S& shape, Inside inside, const Aabb& region, Real tol, Random& rng, int count) {
  RaycastCounts counts;
  raycast_against_marching(shape, inside, region, tol, rng, count, DrawOrder::ZFirst, counts);
  EXPECT_GT(counts.hits, count / 10);
  EXPECT_GT(counts.misses, count / 10);
}

/// Mass properties integrated on an n^3 midpoint grid over `box` from the implicit
/// `inside` (density 1 scaled by `density`), accumulated in double: volume, mass, centroid
/// and the inertia tensor about the centroid.
template <class Inside>
MassProperties integrate_mass_on_grid(Inside inside, const Aabb& box, int n, Real density) {
  const Vec3 size = box.extents();
  const double cell = static_cast<double>(size.x) * size.y * size.z / (static_cast<double>(n) * n * n);
  double vol = 0.0;
  double m1[3] = {0.0, 0.0, 0.0};
  double m2[3][3] = {{0.0, 0.0, 0.0}, {0.0, 0.0, 0.0}, {0.0, 0.0, 0.0}};
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      for (int k = 0; k < n; ++k) {
        const double x[3] = {box.min.x + (i + 0.5) * size.x / n, box.min.y + (j + 0.5) * size.y / n,
                             box.min.z + (k + 0.5) * size.z / n};
        if (!inside(Vec3(static_cast<Real>(x[0]), static_cast<Real>(x[1]), static_cast<Real>(x[2])))) continue;
        vol += cell;
        for (int a = 0; a < 3; ++a) {
          m1[a] += cell * x[a];
          for (int b = 0; b < 3; ++b) m2[a][b] += cell * x[a] * x[b];
        }
      }
    }
  }
  MassProperties m;
  m.volume = static_cast<Real>(vol);
  m.mass = static_cast<Real>(vol * density);
  if (vol <= 0.0) return m;
  double c[3];
  for (int a = 0; a < 3; ++a) c[a] = m1[a] / vol;
  m.centroid = Vec3(static_cast<Real>(c[0]), static_cast<Real>(c[1]), static_cast<Real>(c[2]));
  // Second moments about the centroid, then I = tr(C) E - C.
  double cov[3][3];
  for (int a = 0; a < 3; ++a) {
    for (int b = 0; b < 3; ++b) cov[a][b] = m2[a][b] - vol * c[a] * c[b];
  }
  const double trace = cov[0][0] + cov[1][1] + cov[2][2];
  for (int a = 0; a < 3; ++a) {
    for (int b = 0; b < 3; ++b) {
      m.inertia[a][b] = static_cast<Real>(density * ((a == b ? trace : 0.0) - cov[a][b]));
    }
  }
  return m;
}

/// Mass properties compared within a relative tolerance `rel` of the largest value (volume,
/// mass, inertia) and `abs_centroid` for the centroid.
inline void expect_mass_near(const MassProperties& got, const MassProperties& ref, Real rel, Real abs_centroid) {
  EXPECT_NEAR(got.volume, ref.volume, rel * std::abs(ref.volume));
  EXPECT_NEAR(got.mass, ref.mass, rel * std::abs(ref.mass));
  expect_vec_near(got.centroid, ref.centroid, abs_centroid, "centroid");
  Real scale = Real(0);
  for (int a = 0; a < 3; ++a) {
    for (int b = 0; b < 3; ++b) scale = std::max(scale, std::abs(ref.inertia[a][b]));
  }
  for (int a = 0; a < 3; ++a) {
    for (int b = 0; b < 3; ++b) {
      EXPECT_NEAR(got.inertia[a][b], ref.inertia[a][b], rel * scale) << "inertia[" << a << "][" << b << "]";
    }
  }
}

}  // namespace proxima::test
