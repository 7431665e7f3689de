// Cone against cone: a closed form for coaxial cones, the generic ladder otherwise.
//
// Steps (coaxial: the axes parallel or opposite within kCoaxialSine, B's centre on A's
// axis within the coordinates' rounding, where the closed form's error is a few units in the
// last place):
//  1. B's centre height c along A's axis, and B's axis direction s = +-1 along A's;
//  2. both cones are solids of revolution about one axis, so their Minkowski difference
//     B - A is one too, and its section by a plane through the axis is the difference of the
//     two sections (a body of revolution's section through its axis is its projection on
//     that plane, and projection commutes with the Minkowski sum): in the (x, z) plane
//     A's triangle (+-R_A, -h_A), (0, h_A) and B's (+-R_B, c - s h_B), (0, c + s h_B). The
//     pair's signed distance is that of the origin from the difference of two triangles;
//  3. the signed distance of two convex sets is the largest separation over directions u,
//     min over B of u.b - max over A of u.a (the overlap along u, negated, when they meet),
//     and every direction's separation bounds it from below. For two polygons the largest
//     is along an edge normal (A's outward, B's inward: the difference's edges; exact when
//     they meet or when an edge is closest) or along a vertex of the difference (b - a,
//     when a vertex is closest): the best of these 15 candidates is the answer, no
//     polygon is built. The normal is the candidate, in A's xz-plane (every azimuth is an
//     answer: A's local +x is taken), never the difference of nearby points;
//  4. witnesses: A's supporting vertex or edge along u and B's along -u, projected on the
//     direction across u; A's point at the middle of the two projections' overlap, B's at
//     A's plus the signed distance along the normal (on B's surface by step 3).
// Manifold: the supporting features along the normal, clipped (supporting_face_manifold.hpp).
// intersect applies the touching rule (contact.hpp) to the coaxial distance.
#include <array>
#include <utility>

#include "narrowphase/closed_form_or_ladder.hpp"
#include "narrowphase/pairs_curved.hpp"
#include "narrowphase/rounded_common.hpp"

