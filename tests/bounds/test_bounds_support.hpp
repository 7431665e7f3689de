#pragma once
// Shared helpers of the bounding-volume tests: random point clouds of many kinds (uniform,
// Gaussian, on a line, on a plane, all equal, 1 and 2 points, tiny/huge scales, far from
// the origin) and tolerance helpers.
#include <proxima/core/math.hpp>
#include <proxima/core/tolerance.hpp>

#include <random>
#include <string>
#include <vector>

#include "support/random.hpp"

namespace proxima::test {

/// Kinds of random clouds the fitters are checked on.
enum class CloudKind { Uniform, Gaussian, Sphere, Line, Plane, Equal, One, Two, Box };

/// Human-readable name of a cloud kind (for failure messages).
inline const char* cloud_name(CloudKind k) {
  switch (k) {
    case CloudKind::Uniform: return "uniform";
    case CloudKind::Gaussian: return "gaussian";
    case CloudKind::Sphere: return "sphere";
    case CloudKind::Line: return "line";
    case CloudKind::Plane: return "plane";
    case CloudKind::Equal: return "equal";
    case CloudKind::One: return "one";
    case CloudKind::Two: return "two";
    case CloudKind::Box: return "box";
  }
  return "?";
}

/// All kinds, for sweeps.
inline constexpr CloudKind kAllCloudKinds[] = {CloudKind::Uniform, CloudKind::Gaussian, CloudKind::Sphere,
                                               CloudKind::Line,    CloudKind::Plane,    CloudKind::Equal,
                                               CloudKind::One,     CloudKind::Two,      CloudKind::Box};

/// A random cloud of `n` points of the given kind, scaled by `scale`, randomly rotated
/// (anisotropically stretched for the volumetric kinds) and moved to `offset`.
inline std::vector<Vec3> make_cloud(Random& rng, CloudKind kind, int n, Real scale, const Vec3& offset) {
  std::vector<Vec3> pts;
  const Quat q = rng.rotation();
  const Real stretch_z = rng.uniform(Real(0.2), Real(1));
  const Real stretch_y = rng.uniform(Real(0.2), Real(1));
  const Real stretch_x = rng.uniform(Real(0.2), Real(1));
  const Vec3 stretch(stretch_x, stretch_y, stretch_z);
  std::normal_distribution<double> gauss(0.0, 1.0);
  const Vec3 dir = rng.unit_vector();
  const Vec3 base = rng.vec3(Real(-1), Real(1));
  Vec3 t1, t2;
  orthonormal_basis(dir, t1, t2);
  switch (kind) {
    case CloudKind::One: n = 1; break;
    case CloudKind::Two: n = 2; break;
    default: break;
  }
  for (int i = 0; i < n; ++i) {
    Vec3 p(Real(0));
    switch (kind) {
      case CloudKind::Uniform: p = q * (rng.vec3(Real(-1), Real(1)) * stretch); break;
      case CloudKind::Gaussian: {
        const Real gz = Real(gauss(rng.engine()));
        const Real gy = Real(gauss(rng.engine()));
        const Real gx = Real(gauss(rng.engine()));
        p = q * (Vec3(gx, gy, gz) * stretch);
        break;
      }
      case CloudKind::Sphere: p = rng.unit_vector(); break;
      case CloudKind::Line: p = base + rng.uniform(Real(-1), Real(1)) * dir; break;
      case CloudKind::Plane: {
        const Real v = rng.uniform(Real(-1), Real(1));
        const Real u = rng.uniform(Real(-1), Real(1));
        p = base + u * t1 + v * t2;
        break;
      }
      case CloudKind::Equal: p = base; break;
      case CloudKind::One:
      case CloudKind::Two: p = rng.vec3(Real(-1), Real(1)); break;
      case CloudKind::Box: {
        // Points on the surface of a rotated box: many coplanar points.
        Vec3 c = rng.vec3(Real(-1), Real(1));
        c[rng.integer(0, 2)] = rng.integer(0, 1) ? Real(1) : Real(-1);
        p = q * (c * stretch);
        break;
      }
    }
    pts.push_back(p * scale + offset);
  }
  return pts;
}

/// One test case of a sweep: a cloud and how it was made.
struct CloudCase {
  std::vector<Vec3> points;  ///< the cloud
  std::string label;         ///< kind, scale and offset, for messages
  Real scale = Real(1);      ///< its scale
  Real magnitude = Real(1);  ///< its largest |coordinate|
};

/// A deterministic sweep of `count` clouds over every kind, sizes 1..max_points, scales
/// 1, 1e-4 and 1e4 and offsets 0 and 1e4 (times the scale or absolute).
inline std::vector<CloudCase> make_cloud_sweep(std::uint64_t seed, int count, int max_points) {
  Random rng(seed);
  std::vector<CloudCase> out;
  constexpr int kinds = static_cast<int>(sizeof(kAllCloudKinds) / sizeof(kAllCloudKinds[0]));
  for (int i = 0; i < count; ++i) {
    const CloudKind kind = kAllCloudKinds[i % kinds];
    const int variant = (i / kinds) % 5;
    Real scale = Real(1);
    Vec3 offset(Real(0));
    switch (variant) {
      case 0: break;
      case 1: scale = Real(1e-4); break;
      case 2: scale = Real(1e4); break;
      case 3: offset = Vec3(Real(1e4), Real(-1e4), Real(0.5e4)); break;
      case 4: offset = rng.vec3(Real(-5), Real(5)); break;
    }
    const int n = rng.integer(1, max_points);
    CloudCase c;
    c.points = make_cloud(rng, kind, n, scale, offset);
    c.scale = scale;
    c.label = std::string(cloud_name(kind)) + " n=" + std::to_string(c.points.size()) +
              " variant=" + std::to_string(variant) + " case=" + std::to_string(i);
    Real m = Real(0);
    for (const Vec3& p : c.points) m = std::max({m, std::abs(p.x), std::abs(p.y), std::abs(p.z)});
    c.magnitude = m;
    out.push_back(std::move(c));
  }
  return out;
}

/// Absolute tolerance for quantities of size `size` computed from coordinates of
/// magnitude `magnitude`: a few hundred ulps of both.
inline Real abs_tol(Real size, Real magnitude) { return Real(64) * kEpsilon * (std::abs(size) + std::abs(magnitude)); }

}  // namespace proxima::test
