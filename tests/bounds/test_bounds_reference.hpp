#pragma once
// Independent references for the overlap and query tests of the bounding volumes, written
// without the library's bounds code:
//  - every volume as "core points + radius" (box corners, k-DOP vertices by brute-force
//    plane-triple enumeration in long double, the hull's input cloud, a capsule's segment,
//    a sphere's centre) and, for polytopes, as half-spaces n . x <= d;
//  - a point-in-volume predicate of its own for each volume;
//  - Frank-Wolfe on the distance between the cores' convex hulls, which yields a certified
//    upper bound (a pair of points of the hulls) and a certified lower bound (a separating
//    direction's gap) at every iteration;
//  - an emptiness test of intersections of half-spaces by vertex enumeration.
#include <proxima/bounds/bounding_capsule.hpp>
#include <proxima/bounds/bounding_sphere.hpp>
#include <proxima/bounds/fit_kdop.hpp>
#include <proxima/bounds/kdop.hpp>
#include <proxima/bounds/obb.hpp>
#include <proxima/geometry/aabb.hpp>
#include <proxima/shapes/convex_hull.hpp>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/vec3.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <variant>
#include <vector>

namespace proxima::test {

using D3 = glm::dvec3;

/// A half-space n . x <= d.
struct HalfSpaceRef {
  D3 n;      ///< outward normal (any length)
  double d;  ///< offset
};

/// Reference description of a bounding volume.
struct VolumeRef {
  std::vector<D3> core;              ///< points whose hull is the core
  double radius = 0.0;               ///< radius around the core
  std::vector<HalfSpaceRef> planes;  ///< half-spaces (polytopes only; empty for round volumes)
  D3 lo{0.0}, hi{0.0};               ///< a box containing the volume
};

/// The 13 k-DOP directions, written independently of the library's table: axes, then
/// corner diagonals, then edge diagonals (Ericson, Real-Time Collision Detection, 4.6).
inline std::vector<D3> kdop_directions_ref(int k) {
  const std::vector<D3> axes{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  const std::vector<D3> corners{{1, 1, 1}, {1, -1, 1}, {1, 1, -1}, {1, -1, -1}};
  const std::vector<D3> edges{{1, 1, 0}, {1, 0, 1}, {0, 1, 1}, {1, -1, 0}, {1, 0, -1}, {0, 1, -1}};
  std::vector<D3> out = axes;
  if (k == 14 || k == 26) out.insert(out.end(), corners.begin(), corners.end());
  if (k == 18 || k == 26) out.insert(out.end(), edges.begin(), edges.end());
  return out;
}

/// Vertices of {x : n_i . x <= d_i + slack} by brute force over plane triples (long double).
inline std::vector<D3> halfspace_vertices(const std::vector<HalfSpaceRef>& h, double slack, bool stop_at_first) {
  using LD = long double;
  std::vector<D3> out;
  const std::size_t n = h.size();
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = i + 1; j < n; ++j) {
      for (std::size_t k = j + 1; k < n; ++k) {
        const D3 a = h[i].n, b = h[j].n, c = h[k].n;
        const LD det = LD(a.x) * (LD(b.y) * c.z - LD(b.z) * c.y) - LD(a.y) * (LD(b.x) * c.z - LD(b.z) * c.x) +
                       LD(a.z) * (LD(b.x) * c.y - LD(b.y) * c.x);
        const LD scale = std::sqrt(LD(glm::dot(a, a)) * glm::dot(b, b) * glm::dot(c, c));
        if (!(std::abs(det) > LD(1e-9) * scale)) continue;
        // Cramer's rule.
        const LD da = h[i].d, db = h[j].d, dc = h[k].d;
        const LD x = (da * (LD(b.y) * c.z - LD(b.z) * c.y) - LD(a.y) * (db * c.z - LD(b.z) * dc) +
                      LD(a.z) * (db * c.y - LD(b.y) * dc)) /
                     det;
        const LD y = (LD(a.x) * (db * c.z - LD(b.z) * dc) - da * (LD(b.x) * c.z - LD(b.z) * c.x) +
                      LD(a.z) * (LD(b.x) * dc - db * c.x)) /
                     det;
        const LD z = (LD(a.x) * (LD(b.y) * dc - db * c.y) - LD(a.y) * (LD(b.x) * dc - db * c.x) +
                      da * (LD(b.x) * c.y - LD(b.y) * c.x)) /
                     det;
        bool ok = true;
        for (const HalfSpaceRef& q : h) {
          if (LD(q.n.x) * x + LD(q.n.y) * y + LD(q.n.z) * z > LD(q.d) + LD(slack) * std::sqrt(LD(glm::dot(q.n, q.n)))) {
            ok = false;
            break;
          }
        }
        if (!ok) continue;
        out.push_back(D3(double(x), double(y), double(z)));
        if (stop_at_first) return out;
      }
    }
  }
  return out;
}