namespace proxima::narrow {

namespace {

/// Axes whose sine of angle is within this count as parallel.
const Real kCoaxialSine = Real(4) * kEpsilon;

/// A point or direction in a meridian plane: x across the axis, z along it.
struct MeridianPoint {
  Real x = Real(0);
  Real z = Real(0);
};

Real meridian_dot(const MeridianPoint& u, const MeridianPoint& p) { return u.x * p.x + u.z * p.z; }

/// A cone's section through its axis: base corners (-R, base), (R, base), apex (0, apex).
std::array<MeridianPoint, 3> cone_section(Real radius, Real base, Real apex) {
  return {MeridianPoint{-radius, base}, MeridianPoint{radius, base}, MeridianPoint{Real(0), apex}};
}

/// min over B of u.b - max over A of u.a: the separation of the sections along u.
Real section_separation(const std::array<MeridianPoint, 3>& a, const std::array<MeridianPoint, 3>& b,
                        const MeridianPoint& u) {
  const Real max_a = std::max({meridian_dot(u, a[0]), meridian_dot(u, a[1]), meridian_dot(u, a[2])});
  const Real min_b = std::min({meridian_dot(u, b[0]), meridian_dot(u, b[1]), meridian_dot(u, b[2])});
  return min_b - max_a;
}

/// The unit direction of (x, z), false when it is zero.
bool meridian_unit(Real x, Real z, MeridianPoint& u) {
  const Real len = std::sqrt(x * x + z * z);
  if (!(len > Real(0))) return false;
  u = MeridianPoint{x / len, z / len};
  return true;
}

/// The interval of a section's supporting feature along u (`sign` = +1: the largest u.p,
/// -1: the smallest) projected on t, the direction across u, with the feature's ends:
/// vertices whose u.p is within `noise` of the extreme count as supporting.
struct SectionFeature {
  MeridianPoint p0, p1;  // ends, ordered along t (equal for a vertex)
  Real t0 = Real(0), t1 = Real(0);
};

SectionFeature section_support(const std::array<MeridianPoint, 3>& s, const MeridianPoint& u, Real sign, Real noise) {
  const MeridianPoint t{u.z, -u.x};
  Real best = -kRealInfinity;
  for (const MeridianPoint& p : s) best = std::max(best, sign * meridian_dot(u, p));
  SectionFeature f;
  bool first = true;
  for (const MeridianPoint& p : s) {
    if (!(sign * meridian_dot(u, p) >= best - noise)) continue;
    const Real tp = meridian_dot(t, p);
    if (first || tp < f.t0) {
      f.p0 = p;
      f.t0 = tp;
    }
    if (first || tp > f.t1) {
      f.p1 = p;
      f.t1 = tp;
    }
    first = false;
  }
  return f;
}

/// The point of feature f at projection `at` across u (clamped to the feature).
MeridianPoint section_point_at(const SectionFeature& f, Real at) {
  if (!(f.t1 > f.t0)) return f.p0;
  const Real lambda = std::clamp((at - f.t0) / (f.t1 - f.t0), Real(0), Real(1));
  return MeridianPoint{f.p0.x + lambda * (f.p1.x - f.p0.x), f.p0.z + lambda * (f.p1.z - f.p0.z)};
}

/// The closed form of two coaxial cones (steps 1-4), false when they are not coaxial.
bool coaxial_cones(const Cone& a, const Transform& pose_a, const Cone& b, const Transform& pose_b,
                   const PairRequest& request, DistanceResult& r) {
  // B's axis in A's frame through the relative rotation (as for parallel cylinders).
  const Vec3 axis_b = (glm::conjugate(pose_a.rotation) * pose_b.rotation) * Vec3(Real(0), Real(0), Real(1));
  if (!(std::sqrt(axis_b.x * axis_b.x + axis_b.y * axis_b.y) <= kCoaxialSine)) return false;
  const Real ra = a.radius();
  const Real rb = b.radius();
  const Real ha = a.half_length();
  const Real hb = b.half_length();
  const Real scale = detail::pair_scale(pose_a, pose_b, std::max({ra, rb, ha, hb}));
  const Vec3 c = pose_a.inverse_apply(pose_b.position);
  if (!(std::sqrt(c.x * c.x + c.y * c.y) <= detail::offset_noise(scale))) return false;
  const Real s = axis_b.z >= Real(0) ? Real(1) : Real(-1);
  const std::array<MeridianPoint, 3> sa = cone_section(ra, -ha, ha);
  const std::array<MeridianPoint, 3> sb = cone_section(rb, c.z - s * hb, c.z + s * hb);
  // Candidates: A's outward edge normals, B's inward ones, the difference's vertices.
  std::array<MeridianPoint, 15> candidates;
  std::size_t count = 0;
  for (const auto& [x, z] :
       {std::pair{Real(0), Real(-1)}, std::pair{Real(2) * ha, ra}, std::pair{-Real(2) * ha, ra}, std::pair{Real(0), s},
        std::pair{-Real(2) * hb, -s * rb}, std::pair{Real(2) * hb, -s * rb}}) {
    if (meridian_unit(x, z, candidates[count])) ++count;
  }
  for (const MeridianPoint& q : sb) {
    for (const MeridianPoint& p : sa) {
      if (meridian_unit(q.x - p.x, q.z - p.z, candidates[count])) ++count;
    }
  }
  MeridianPoint u = candidates[0];
  Real sd = section_separation(sa, sb, u);
  for (std::size_t k = 1; k < count; ++k) {
    const Real gap = section_separation(sa, sb, candidates[k]);
    if (gap > sd) {
      sd = gap;
      u = candidates[k];
    }
  }
  // Witnesses: the middle of the supporting features' overlap across u.
  const Real noise = detail::offset_noise(scale);
  const SectionFeature fa = section_support(sa, u, Real(1), noise);
  const SectionFeature fb = section_support(sb, u, Real(-1), noise);
  const MeridianPoint on_a = section_point_at(fa, Real(0.5) * (std::max(fa.t0, fb.t0) + std::min(fa.t1, fb.t1)));
  r = detail::analytic_answer(pose_a, sd, Vec3(u.x, Real(0), u.z), Vec3(on_a.x, Real(0), on_a.z), request, scale);
  return true;
}

}  // namespace

PROXIMA_CLOSED_FORM_OR_LADDER(Cone, coaxial_cones)

}  // namespace proxima::narrow
