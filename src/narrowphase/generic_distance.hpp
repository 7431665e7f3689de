#pragma once
/// @file generic_distance.hpp
/// The generic narrow phase for any pair of convex shapes without a closed-form routine:
///   1. B's pose relative to A; B's core support mapped into A's local frame once;
///   2. GJK (plain or Nesterov, PairRequest::gjk) between the cores, warm-started from the
///      PairCache (axis in A's frame, hull support hints); the radii are added after:
///      distance = |v| - r_A - r_B, witnesses moved by the radii along the normal;
///   3. cores overlapping (or touching within rounding): EPA from GJK's simplex for depth
///      and normal; when EPA reports Degenerate, the SAT for polytope pairs, else GJK's own
///      core contact (depth r_A + r_B along the best axis known), status Degenerate;
///   4. tolerance from resolve_tolerance (size of the pair), outputs in the world frame,
///      cache written back.
/// pair_intersect runs GJK in boolean mode with early exit on a separating axis.

#include <proxima/core/tolerance.hpp>
#include <proxima/geometry/epa.hpp>
#include <proxima/geometry/epa_refine.hpp>
#include <proxima/geometry/gjk.hpp>
#include <proxima/shapes/halfspace.hpp>

#include <algorithm>
#include <cmath>
#include <type_traits>

#include "pair_support.hpp"
#include "polytope_sat.hpp"
#include "support_binding.hpp"

namespace proxima::narrow {

namespace generic_detail {

/// Largest extent of a shape's local box (its size for tolerances).
template <class S>
Real shape_size(const S& s) {
  const Aabb box = s.local_aabb();
  const Vec3 e = box.max - box.min;
  const Real m = std::max({std::abs(box.max.x), std::abs(box.max.y), std::abs(box.max.z), std::abs(box.min.x),
                           std::abs(box.min.y), std::abs(box.min.z)});
  return std::max({e.x, e.y, e.z, m});
}

inline Real max_abs3(const Vec3& v) { return std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)}); }

/// Everything a generic query needs, in A's local frame.
template <class A, class B>
struct PairSetup {
  CoreSupport<A> support_a;
  MappedSupport<CoreSupport<B>> support_b;
  Vec3 translation{Real(0)};  ///< B's origin in A's frame
  Real radius_a = Real(0);
  Real radius_b = Real(0);
  Real scale = Real(1);      ///< size of the pair in A's frame: shapes and B's offset (length)
  Real tolerance = Real(0);  ///< resolved absolute tolerance (world scale: positions included)
  Vec3 axis{Real(0)};        ///< initial direction A to B (A's frame)

  PairSetup(const A& a, const Transform& pose_a, const B& b, const Transform& pose_b, const PairRequest& request,
            const PairCache* cache)
      : support_a(bind_core_support(a, cache && cache->valid ? cache->support_hint_a : 0u)),
        support_b{bind_core_support(b, cache && cache->valid ? cache->support_hint_b : 0u), Mat3(Real(1)),
                  Mat3(Real(1)), Vec3(Real(0))} {
    const Transform rel = relative(pose_a, pose_b);
    support_b.rotation = glm::mat3_cast(rel.rotation);
    support_b.rotation_t = glm::transpose(support_b.rotation);
    support_b.translation = rel.position;
    translation = rel.position;
    radius_a = a.core_radius();
    radius_b = b.core_radius();
    // The solve runs in A's frame, where only the shapes and B's offset set the size; far
    // from the origin the world coordinates add rounding to the answer's status only.
    scale = std::max({shape_size(a), shape_size(b), max_abs3(translation)});
    tolerance = resolve_tolerance(request, std::max({scale, max_abs3(pose_a.position), max_abs3(pose_b.position)}));
    axis = cache && cache->valid ? cache->axis : translation;
  }

  gjk::Settings gjk_settings(const PairRequest& request) const {
    gjk::Settings s;
    s.max_iterations = std::max(request.max_iterations, 1);
    s.abs_tolerance = Real(0.01) * tolerance;
    s.variant = request.gjk;
    return s;
  }

  void store(PairCache* cache, const Vec3& normal_local) const {
    if (!cache) return;
    cache->axis = normal_local;
    cache->support_hint_a = support_a.hint();
    cache->support_hint_b = support_b.hint();
    cache->valid = true;
  }
};