inline VolumeRef ref_of(const Aabb& b) {
  VolumeRef r;
  for (int k = 0; k < 8; ++k)
    r.core.push_back(D3(k & 1 ? b.max.x : b.min.x, k & 2 ? b.max.y : b.min.y, k & 4 ? b.max.z : b.min.z));
  for (int i = 0; i < 3; ++i) {
    D3 n(0.0);
    n[i] = 1.0;
    r.planes.push_back({n, double(b.max[i])});
    r.planes.push_back({-n, -double(b.min[i])});
  }
  r.lo = D3(b.min);
  r.hi = D3(b.max);
  return r;
}

inline VolumeRef ref_of(const BoundingSphere& s) {
  VolumeRef r;
  r.core.push_back(D3(s.center));
  r.radius = double(s.radius);
  r.lo = D3(s.center) - r.radius;
  r.hi = D3(s.center) + r.radius;
  return r;
}

inline VolumeRef ref_of(const Obb& o) {
  VolumeRef r;
  const D3 c(o.center);
  const D3 ax[3] = {D3(o.axes[0]), D3(o.axes[1]), D3(o.axes[2])};
  const D3 h(o.half_extents);
  for (int k = 0; k < 8; ++k) {
    D3 p = c;
    for (int i = 0; i < 3; ++i) p += ((k >> i) & 1 ? h[i] : -h[i]) * ax[i];
    r.core.push_back(p);
  }
  for (int i = 0; i < 3; ++i) {
    r.planes.push_back({ax[i], glm::dot(ax[i], c) + h[i]});
    r.planes.push_back({-ax[i], -glm::dot(ax[i], c) + h[i]});
  }
  r.lo = r.hi = r.core[0];
  for (const D3& p : r.core) {
    r.lo = glm::min(r.lo, p);
    r.hi = glm::max(r.hi, p);
  }
  return r;
}

inline VolumeRef ref_of(const BoundingCapsule& c) {
  VolumeRef r;
  r.core = {D3(c.p0), D3(c.p1)};
  r.radius = double(c.radius);
  r.lo = glm::min(r.core[0], r.core[1]) - r.radius;
  r.hi = glm::max(r.core[0], r.core[1]) + r.radius;
  return r;
}

template <int K>
VolumeRef ref_of(const Kdop<K>& k) {
  VolumeRef r;
  const std::vector<D3> dirs = kdop_directions_ref(K);
  for (int i = 0; i < K / 2; ++i) {
    r.planes.push_back({dirs[static_cast<std::size_t>(i)], double(k.max[i])});
    r.planes.push_back({-dirs[static_cast<std::size_t>(i)], -double(k.min[i])});
  }
  const double slack = 1e-12 * (1.0 + std::abs(double(k.max[0])) + std::abs(double(k.min[0])));
  r.core = halfspace_vertices(r.planes, slack, false);
  r.lo = D3(k.min[0], k.min[1], k.min[2]);
  r.hi = D3(k.max[0], k.max[1], k.max[2]);
  return r;
}

/// A hull given by the cloud it was built from (core) and its faces (planes).
inline VolumeRef ref_of(const ConvexHull& h, const std::vector<Vec3>& cloud) {
  VolumeRef r;
  for (const Vec3& p : cloud) r.core.push_back(D3(p));
  for (const HullFace& f : h.faces()) r.planes.push_back({D3(f.normal), double(f.offset)});
  r.lo = r.hi = r.core[0];
  for (const D3& p : r.core) {
    r.lo = glm::min(r.lo, p);
    r.hi = glm::max(r.hi, p);
  }
  return r;
}

/// Distance bounds between two cores' convex hulls (Frank-Wolfe): lower <= dist <= upper.
struct DistanceBounds {
  double lower = 0.0;
  double upper = 0.0;
};

inline DistanceBounds frank_wolfe_distance(const std::vector<D3>& a, const std::vector<D3>& b, int iterations,
                                           double target_gap) {
  D3 x = a[0], y = b[0];
  DistanceBounds out{0.0, glm::length(x - y)};
  out.lower = -std::numeric_limits<double>::max();
  for (int it = 0; it < iterations; ++it) {
    const D3 v = x - y;
    const double vv = glm::dot(v, v);
    out.upper = std::min(out.upper, std::sqrt(vv));
    if (vv == 0.0) {
      out.lower = std::max(out.lower, 0.0);
      break;
    }
    std::size_t ia = 0, ib = 0;
    for (std::size_t i = 1; i < a.size(); ++i) {
      if (glm::dot(a[i], v) < glm::dot(a[ia], v)) ia = i;
    }
    for (std::size_t i = 1; i < b.size(); ++i) {
      if (glm::dot(b[i], v) > glm::dot(b[ib], v)) ib = i;
    }
    const double len = std::sqrt(vv);
    out.lower = std::max(out.lower, (glm::dot(a[ia], v) - glm::dot(b[ib], v)) / len);
    if (out.upper - std::max(out.lower, 0.0) <= target_gap) break;
    const D3 dx = a[ia] - x, dy = b[ib] - y;
    const D3 d = dx - dy;
    const double dd = glm::dot(d, d);
    if (dd == 0.0) break;
    const double t = std::clamp(-glm::dot(v, d) / dd, 0.0, 1.0);
    x += t * dx;
    y += t * dy;
  }
  out.lower = std::max(out.lower, 0.0);
  return out;
}

