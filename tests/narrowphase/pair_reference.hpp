#pragma once
// Long double references for the narrow-phase pair tests: support functions of every shape
// written from their definitions (not the library's support code), the overlap of two placed
// shapes along a direction, its minimum over directions (the penetration depth, or minus the
// distance) by dense Fibonacci sampling refined by a pattern search or, near a given
// direction, by Newton's method on the sphere, and core distances of
// points and segments to segments, boxes and triangles by nested golden-section searches.
#include <proxima/core/transform.hpp>
#include <proxima/narrowphase/contact.hpp>
#include <proxima/shapes/shape.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <type_traits>
#include <variant>
#include <vector>

#include "geometry/long_double_reference.hpp"

namespace proxima::test {

// Rotation matrix of q in long double (rows: r[i] is the i-th row).
struct LRot {
  LVec r[3];
  LVec apply(const LVec& v) const { return {glm::dot(r[0], v), glm::dot(r[1], v), glm::dot(r[2], v)}; }
  LVec apply_t(const LVec& v) const { return r[0] * v.x + r[1] * v.y + r[2] * v.z; }
};

inline LRot ld_rotation(const Quat& qr) {
  const LD w = qr.w, x = qr.x, y = qr.y, z = qr.z;
  const LD n = std::sqrt(w * w + x * x + y * y + z * z);
  const LD a = w / n, b = x / n, c = y / n, d = z / n;
  LRot m;
  m.r[0] = LVec(1 - 2 * (c * c + d * d), 2 * (b * c - a * d), 2 * (b * d + a * c));
  m.r[1] = LVec(2 * (b * c + a * d), 1 - 2 * (b * b + d * d), 2 * (c * d - a * b));
  m.r[2] = LVec(2 * (b * d - a * c), 2 * (c * d + a * b), 1 - 2 * (b * b + c * c));
  return m;
}

// A placed frame in long double: world = R local + p.
struct LPose {
  LRot rot;
  LVec p;
  explicit LPose(const Transform& t) : rot(ld_rotation(t.rotation)), p(ld(t.position)) {}
  LVec to_world(const Vec3& l) const { return rot.apply(ld(l)) + p; }
  LVec to_local(const LVec& w) const { return rot.apply_t(w - p); }
  LVec dir_local(const LVec& w) const { return rot.apply_t(w); }
};

inline LD lnorm(const LVec& v) { return std::sqrt(glm::dot(v, v)); }
inline LD radial(const LVec& u) { return std::sqrt(u.x * u.x + u.y * u.y); }

// Local support functions h(u) = max over the shape of u . x.
inline LD support_local(const Point&, const LVec&) { return 0; }
inline LD support_local(const Segment& s, const LVec& u) {
  return std::max(glm::dot(u, ld(s.a())), glm::dot(u, ld(s.b())));
}
inline LD support_local(const Triangle& t, const LVec& u) {
  return std::max({glm::dot(u, ld(t.a())), glm::dot(u, ld(t.b())), glm::dot(u, ld(t.c()))});
}
inline LD support_local(const Sphere& s, const LVec& u) { return LD(s.radius()) * lnorm(u); }
inline LD support_local(const Capsule& c, const LVec& u) {
  return LD(c.half_length()) * std::abs(u.z) + LD(c.radius()) * lnorm(u);
}
inline LD support_local(const Box& b, const LVec& u) {
  const Vec3& h = b.half_extents();
  return LD(h.x) * std::abs(u.x) + LD(h.y) * std::abs(u.y) + LD(h.z) * std::abs(u.z);
}
inline LD support_local(const Cylinder& c, const LVec& u) {
  return LD(c.half_length()) * std::abs(u.z) + LD(c.radius()) * radial(u);
}
inline LD support_local(const Cone& c, const LVec& u) {
  const LD h = c.half_length();
  return std::max(h * u.z, -h * u.z + LD(c.radius()) * radial(u));
}
inline LD support_local(const Ellipsoid& e, const LVec& u) {
  const Vec3& r = e.radii();
  const LVec s(LD(r.x) * u.x, LD(r.y) * u.y, LD(r.z) * u.z);
  return lnorm(s);
}
inline LD support_local(const ConvexHull& h, const LVec& u) {
  LD best = -std::numeric_limits<LD>::infinity();
  for (const Vec3& v : h.vertices()) best = std::max(best, glm::dot(u, ld(v)));
  return best;
}

template <class S>
LD support_world(const S& s, const Transform& pose, const LVec& u) {
  const LPose p(pose);
  return support_local(s, p.dir_local(u)) + glm::dot(u, p.p);
}

// Overlap of the projections of A and B along unit n (A to B): h_A(n) + h_B(-n). Positive:
// the depth along n; negative: minus the gap along n.
template <class A, class B>
LD overlap_along(const A& a, const Transform& pa, const B& b, const Transform& pb, const LVec& n) {
  return support_world(a, pa, n) + support_world(b, pb, -n);
}

// Minimum over unit directions of overlap_along: the penetration depth (> 0), or minus the
// distance (< 0). Fibonacci sampling of `samples` directions, then a pattern search from the
// best few. Never below the true minimum.
template <class A, class B>
LD min_overlap(const A& a, const Transform& pa, const B& b, const Transform& pb, int samples = 600) {
  const auto f = [&](const LVec& u) { return overlap_along(a, pa, b, pb, u / lnorm(u)); };
  std::vector<std::pair<LD, LVec>> best;
  const LD golden = LD(3.14159265358979323846L) * (LD(3) - std::sqrt(LD(5)));
  for (int i = 0; i < samples; ++i) {
    const LD z = LD(1) - (LD(2) * i + 1) / LD(samples);
    const LD r = std::sqrt(std::max(LD(0), LD(1) - z * z));
    const LVec u(r * std::cos(golden * i), r * std::sin(golden * i), z);
    best.emplace_back(f(u), u);
  }
  std::partial_sort(best.begin(), best.begin() + 4, best.end(),
                    [](const auto& x, const auto& y) { return x.first < y.first; });
  LD result = best[0].first;
  for (int k = 0; k < 4; ++k) {
    LVec u = best[static_cast<std::size_t>(k)].second;
    LD fu = best[static_cast<std::size_t>(k)].first;
    for (LD step = 0.1L; step > 1e-12L; step *= 0.5L) {
      for (int rep = 0; rep < 30; ++rep) {
        const LVec t1 =
            lnorm(glm::cross(u, LVec(1, 0, 0))) > 0.5L ? glm::cross(u, LVec(1, 0, 0)) : glm::cross(u, LVec(0, 1, 0));
        const LVec e1 = t1 / lnorm(t1);
        const LVec e2 = glm::cross(u, e1);
        bool moved = false;
        for (int dir = 0; dir < 8; ++dir) {
          const LD ang = LD(dir) * LD(3.14159265358979323846L) / LD(4);
          LVec v = u + step * (std::cos(ang) * e1 + std::sin(ang) * e2);
          v /= lnorm(v);
          const LD fv = f(v);
          if (fv < fu) {
            fu = fv;
            u = v;
            moved = true;
          }
        }
        if (!moved) break;
      }
    }
    result = std::min(result, fu);
  }
  return result;
}

// overlap_along for two convex shapes held in Shapes (half-spaces, meshes and compounds have
// no bounded support: NaN). The offset between the poses enters as one exact difference, so
// that shapes far from the origin keep the precision of their size: n . (p_A - p_B) plus the
// local supports.
inline LD overlap_along_shapes(const Shape& a, const Transform& pa, const Shape& b, const Transform& pb,
                               const LVec& n) {
  const auto local_support = [](const Shape& s, const Transform& pose, const LVec& u) {
    return std::visit(
        [&](const auto& shape) -> LD {
          using S = std::decay_t<decltype(shape)>;
          if constexpr (std::is_same_v<S, HalfSpace> || std::is_same_v<S, TriangleMesh> || std::is_same_v<S, Compound>)
            return std::numeric_limits<LD>::quiet_NaN();
          else
            return support_local(shape, LPose(pose).dir_local(u));
        },
        s);
  };
  return local_support(a, pa, n) + local_support(b, pb, -n) + glm::dot(n, ld(pa.position) - ld(pb.position));
}

// A local minimum of a function f of unit directions (the overlap along them), by Newton's
// method on the sphere in long double with central differences (gradient by the five-point
// stencil over 1e-6 rad, Hessian over 1e-4 rad). The gradient's stencil is of fourth order:
// the plain central difference's truncation, f''' d^2 / 6, was 8e-7 on a cone's rim seen
// nearly edge-on (f''' about 5e6 on a pair of size 2e3 whose curvatures are 3e4 and 600),
// which put the reference's minimum 1.8e-9 rad off, where f along the great circle through
// both is symmetric about the library's normal. `smooth`: the Hessian over 1e-3 rad agrees
// within 1 % (no crease of f within reach, where differences measure the crease, not a
// curvature); `curvature`: the Hessian's least eigenvalue there (how well the minimum pins
// the direction).
struct DirectionMinimum {
  LVec normal;       // unit
  LD value = 0;      // f there
  LD curvature = 0;  // least eigenvalue of f's Hessian on the sphere
  bool smooth = false;
  bool converged = false;
};

template <class F>
DirectionMinimum minimize_over_directions(F f, LVec n, LD scale) {
  DirectionMinimum r;
  n /= lnorm(n);
  for (int it = 0; it < 40; ++it) {
    const LVec t1 = glm::cross(n, std::abs(n.x) < 0.6L ? LVec(1, 0, 0) : LVec(0, 1, 0)) /
                    lnorm(glm::cross(n, std::abs(n.x) < 0.6L ? LVec(1, 0, 0) : LVec(0, 1, 0)));
    const LVec t2 = glm::cross(n, t1);
    const auto at = [&](LD u, LD v) {
      const LVec m = n + u * t1 + v * t2;
      return f(m / lnorm(m));
    };
    const LD d = 1e-6L, e = 1e-4L, w = 1e-3L;
    const LD f0 = at(0, 0);
    const LD g1 = (8 * (at(d, 0) - at(-d, 0)) - (at(2 * d, 0) - at(-2 * d, 0))) / (12 * d);
    const LD g2 = (8 * (at(0, d) - at(0, -d)) - (at(0, 2 * d) - at(0, -2 * d))) / (12 * d);
    const LD h11 = (at(e, 0) - 2 * f0 + at(-e, 0)) / (e * e);
    const LD h22 = (at(0, e) - 2 * f0 + at(0, -e)) / (e * e);
    const LD h12 = (at(e, e) - at(e, -e) - at(-e, e) + at(-e, -e)) / (4 * e * e);
    const LD k11 = (at(w, 0) - 2 * f0 + at(-w, 0)) / (w * w);
    const LD k22 = (at(0, w) - 2 * f0 + at(0, -w)) / (w * w);
    const LD floor = 1e-3L * scale;
    r.smooth = std::abs(k11 - h11) <= 1e-2L * (std::abs(h11) + floor) &&
               std::abs(k22 - h22) <= 1e-2L * (std::abs(h22) + floor);
    const LD tr = 0.5L * (h11 + h22);
    const LD disc = std::sqrt(0.25L * (h11 - h22) * (h11 - h22) + h12 * h12);
    r.curvature = tr - disc;
    r.normal = n;
    r.value = f0;
    const LD det = h11 * h22 - h12 * h12;
    const LD grad = std::sqrt(g1 * g1 + g2 * g2);
    if (!(r.curvature > 0) || !(det > 0)) return r;
    LD s1 = -(h22 * g1 - h12 * g2) / det;
    LD s2 = -(h11 * g2 - h12 * g1) / det;
    const LD len = std::sqrt(s1 * s1 + s2 * s2);
    if (len > 0.1L) s1 *= 0.1L / len, s2 *= 0.1L / len;
    const LVec m = (n + s1 * t1 + s2 * t2) / lnorm(n + s1 * t1 + s2 * t2);
    if (f(m) > f0 + 1e-17L * scale) {
      r.converged = grad < 1e-13L * scale;
      return r;
    }
    n = m;
    if (len < 1e-15L) {
      r.converged = true;
      r.normal = n;
      r.value = f(n);
      return r;
    }
  }
  return r;
}

// Squared distance of point p to the solid box [-h, h].
inline LD ref_dist2_point_box(const LVec& p, const Vec3& h) {
  const LVec q(std::clamp(p.x, -LD(h.x), LD(h.x)), std::clamp(p.y, -LD(h.y), LD(h.y)),
               std::clamp(p.z, -LD(h.z), LD(h.z)));
  return dist2(p, q);
}

// min over s in [0, 1] of f(p0 + s (p1 - p0)), f convex along the segment (squared distances
// to convex sets are).
template <class F>
LD min_along_segment(const LVec& p0, const LVec& p1, F f) {
  return golden_min([&](LD s) { return f(p0 + s * (p1 - p0)); }, LD(0), LD(1), 160);
}

// Squared distance of segments p0p1 and q0q1.
inline LD ref_dist2_segment_segment(const LVec& p0, const LVec& p1, const LVec& q0, const LVec& q1) {
  return min_along_segment(p0, p1, [&](const LVec& x) { return ref_dist2_point_segment(x, q0, q1); });
}

// Core segment of a capsule in world (long double).
inline void capsule_core(const Capsule& c, const Transform& t, LVec& p0, LVec& p1) {
  const LPose p(t);
  p0 = p.to_world(c.bottom());
  p1 = p.to_world(c.top());
}

}  // namespace proxima::test