/// A's-frame answer before the move to the world frame.
struct LocalAnswer {
  Real signed_distance = Real(0);
  Vec3 point_a{Real(0)};
  Vec3 point_b{Real(0)};
  Vec3 normal{Real(0), Real(0), Real(1)};
  PairStatus status = PairStatus::Separated;
  PairMethod method = PairMethod::Gjk;
  int iterations = 0;
  std::uint32_t sat_feature = 0;
  bool sat_used = false;
};

inline Vec3 unit_or(const Vec3& v, const Vec3& fallback) {
  const Real l2 = glm::dot(v, v);
  if (l2 > Real(0) && std::isfinite(l2)) return v / std::sqrt(l2);
  const Real f2 = glm::dot(fallback, fallback);
  if (f2 > Real(0) && std::isfinite(f2)) return fallback / std::sqrt(f2);
  return Vec3(Real(0), Real(0), Real(1));
}

template <class A, class B>
LocalAnswer solve(const A& a, const B& b, PairSetup<A, B>& setup, const PairRequest& request) {
  LocalAnswer ans;
  const gjk::Outcome g = gjk::distance(setup.support_a, setup.support_b, setup.axis, setup.gjk_settings(request));
  ans.iterations = g.iterations;
  const Real radii = setup.radius_a + setup.radius_b;
  const Real core_contact = Real(16) * kEpsilon * setup.scale;
  if constexpr (kIsPolytope<A> && kIsPolytope<B>) {
    // GJK stopped by the cap on a polytope pair: the SAT decides overlap exactly.
    if (g.status == gjk::Status::MaxIterations) {
      const PolytopeView va(a);
      const PolytopeView vb(b);
      const SatResult s = polytope_sat(va, vb, setup.support_b.rotation, setup.support_b.translation);
      if (s.valid && s.signed_distance < Real(0)) {
        ans.normal = s.normal;
        ans.signed_distance = s.signed_distance - radii;
        ans.point_a = s.point_a;
        ans.point_b = s.point_b;
        ans.method = PairMethod::Sat;
        ans.status = status_from_distance(ans.signed_distance, setup.tolerance);
        ans.sat_feature = s.feature;
        ans.sat_used = true;
        return ans;
      }
    }
  }
  if (g.status != gjk::Status::Overlapping && g.distance > core_contact) {
    const Vec3 n = -g.v / g.distance;
    ans.normal = n;
    ans.signed_distance = g.distance - radii;
    ans.point_a = g.point_a + setup.radius_a * n;
    ans.point_b = g.point_b - setup.radius_b * n;
    ans.method = PairMethod::Gjk;
    ans.status = g.status == gjk::Status::MaxIterations ? PairStatus::MaxIterations
                                                        : status_from_distance(ans.signed_distance, setup.tolerance);
    return ans;
  }
  // Cores overlap or touch: EPA. When GJK did not enclose the origin (the cores only touch,
  // within rounding), EPA runs on cores inflated by a small ball, whose Minkowski
  // difference holds the origin robustly; the depth is then exactly 2 delta larger.
  epa::Settings es;
  es.max_iterations = std::max(request.max_iterations, 1);
  es.max_faces = request.max_epa_faces;
  // Curved shapes converge slowly: a relative 1e-9 of the pair's size is enough in double.
  es.abs_tolerance = std::max(Real(0.1) * setup.tolerance, Real(1e-9) * setup.scale);
  const bool touching = g.simplex.size < 4;
  const bool polytopes = kIsPolytope<A> && kIsPolytope<B>;
  // EPA converges only linearly on curved supports: unless its gap is already within
  // rounding, Newton steps on the support function of D take its normal to the minimum.
  // The refined support distance is an upper bound of the depth; the witnesses are support
  // points (combined across an edge or face of D) with point_a - point_b = depth * normal.
  const auto polish = [&](epa::Outcome& ep, auto& sa, auto& sb, bool curved) {
    if (!curved || ep.status == epa::Status::Degenerate) return;
    const Real target = Real(64) * kEpsilon * setup.scale;
    if (ep.status == epa::Status::Converged && ep.gap <= target) return;
    // From the normal of EPA's least upper bound (its nearest face's normal may be worse).
    const epa::Refinement f =
        epa::refine(sa, sb, ep.upper_normal, setup.scale, std::clamp(request.max_iterations, 1, 96));
    ep.iterations += f.iterations;
    // Unconverged, EPA's own answer stands (at its cap: the nearest face, a lower bound).
    if (!f.converged || !(f.depth <= ep.depth + ep.gap + kSqrtEpsilon * setup.scale)) return;
    // A converged EPA keeps its own answer where the refined witnesses could not be placed
    // on both surfaces (an edge of D meeting a curved side off the tipped supports' reach).
    if (ep.status == epa::Status::Converged && f.witness_gap > kSqrtEpsilon * setup.scale) return;
    ep.status = epa::Status::Converged;
    ep.gap = std::max(f.depth - ep.depth, Real(0));
    ep.depth = f.depth;
    ep.normal = f.normal;
    ep.point_a = f.support_a;
    ep.point_b = f.support_b;
  };
  const auto inflated_epa = [&]() {
    const Real delta = std::max(Real(1024) * kEpsilon * setup.scale, setup.tolerance);
    InflatedSupport<decltype(setup.support_a)> ia{setup.support_a, delta};
    InflatedSupport<decltype(setup.support_b)> ib{setup.support_b, delta};
    const gjk::Outcome gi = gjk::distance(ia, ib, setup.axis, setup.gjk_settings(request));
    ans.iterations += gi.iterations;
    epa::Outcome ei = epa::penetration(ia, ib, gi.simplex, setup.scale, es);
    // Inflated cores are curved; for polytopes only when the cores merely touch (deeper
    // polytope pairs have the exact SAT fall-back, while a refinement stops at a local
    // minimum of a starved EPA's normal).
    polish(ei, ia, ib, !polytopes || touching);
    if (ei.status != epa::Status::Degenerate) {
      ei.depth -= Real(2) * delta;
      ei.point_a -= delta * ei.normal;
      ei.point_b += delta * ei.normal;
    }
    return ei;
  };
  epa::Outcome e;
  if (touching) {
    e = inflated_epa();
  } else {
    e = epa::penetration(setup.support_a, setup.support_b, g.simplex, setup.scale, es);
    polish(e, setup.support_a, setup.support_b, !polytopes);
    if (e.status == epa::Status::MaxIterations) {
      // Rounding stopped the expansion early: a second polytope, grown on the slightly
      // inflated cores, meets other slivers; keep the answer with the smaller error bound.
      ans.iterations += e.iterations;
      const epa::Outcome e2 = inflated_epa();
      if (e2.status != epa::Status::Degenerate && e2.gap < e.gap) e = e2;
    }
  }
  ans.iterations += e.iterations;
  if (e.status == epa::Status::Converged || (e.status == epa::Status::MaxIterations && !polytopes)) {
    ans.normal = e.normal;
    ans.signed_distance = -(e.depth + radii);  // e.depth may be slightly negative when touching
    ans.point_a = e.point_a + setup.radius_a * e.normal;
    ans.point_b = e.point_b - setup.radius_b * e.normal;
    ans.method = PairMethod::Epa;
    ans.status = e.status == epa::Status::MaxIterations ? PairStatus::MaxIterations
                                                        : status_from_distance(ans.signed_distance, setup.tolerance);
    return ans;
  }
  if constexpr (kIsPolytope<A> && kIsPolytope<B>) {
    const PolytopeView va(a);
    const PolytopeView vb(b);
    const SatResult s = polytope_sat(va, vb, setup.support_b.rotation, setup.support_b.translation);
    if (s.valid) {
      ans.normal = s.normal;
      ans.signed_distance = s.signed_distance - radii;
      // Touching cores: GJK's witnesses are exact points of both; else the SAT's features.
      const Vec3 core_a = touching ? g.point_a : s.point_a;
      ans.point_a = core_a + setup.radius_a * s.normal;
      ans.point_b = ans.point_a + ans.signed_distance * s.normal;
      ans.method = PairMethod::Sat;
      ans.status = e.status == epa::Status::Degenerate ? PairStatus::Degenerate
                                                       : status_from_distance(ans.signed_distance, setup.tolerance);
      ans.sat_feature = s.feature;
      ans.sat_used = true;
      return ans;
    }
  } else {
    (void)a;
    (void)b;
  }
  // GJK's core contact: the cores touch (distance ~0) and D = core A - core B, holding the
  // origin, is too thin for EPA (a point against a segment, coincident segments). The depth
  // is radii plus min over n of D's support distance, 0 along D's normals at the origin:
  // descend the support function from GJK's last direction to such a normal.
  Vec3 n = unit_or(-g.v, setup.axis);
  {
    const epa::Refinement f =
        epa::refine(setup.support_a, setup.support_b, n, setup.scale, std::clamp(request.max_iterations, 1, 96));
    ans.iterations += f.iterations;
    // Its support distance is an upper bound of the core depth (0 in exact arithmetic).
    const Real reach = std::max(setup.tolerance, kSqrtEpsilon * setup.scale);
    if (f.depth <= reach && f.witness_gap <= reach) {
      n = f.normal;
      ans.normal = n;
      ans.signed_distance = -std::max(f.depth, Real(0)) - radii;
      ans.point_a = f.support_a + setup.radius_a * n;
      ans.point_b = ans.point_a + ans.signed_distance * n;
      ans.method = PairMethod::Epa;
      ans.status = status_from_distance(ans.signed_distance, setup.tolerance);
      return ans;
    }
  }
  ans.normal = n;
  ans.signed_distance = g.distance - radii;
  ans.point_a = g.point_a + setup.radius_a * n;
  ans.point_b = ans.point_a + ans.signed_distance * n;  // keeps the witness relation exact
  ans.method = PairMethod::Gjk;
  ans.status = PairStatus::Degenerate;
  return ans;
}

}  // namespace generic_detail