/// True when `p` is in the volume grown by `margin` (reference predicate).
inline bool ref_contains(const VolumeRef& v, const D3& p, double margin) {
  if (!v.planes.empty()) {
    for (const HalfSpaceRef& h : v.planes) {
      if (glm::dot(h.n, p) > h.d + margin * glm::length(h.n)) return false;
    }
    return true;
  }
  // Round volumes: the core is a point or a segment.
  double d2;
  if (v.core.size() == 1) {
    d2 = glm::dot(p - v.core[0], p - v.core[0]);
  } else {
    const D3 ab = v.core[1] - v.core[0];
    const double l2 = glm::dot(ab, ab);
    const double t = l2 > 0 ? std::clamp(glm::dot(p - v.core[0], ab) / l2, 0.0, 1.0) : 0.0;
    const D3 q = v.core[0] + t * ab;
    d2 = glm::dot(p - q, p - q);
  }
  const double r = v.radius + margin;
  return r >= 0 && d2 <= r * r;
}

/// The bounding-volume types of the pairwise tests.
enum class VolumeType { Aabb, Sphere, Obb, Capsule, Kdop, Hull };
/// Number of volume types.
inline constexpr int kVolumeTypeCount = 6;
/// Name of a volume type (messages).
inline const char* volume_name(VolumeType t) {
  static const char* const kNames[] = {"aabb", "sphere", "obb", "capsule", "kdop", "hull"};
  return kNames[static_cast<int>(t)];
}

/// Any bounding volume (with the k-DOP size fixed).
template <int K>
using AnyVolume = std::variant<Aabb, BoundingSphere, Obb, BoundingCapsule, Kdop<K>, ConvexHull>;

/// A random volume and its independent reference.
template <int K>
struct TestVolume {
  AnyVolume<K> volume;  ///< the library object
  VolumeRef ref;        ///< its reference description
};

/// A random volume of type `t` of size ~`scale` around a random point of the cube
/// [-spread, spread]^3 * scale, moved by `offset`.
template <int K, class Rng>
TestVolume<K> make_volume(Rng& rng, VolumeType t, Real scale, const Vec3& offset, Real spread = Real(1.5)) {
  const Vec3 c = rng.vec3(-spread, spread) * scale + offset;
  auto size = [&] { return rng.uniform(Real(0.1), Real(1.2)) * scale; };
  TestVolume<K> out;
  switch (t) {
    case VolumeType::Aabb: {
      const Vec3 h(size(), size(), size());
      const Aabb b{c - h, c + h};
      out.volume = b;
      out.ref = ref_of(b);
      break;
    }
    case VolumeType::Sphere: {
      const BoundingSphere s{c, size()};
      out.volume = s;
      out.ref = ref_of(s);
      break;
    }
    case VolumeType::Obb: {
      const Obb o{c, glm::mat3_cast(rng.rotation()), Vec3(size(), size(), size())};
      out.volume = o;
      out.ref = ref_of(o);
      break;
    }
    case VolumeType::Capsule: {
      const Vec3 half = rng.unit_vector() * size();
      const BoundingCapsule cap{c - half, c + half, size() * Real(0.6)};
      out.volume = cap;
      out.ref = ref_of(cap);
      break;
    }
    case VolumeType::Kdop:
    case VolumeType::Hull: {
      std::vector<Vec3> cloud;
      const Quat q = rng.rotation();
      const Vec3 stretch(size(), size(), size());
      const int n = rng.integer(5, 14);
      for (int i = 0; i < n; ++i) cloud.push_back(c + q * (rng.vec3(Real(-1), Real(1)) * stretch));
      if (t == VolumeType::Kdop) {
        const Kdop<K> k = *fit_kdop<K>(cloud);
        out.volume = k;
        out.ref = ref_of(k);
      } else {
        auto h = ConvexHull::create(cloud);
        if (!h) return make_volume<K>(rng, t, scale, offset, spread);
        out.ref = ref_of(*h, cloud);
        out.volume = std::move(*h);
      }
      break;
    }
  }
  return out;
}

}  // namespace proxima::test