/// Signed distance of any convex pair by GJK / EPA / SAT (see the file comment). A and B in
/// their local frames with world poses; results in the world frame (contact.hpp). Callable on
/// pairs that also have a closed-form routine (tests compare the two).
template <class A, class B>
DistanceResult generic_distance(const A& a, const Transform& pose_a, const B& b, const Transform& pose_b,
                                const PairRequest& request, PairCache* cache) {
  static_assert(!std::is_same_v<A, HalfSpace> && !std::is_same_v<B, HalfSpace>,
                "half-space pairs are served by their closed-form routines");
  if (!finite_poses(pose_a, pose_b)) return invalid_distance();
  generic_detail::PairSetup<A, B> setup(a, pose_a, b, pose_b, request, cache);
  const generic_detail::LocalAnswer ans = generic_detail::solve(a, b, setup, request);
  setup.store(cache, ans.normal);
  if (cache && ans.sat_used) cache->sat_feature = ans.sat_feature;
  DistanceResult r;
  r.signed_distance = ans.signed_distance;
  r.point_a = pose_a.apply(ans.point_a);
  r.point_b = pose_a.apply(ans.point_b);
  r.normal = pose_a.apply_vector(ans.normal);
  r.status = ans.status;
  r.method = ans.method;
  r.iterations = ans.iterations;
  return r;
}

/// True when A and B are within request.contact_distance (plus tolerance) of each other: GJK
/// in boolean mode, stopping at the first separating axis or the first proof of contact.
template <class A, class B>
bool generic_intersect(const A& a, const Transform& pose_a, const B& b, const Transform& pose_b,
                       const PairRequest& request, PairCache* cache) {
  static_assert(!std::is_same_v<A, HalfSpace> && !std::is_same_v<B, HalfSpace>,
                "half-space pairs are served by their closed-form routines");
  if (!finite_poses(pose_a, pose_b)) return false;
  generic_detail::PairSetup<A, B> setup(a, pose_a, b, pose_b, request, cache);
  gjk::Settings s = setup.gjk_settings(request);
  const Real margin = setup.radius_a + setup.radius_b + std::max(request.contact_distance, Real(0)) + setup.tolerance;
  s.margin = margin;
  const gjk::Outcome g = gjk::distance(setup.support_a, setup.support_b, setup.axis, s);
  if (cache) {
    // A proven separating axis is the best start for the next, coherent query.
    const Vec3 n = g.status == gjk::Status::EarlyExit ? generic_detail::unit_or(g.separating_axis, -g.v)
                                                      : generic_detail::unit_or(-g.v, setup.axis);
    setup.store(cache, n);
  }
  if (g.status == gjk::Status::EarlyExit) return false;
  if (g.status == gjk::Status::Overlapping) return true;
  return g.distance <= margin;
}

/// The generic distance as the pair routine of every pair without a closed-form one (the
/// dispatch table's overload resolution prefers the non-template closed-form routines).
template <class A, class B>
DistanceResult pair_distance(const A& a, const Transform& pose_a, const B& b, const Transform& pose_b,
                             const PairRequest& request, PairCache* cache) {
  return generic_distance(a, pose_a, b, pose_b, request, cache);
}

/// The generic boolean query as the pair routine (see pair_distance).
template <class A, class B>
bool pair_intersect(const A& a, const Transform& pose_a, const B& b, const Transform& pose_b,
                    const PairRequest& request, PairCache* cache) {
  return generic_intersect(a, pose_a, b, pose_b, request, cache);
}

}  // namespace proxima::narrow
