#pragma once
/// @file generic_distance.hpp
/// The generic narrow phase for any pair of convex shapes without a closed-form routine:
///   1. B's pose relative to A; B's core support mapped into A's local frame once;
///   2. GJK (plain or Nesterov, PairRequest::gjk) between the cores, warm-started from the
///      PairCache (axis in A's frame, hull support hints), its simplex arithmetic in double
///      unless both shapes are polytopes (gjk::Settings::wide); the radii are added after:
///      distance = |v| - r_A - r_B, witnesses moved by the radii along the normal;
///   3. a polytope pair whose GJK (simplex in Real) stopped with its duality gap open runs
///      GJK again with the simplex in double (widen_open_polytope_gjk);
///   4. a ladder of stages, the first that answers wins (GenericStage names it):
///      a. SatAtGjkCap: polytopes whose GJK hit its cap: the SAT, when it proves an overlap;
///      b. CoreClosestPoint: GJK's answer is not certified (its duality gap is open, or the
///         cores touch, or a point core lies inside the other shape) and one core is a
///         point, segment or triangle, or a box against a curved shape: the exact minimum
///         of the other shape's signed distance over that core (core_closest_point.hpp),
///         where it is exact;
///      b'. SurfaceProjection: GJK's gap is open on cores apart and neither side has such a
///         core (two curved shapes, or a hull and a curved shape): the shapes' own closest
///         points by alternating projections, along the normal that separates them most
///         (surface_projection.hpp); where that gap is within sqrt(eps) of the size and its
///         bounds do not meet, EPA on cores inflated beyond it decides (c), this answer the
///         fall-back;
///      b''. GjkDistance: the cores are apart: GJK's answer;
///      c'. SatAtContact: polytopes whose cores touch (GJK's distance within rounding, its
///         simplex not a tetrahedron round the origin): the SAT's signed distance, exact to
///         rounding there, where EPA on inflated cores is accurate to about 1e-13 of the size;
///      c. Epa / InflatedEpa: the cores overlap: EPA from GJK's simplex (on cores inflated by
///         a small ball when they only touch, or when that beats an EPA stopped by rounding;
///         touching cores whose core search found the distance keep that distance),
///         refined by epa::refine on curved pairs; it answers when it converged (or, on a
///         curved pair, stopped at its cap);
///      d. SatFallback: polytopes whose EPA failed or stopped: the SAT's depth (status
///         Degenerate when EPA failed);
///      e. CoreRefinement: D = core A - core B too thin for EPA: epa::refine from GJK's
///         direction finds a normal along which D's support distance is within reach of 0;
///      f. GjkCoreContact: GJK's core contact (depth r_A + r_B along the best axis known),
///         status Degenerate;
///   5. a side's core curved (cylinder, cone, ellipsoid): the answer's normal refined on D's
///      support function to the precision of the arithmetic (epa::refine), the signed
///      distance taken along it (refine_to_precision);
///   6. an answer whose witnesses stay off point_b = point_a + d n after a Nesterov GJK run:
///      steps 2-5 again from plain GJK, the answer closer to the relation kept;
///   7. tolerance from resolve_tolerance (size of the pair), outputs in the world frame,
///      cache written back.
/// pair_intersect runs GJK in boolean mode with early exit on a separating axis.

#include <proxima/core/tolerance.hpp>
#include <proxima/geometry/epa.hpp>
#include <proxima/geometry/epa_refine.hpp>
#include <proxima/geometry/gjk.hpp>
#include <proxima/shapes/halfspace.hpp>
#include <proxima/shapes/shape.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <type_traits>

#include "core_closest_point.hpp"
#include "pair_support.hpp"
#include "polytope_sat.hpp"
#include "support_binding.hpp"
#include "surface_projection.hpp"

namespace proxima::narrow {

/// The stage of the generic ladder that gave an answer (see the file comment). The answer's
/// PairMethod names the algorithm only; this says which rung of the ladder answered.
enum class GenericStage : std::uint8_t {
  NotRun,             ///< no stage ran (a pose was out of range: status InvalidInput)
  SatAtGjkCap,        ///< polytopes, GJK at its cap: the SAT proved an overlap (method Sat)
  CoreClosestPoint,   ///< a point, segment, triangle or box core against the other shape's closest point
                      ///< (method ClosestPoint)
  SurfaceProjection,  ///< two curved shapes (or a hull and one), GJK's gap open: their closest points
                      ///< by alternating projections (method ClosestPoint)
  GjkDistance,        ///< the cores are apart: GJK's distance (method Gjk)
  Epa,                ///< the cores overlap: EPA on the cores, refined on curved pairs (method Epa)
  InflatedEpa,        ///< EPA on the cores inflated by a small ball (touching cores, or a better bound) (method Epa)
  SatAtContact,       ///< polytopes whose cores touch: the SAT's signed distance (method Sat)
  SatFallback,        ///< polytopes, EPA failed or stopped at its cap: the SAT's depth (method Sat)
  CoreRefinement,     ///< D too thin for EPA: epa::refine from GJK's direction (method Epa)
  GjkCoreContact,     ///< nothing else answered: GJK's core contact, status Degenerate (method Gjk)
};

/// Name of a stage, for messages.
constexpr const char* to_string(GenericStage s) {
  switch (s) {
    case GenericStage::NotRun: return "NotRun";
    case GenericStage::SatAtGjkCap: return "SatAtGjkCap";
    case GenericStage::CoreClosestPoint: return "CoreClosestPoint";
    case GenericStage::SurfaceProjection: return "SurfaceProjection";
    case GenericStage::GjkDistance: return "GjkDistance";
    case GenericStage::Epa: return "Epa";
    case GenericStage::InflatedEpa: return "InflatedEpa";
    case GenericStage::SatAtContact: return "SatAtContact";
    case GenericStage::SatFallback: return "SatFallback";
    case GenericStage::CoreRefinement: return "CoreRefinement";
    case GenericStage::GjkCoreContact: return "GjkCoreContact";
  }
  return "?";
}

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
    s.wide = !(kIsPolytope<A> && kIsPolytope<B>);  // curved sides need GJK's simplex in double
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
  Real signed_distance = Real(0);          ///< > 0 gap, < 0 penetration
  Vec3 point_a{Real(0)};                   ///< witness on A (A's frame)
  Vec3 point_b{Real(0)};                   ///< witness on B (A's frame)
  Vec3 normal{Real(0), Real(0), Real(1)};  ///< unit, A to B (A's frame)
  PairStatus status = PairStatus::Separated;
  PairMethod method = PairMethod::Gjk;
  int iterations = 0;                         ///< GJK + EPA iterations of every stage that ran
  std::uint32_t sat_feature = 0;              ///< the SAT's axis (when sat_used)
  bool sat_used = false;                      ///< the SAT answered
  GenericStage stage = GenericStage::NotRun;  ///< the stage that answered
};

/// A gap between the cores that its stage could not certify: its answer (an upper bound,
/// the fall-back) and a proven lower bound; EPA on cores inflated beyond the gap decides
/// within them.
struct UndecidedGap {
  LocalAnswer answer;  ///< the stage's answer; its signed distance is the upper bound (length)
  Real lower;          ///< a proven lower bound of the distance (length)
};

/// Half-width of the band around the contact threshold inside which generic_intersect asks
/// the distance query instead of trusting boolean GJK: one length tolerance in float; 64 in
/// double, where boolean GJK (its simplex in Real) on curved sides was seen 3 tolerances off
/// (a point 6.6e-14 outside a cylinder of size 0.4 reported overlapping, tolerance 2.2e-14).
inline Real boolean_band(Real tolerance) { return sizeof(Real) == sizeof(float) ? tolerance : Real(64) * tolerance; }

/// How deep the origin lies inside GJK's final simplex (a length): the smallest distance
/// from the origin to a face of the tetrahedron, computed in Wide, less the rounding of that
/// face's normal; 0 when the simplex is not a tetrahedron, is degenerate, or does not hold
/// the origin beyond that rounding. The tetrahedron lies in D = A - B, so the origin is at
/// least this deep inside D. A face's normal, the cross product of two edges, carries the
/// coordinates' rounding (eps max|p|) over each edge, which turns it by up to
/// eps max|p| (|e1| + |e2|) / |n| and moves the origin's depth by |p| times that; bounded by
/// 64 eps max|p|^3 / |n| (no square root). On a sliver (edges 1.2 and 2.7e-5 long, a
/// triangle against a cone) the depth came out 2.9e-12 where the origin lies 9.9e-13
/// outside the face, and intersect answered a hit for shapes 3 tolerances apart.
inline Real enclosed_depth(const gjk::Simplex& s) {
  if (s.size != 4) return Real(0);
  const gjk::WideVec3 p[4] = {gjk::WideVec3(s.v[0].w), gjk::WideVec3(s.v[1].w), gjk::WideVec3(s.v[2].w),
                              gjk::WideVec3(s.v[3].w)};
  gjk::Wide extent = gjk::Wide(0);
  for (const gjk::WideVec3& q : p) extent = std::max({extent, std::abs(q.x), std::abs(q.y), std::abs(q.z)});
  const gjk::Wide rounding = gjk::Wide(64) * std::numeric_limits<gjk::Wide>::epsilon() * extent * extent * extent;
  constexpr int kFaces[4][4] = {{1, 2, 3, 0}, {0, 2, 3, 1}, {0, 1, 3, 2}, {0, 1, 2, 3}};  // face, opposite
  gjk::Wide depth = std::numeric_limits<gjk::Wide>::max();
  for (const auto& f : kFaces) {
    gjk::WideVec3 n = glm::cross(p[f[1]] - p[f[0]], p[f[2]] - p[f[0]]);
    const gjk::Wide len = std::sqrt(glm::dot(n, n));
    if (!(len > gjk::Wide(0)) || !std::isfinite(len)) return Real(0);
    if (glm::dot(n, p[f[3]] - p[f[0]]) > gjk::Wide(0)) n = -n;         // outward
    depth = std::min(depth, (glm::dot(n, p[f[0]]) - rounding) / len);  // origin's depth below the face
  }
  return depth > gjk::Wide(0) ? Real(depth) : Real(0);
}

/// v made unit, else `fallback` made unit, else +z.
inline Vec3 unit_or(const Vec3& v, const Vec3& fallback) {
  const Real l2 = glm::dot(v, v);
  if (l2 > Real(0) && std::isfinite(l2)) return v / std::sqrt(l2);
  const Real f2 = glm::dot(fallback, fallback);
  if (f2 > Real(0) && std::isfinite(f2)) return fallback / std::sqrt(f2);
  return Vec3(Real(0), Real(0), Real(1));
}

/// The state the stages of the ladder share: the pair, GJK's run on the cores, and the
/// answer being built (its iteration count adds up over the stages that ran).
template <class A, class B>
struct Ladder {
  /// Runs GJK between the cores of `shape_a` and `shape_b` (the first step of every query).
  Ladder(const A& shape_a, const B& shape_b, PairSetup<A, B>& pair, const PairRequest& options)
      : a(shape_a),
        b(shape_b),
        setup(pair),
        request(options),
        core(gjk::distance(pair.support_a, pair.support_b, pair.axis, pair.gjk_settings(options))),
        radii(pair.radius_a + pair.radius_b),
        touching(core.simplex.size < 4) {
    ans.iterations = core.iterations;
  }

  const A& a;                  ///< shape A (A's frame)
  const B& b;                  ///< shape B
  PairSetup<A, B>& setup;      ///< supports, radii, scale and tolerance
  const PairRequest& request;  ///< caps and options
  gjk::Outcome core;           ///< GJK between the cores
  Real radii;                  ///< r_A + r_B
  bool touching;               ///< GJK did not enclose the origin in a tetrahedron (the cores only touch)
  LocalAnswer ans;             ///< the answer
  /// Set where the cores are apart by a gap no stage could certify and EPA, on cores
  /// inflated beyond it, is to decide within its bounds (projected_distance).
  std::optional<UndecidedGap> undecided;
  /// The core stage's least signed distance (radii included) where GJK finds the cores
  /// touching and that distance is within the tolerance: exact to rounding, where EPA on
  /// inflated cores, which gives the touching pair its normal, errs by about 1e-13 of the
  /// size. NaN when not set.
  Real core_touch = std::numeric_limits<Real>::quiet_NaN();
};

/// True for the shapes whose core has a curved support (no vertex answers it near most
/// directions): cylinder, cone, ellipsoid. Spheres and capsules are rounded points and
/// segments.
template <class S>
inline constexpr bool kCurvedCore =
    std::is_same_v<S, Cylinder> || std::is_same_v<S, Cone> || std::is_same_v<S, Ellipsoid>;

/// True when a side's core is curved: the pair's answer is refined to the precision of the
/// arithmetic (refine_to_precision).
template <class A, class B>
inline constexpr bool kCurvedCorePair = kCurvedCore<A> || kCurvedCore<B>;

/// True when both shapes are polytopes (the SAT applies).
template <class A, class B>
inline constexpr bool kPolytopePair = (kIsPolytope<A> && kIsPolytope<B>);

/// Writes what both SAT stages answer alike (normal, distance, method, axis, stage); the
/// caller adds the witnesses and the status.
template <class A, class B>
void answer_from_sat(Ladder<A, B>& l, const SatResult& s, GenericStage stage) {
  l.ans.normal = s.normal;
  l.ans.signed_distance = s.signed_distance - l.radii;
  l.ans.method = PairMethod::Sat;
  l.ans.sat_feature = s.feature;
  l.ans.sat_used = true;
  l.ans.stage = stage;
}

/// The SAT between the two polytopes (A's frame).
template <class A, class B>
SatResult run_sat(const Ladder<A, B>& l) {
  const PolytopeView va(l.a);
  const PolytopeView vb(l.b);
  return polytope_sat(va, vb, l.setup.support_b.rotation, l.setup.support_b.translation);
}

/// Stage a: GJK stopped by the cap on a polytope pair: the SAT decides overlap exactly.
template <class A, class B>
bool sat_at_gjk_cap(Ladder<A, B>& l) {
  if constexpr (kPolytopePair<A, B>) {
    if (l.core.status != gjk::Status::MaxIterations) return false;
    const SatResult s = run_sat(l);
    if (!(s.valid && s.signed_distance < Real(0))) return false;
    answer_from_sat(l, s, GenericStage::SatAtGjkCap);
    l.ans.point_a = s.point_a;
    l.ans.point_b = s.point_b;
    l.ans.status = status_from_distance(l.ans.signed_distance, l.setup.tolerance);
    return true;
  } else {
    (void)l;
    return false;
  }
}

/// True when GJK found the cores apart beyond rounding (16 eps of the pair's size).
template <class A, class B>
bool cores_apart(const Ladder<A, B>& l) {
  return l.core.status != gjk::Status::Overlapping && l.core.distance > Real(16) * kEpsilon * l.setup.scale;
}

/// True when GJK's answer on cores apart is not certified: its duality gap open beyond a
/// quarter of the tolerance, its cap reached, or no positive lower bound (nothing proved the
/// cores apart: a float run on a long thin box ended on a repeated vertex, its v's direction
/// rounded, 9e-5 from a point 0.05 deep inside).
template <class A, class B>
bool gjk_gap_open(const Ladder<A, B>& l) {
  const gjk::Outcome& g = l.core;
  return cores_apart(l) && (g.status == gjk::Status::MaxIterations || !(g.lower_bound > Real(0)) ||
                            g.distance - g.lower_bound > Real(0.25) * l.setup.tolerance);
}

/// True when side S's core serves the core stage against the other side O: a point, segment
/// or triangle core always, a box only against a shape that is not a polytope (between
/// polytopes GJK ends on a repeated vertex and the SAT backs it).
template <class S, class O>
inline constexpr bool kCoreServes = SimpleCore<S>::kCount != 0 && (!std::is_same_v<S, Box> || !kIsPolytope<O>);

/// True when the pair has a side whose core serves the core stage (core_closest_point.hpp).
template <class A, class B>
inline constexpr bool kHasSimpleCore = kCoreServes<A, B> || kCoreServes<B, A>;

/// The side searched by the core stage: A's core when it is simple and has no more vertices
/// than B's (a point before a segment before a triangle), else B's.
template <class A, class B>
inline constexpr bool kCoreStageOnA = SimpleCore<A>::kCount != 0 &&
                                      (SimpleCore<B>::kCount == 0 || SimpleCore<A>::kCount <= SimpleCore<B>::kCount);

/// The least signed distance of the other shape X over the searched core (A's frame), and
/// the core's radius.
struct CoreSearch {
  CoreClosest closest;  ///< the core's point nearest X, X's closest point and normal
  Real radius;          ///< the searched core's radius
};

/// A and B as placed shapes in A's frame (closest points and supports of the full shapes).
template <class A, class B>
PlacedShape<A> placed_a(const Ladder<A, B>& l) {
  return {l.a, Mat3(Real(1)), Mat3(Real(1)), Vec3(Real(0))};
}
/// See placed_a.
template <class A, class B>
PlacedShape<B> placed_b(const Ladder<A, B>& l) {
  const auto& m = l.setup.support_b;
  return {l.b, m.rotation, m.rotation_t, m.translation};
}

/// Runs core_closest_point on the side kCoreStageOnA names, X placed in A's frame. A box
/// searches the features facing X: corners within 5 % of the pair's scale of its support
/// plane along GJK's direction towards X; all of them where that direction is not known to
/// be good: GJK's lower bound under half its distance (stalled on a sliver, v's direction is
/// the sliver's normal), or no distance.
template <class A, class B>
CoreSearch search_simple_core(const Ladder<A, B>& l) {
  const bool has_direction =
      l.core.distance > Real(0) && std::isfinite(l.core.distance) && l.core.lower_bound >= Real(0.5) * l.core.distance;
  const Vec3 a_to_b = has_direction ? -l.core.v / l.core.distance : Vec3(Real(0));
  const Real window = has_direction ? Real(0.05) * l.setup.scale : std::numeric_limits<Real>::infinity();
  if constexpr (kCoreStageOnA<A, B>) {
    return {core_closest_point(placed_b(l), SimpleCore<A>::vertices(l.a), a_to_b, window), l.setup.radius_a};
  } else {
    const auto& m = l.setup.support_b;
    auto v = SimpleCore<B>::vertices(l.b);
    for (Vec3& p : v) p = m.rotation * p + m.translation;
    return {core_closest_point(placed_a(l), v, -a_to_b, window), l.setup.radius_b};
  }
}

/// The core stage's answer from its search, along normal n (A to B). `exact_witnesses`:
/// the core's point and X's closest point, else (touching) X's point and the other placed
/// along n so that point_b = point_a + signed_distance n.
template <class A, class B>
void answer_from_core(Ladder<A, B>& l, const CoreSearch& c, const Vec3& n, bool exact_witnesses) {
  constexpr bool kOnA = kCoreStageOnA<A, B>;
  l.ans.normal = n;
  l.ans.signed_distance = c.closest.signed_distance - c.radius;
  const Vec3 core_surface = c.closest.core_point + (kOnA ? c.radius : -c.radius) * n;
  l.ans.point_a = kOnA ? core_surface : c.closest.surface_point;
  l.ans.point_b = kOnA ? c.closest.surface_point : core_surface;
  if (!exact_witnesses) {
    if (kOnA)
      l.ans.point_b = l.ans.point_a + l.ans.signed_distance * n;
    else
      l.ans.point_a = l.ans.point_b - l.ans.signed_distance * n;
  }
  l.ans.method = PairMethod::ClosestPoint;
  l.ans.status = status_from_distance(l.ans.signed_distance, l.setup.tolerance);
  l.ans.stage = GenericStage::CoreClosestPoint;
}

/// Stage b: GJK's answer is not certified (its gap is open, the cores touch, or it hit its
/// cap) and a side's core is a point, segment or triangle (or a box, the other shape curved):
/// the least signed distance of the other shape X over that core (core_closest_point.hpp).
/// A point core answers always (its
/// distance or depth is exact). A segment, triangle or box core answers when apart beyond the
/// tolerance; within it, where GJK stalled above it, as touching along GJK's direction -v
/// (X's normal at the contact may be any of its normal cone, a rim's or a segment's, where
/// the answer needs one across the core too). It leaves to the stages below a core through
/// X (deeper than its deepest point), cores GJK finds touching or overlapping, and a least
/// sd above GJK's upper bound |v| (X through the interior of a triangle whose edges stay
/// outside). Where GJK finds the cores touching and sd is within the tolerance, it keeps sd
/// (Ladder::core_touch) for EPA's answer, which gives the normal.
template <class A, class B>
bool core_closest(Ladder<A, B>& l) {
  if constexpr (!kHasSimpleCore<A, B>) {
    (void)l;
    return false;
  } else {
    constexpr bool kPointCore = (kCoreStageOnA<A, B> ? SimpleCore<A>::kCount : SimpleCore<B>::kCount) == 1;
    const gjk::Outcome& g = l.core;
    const Real tolerance = l.setup.tolerance;
    const bool overlapping = g.status == gjk::Status::Overlapping;
    const bool apart = cores_apart(l);
    if (apart && !gjk_gap_open(l)) return false;  // certified by GJK's duality gap
    // An overlap deeper than the tolerance inside GJK's tetrahedron is EPA's to measure.
    if (overlapping && !kPointCore && !(enclosed_depth(g.simplex) <= tolerance)) return false;
    const CoreSearch c = search_simple_core(l);
    const Real sd = c.closest.signed_distance;
    if (!std::isfinite(sd)) return false;
    // X's outward normal points from X to the core: B to A when the core is A's.
    const Vec3 n = kCoreStageOnA<A, B> ? -c.closest.normal : c.closest.normal;
    if (kPointCore || (sd > tolerance && sd <= g.distance + tolerance)) {
      answer_from_core(l, c, n, true);
      return true;
    }
    if (!apart && std::abs(sd) <= tolerance) l.core_touch = sd - c.radius;  // for EPA's answer
    if (!apart || overlapping || !(std::abs(sd) <= tolerance)) return false;
    answer_from_core(l, c, -g.v / g.distance, false);
    return true;
  }
}

/// Before the stages: a polytope pair runs GJK's simplex in Real (float in the float build,
/// for speed); where that run stops with its duality gap open (a sliver of nearby vertices
/// on a large polytope near contact: seen 2.5 tolerances above the distance on a box and a
/// hull of size 7 in float), GJK runs again from its direction with the simplex in double,
/// and its answer replaces the first when it is no farther.
template <class A, class B>
void widen_open_polytope_gjk(Ladder<A, B>& l) {
  if constexpr (kPolytopePair<A, B> && !std::is_same_v<Real, gjk::Wide>) {  // nothing wider in double
    if (!gjk_gap_open(l) || l.core.status == gjk::Status::MaxIterations) return;
    gjk::Settings s = l.setup.gjk_settings(l.request);
    s.wide = true;
    const gjk::Outcome again = gjk::distance(l.setup.support_a, l.setup.support_b, -l.core.v, s);
    l.ans.iterations += again.iterations;
    if (again.status == gjk::Status::MaxIterations || !(again.distance <= l.core.distance)) return;
    l.core = again;
    l.touching = again.simplex.size < 4;
  } else {
    (void)l;
  }
}

/// Stage b'': GJK's gap is open on cores apart, no side has a simple core and the pair is
/// not two polytopes (two curved shapes, or a hull and a curved shape; radii 0): the
/// shapes' own closest points by alternating projections (surface_projection.hpp). Answers
/// when its distance is below GJK's, along the normal that separates the shapes most; the
/// witness on B is placed on that normal (point_b = point_a + distance n).
template <class A, class B>
bool projected_distance(Ladder<A, B>& l) {
  if constexpr (kPolytopePair<A, B> || kHasSimpleCore<A, B>) {
    (void)l;
    return false;
  } else {
    // A run stopped by the request's cap answers as capped (stage b'').
    if (!gjk_gap_open(l) || l.core.status == gjk::Status::MaxIterations || l.radii != Real(0)) return false;
    const gjk::Outcome& g = l.core;
    PairSetup<A, B>& setup = l.setup;
    const SurfaceProjection p =
        surface_projection(placed_a(l), placed_b(l), setup.support_a, setup.support_b, g.point_a, -g.v / g.distance);
    l.ans.iterations += p.rounds;
    if (!(p.upper < g.distance) || !(p.upper > Real(0))) return false;
    const Real lower = std::max(p.lower, g.lower_bound);
    l.ans.normal = p.normal;
    l.ans.signed_distance = p.upper;
    l.ans.point_a = p.point_a;
    l.ans.point_b = p.point_a + p.upper * p.normal;
    l.ans.method = PairMethod::ClosestPoint;
    l.ans.status = status_from_distance(p.upper, setup.tolerance);
    l.ans.stage = GenericStage::SurfaceProjection;
    if (p.upper - lower > setup.tolerance && p.upper <= kSqrtEpsilon * setup.scale) {
      l.undecided = UndecidedGap{l.ans, lower};  // touching within rounding: EPA decides
      return false;
    }
    return true;
  }
}

/// The normal of the feature of D holding GJK's closest point, from its final simplex `s`
/// (`n`: -v / |v|, unit): a triangle's plane (it lies in D's supporting plane, so its normal
/// is the face's), a segment's perpendicular through n (exact across the edge, the
/// direction along which the gap has a kink), a vertex's n. v, a weighted sum of the
/// simplex's points, carries their rounding over its length: the tilt of a short gap's
/// normal.
inline Vec3 simplex_feature_normal(const gjk::Simplex& s, const Vec3& n) {
  Vec3 m = n;
  if (s.size == 3) {
    m = glm::cross(s.v[1].w - s.v[0].w, s.v[2].w - s.v[0].w);
  } else if (s.size == 2) {
    m = across_direction(n, s.v[1].w - s.v[0].w);
  }
  const Real len = glm::length(m);
  if (!(len > Real(0)) || !std::isfinite(len)) return n;
  m /= len;
  return glm::dot(m, n) < Real(0) ? -m : m;
}

/// Stage b': the cores are apart (beyond rounding): GJK's distance minus the radii. Where
/// both cores are polytopes the normal is that of D's feature holding the closest point
/// (simplex_feature_normal) and the distance the gap along it, so that the overlap along
/// the reported normal is the reported distance to rounding (a box 1.8e-6 from a hull had
/// its normal tilted by v's rounding, the gap along it 74 ulps of the size off). Curved
/// cores are refined instead (refine_to_precision).
template <class A, class B>
bool gjk_distance(Ladder<A, B>& l) {
  const gjk::Outcome& g = l.core;
  if (!cores_apart(l)) return false;
  Vec3 n = -g.v / g.distance;
  Real core_distance = g.distance;
  if constexpr (!kCurvedCorePair<A, B>) {
    // The simplex lies in D's supporting plane along the feature's normal m, so the gap
    // along m is the plane's distance from the origin, -w . m for any of its points. Kept
    // where that agrees with |v| to rounding: a degenerate simplex (a needle hull's) gives
    // a noisy m, and GJK's answer stands there.
    const Vec3 m = simplex_feature_normal(g.simplex, n);
    if (m != n) {
      Real plane = Real(0);
      for (int i = 0; i < g.simplex.size; ++i) plane -= glm::dot(g.simplex.v[static_cast<std::size_t>(i)].w, m);
      plane /= Real(g.simplex.size);
      if (std::abs(plane - g.distance) <= Real(16) * kEpsilon * l.setup.scale) {
        n = m;
        core_distance = plane;
      }
    }
  }
  l.ans.normal = n;
  l.ans.signed_distance = core_distance - l.radii;
  l.ans.point_a = g.point_a + l.setup.radius_a * n;
  l.ans.point_b = g.point_b - l.setup.radius_b * n;
  l.ans.method = PairMethod::Gjk;
  l.ans.status = g.status == gjk::Status::MaxIterations
                     ? PairStatus::MaxIterations
                     : status_from_distance(l.ans.signed_distance, l.setup.tolerance);
  l.ans.stage = GenericStage::GjkDistance;
  return true;
}

/// Stage c': polytopes whose cores touch: GJK's distance is within rounding (not apart) and
/// its simplex does not enclose the origin in a tetrahedron. The SAT's largest separation is
/// 0 to rounding at contact and minus the depth on an overlap (exact for polytopes), where
/// EPA on inflated cores errs by about 1e-13 of the size; pairs whose Minkowski difference
/// has no volume (a point on a segment) answer 0. GJK's witness (a point of both cores) is
/// kept, the other placed along the SAT's normal. Pairs without an axis (points and
/// segments only) go on to EPA.
template <class A, class B>
bool sat_at_contact(Ladder<A, B>& l) {
  if constexpr (kPolytopePair<A, B>) {
    if (!l.touching || cores_apart(l)) return false;
    const SatResult s = run_sat(l);
    // A degenerate simplex may also stop GJK on a deep overlap (the origin on a segment of D,
    // as for identical shapes): that depth and its witnesses are EPA's.
    if (!s.valid || !(std::abs(s.signed_distance) <= l.setup.tolerance)) return false;
    answer_from_sat(l, s, GenericStage::SatAtContact);
    l.ans.point_a = l.core.point_a + l.setup.radius_a * s.normal;
    l.ans.point_b = l.ans.point_a + l.ans.signed_distance * s.normal;
    l.ans.status = status_from_distance(l.ans.signed_distance, l.setup.tolerance);
    return true;
  } else {
    (void)l;
    return false;
  }
}

/// EPA's options for the request. Curved shapes converge slowly: a relative 1e-9 of the
/// pair's size is enough in double.
template <class A, class B>
epa::Settings epa_settings(const Ladder<A, B>& l) {
  epa::Settings es;
  es.max_iterations = std::max(l.request.max_iterations, 1);
  es.max_faces = l.request.max_epa_faces;
  es.abs_tolerance = std::max(Real(0.1) * l.setup.tolerance, Real(1e-9) * l.setup.scale);
  return es;
}

/// EPA converges only linearly on curved supports: unless its gap is already within
/// rounding, Newton steps on the support function of D (epa::refine) take its normal to the
/// minimum. The refined support distance is an upper bound of the depth; the witnesses are
/// support points (combined across an edge or face of D) with point_a - point_b = depth *
/// normal. Nothing changes when `curved` is false or EPA failed.
template <class A, class B, class SupportA, class SupportB>
void polish(const Ladder<A, B>& l, epa::Outcome& ep, SupportA& sa, SupportB& sb, bool curved) {
  if (!curved || ep.status == epa::Status::Degenerate) return;
  const Real scale = l.setup.scale;
  const Real target = Real(64) * kEpsilon * scale;
  // EPA's witnesses against point_a - point_b = depth n: a converged EPA whose gap is within
  // rounding still refines where they are off it (a cone's apex and a point of a sliver hull
  // 0.067 apart across the normal, EPA's gap 0).
  const Real epa_gap = glm::length((ep.point_a - ep.point_b) - ep.depth * ep.normal);
  // EPA's normal on a curved core is a face normal of its polytope, off by about
  // sqrt(gap / curvature) even where its gap is within rounding: refined always there.
  if (!kCurvedCorePair<A, B> && ep.status == epa::Status::Converged && ep.gap <= target && epa_gap <= l.setup.tolerance)
    return;
  // From the normal of EPA's least upper bound (its nearest face's normal may be worse).
  const int cap = std::clamp(l.request.max_iterations, 1, 96);
  epa::Refinement f = epa::refine(sa, sb, ep.upper_normal, scale, cap);
  ep.iterations += f.iterations;
  // Stopped at its cap, EPA's polytope is coarse, and the support distance of a curved D can
  // have several local minima (two concentric ellipsoids: one per principal direction); a
  // refinement descends to the one nearest its start. From the normals of the polytope's
  // other nearest faces too, the least converged depth is kept (two ellipsoids 14 deep:
  // 0.018 too deep from the upper bound's normal alone).
  for (int k = 0; k < ep.other_count; ++k) {
    const epa::Refinement g = epa::refine(sa, sb, ep.other_normals[static_cast<std::size_t>(k)], scale, cap);
    ep.iterations += g.iterations;
    if (g.converged && (!f.converged || g.depth < f.depth)) f = g;
  }
  // Unconverged, EPA's own answer stands (at its cap: the nearest face, a lower bound).
  if (!f.converged || !(f.depth <= ep.depth + ep.gap + kSqrtEpsilon * scale)) return;
  // A converged EPA keeps its own answer where the refined witnesses could not be placed
  // on both surfaces (an edge of D meeting a curved side off the tipped supports' reach),
  // unless its own are further off point_a - point_b = depth n (a disc 0.15 thick in a
  // sliver hull: EPA 0.007 short, its witnesses 0.04 off the relation; refined 2e-5 off
  // the depth, the witnesses 0.019 apart across the normal).
  if (ep.status == epa::Status::Converged && f.witness_gap > kSqrtEpsilon * scale && f.witness_gap >= epa_gap) return;
  ep.status = epa::Status::Converged;
  ep.gap = std::max(f.depth - ep.depth, Real(0));
  ep.depth = f.depth;
  ep.normal = f.normal;
  ep.point_a = f.support_a;
  ep.point_b = f.support_b;
}

/// EPA on the cores inflated by a small ball delta, whose Minkowski difference holds the
/// origin robustly when the cores only touch; the depth is then exactly 2 delta larger,
/// and is corrected back. Its GJK run's iterations count into the answer.
template <class A, class B>
epa::Outcome inflated_epa(Ladder<A, B>& l, const epa::Settings& es) {
  PairSetup<A, B>& setup = l.setup;
  const Real gap = l.undecided ? l.undecided->answer.signed_distance : Real(0);
  const Real delta = std::max({Real(1024) * kEpsilon * setup.scale, setup.tolerance, gap});
  InflatedSupport<decltype(setup.support_a)> ia{setup.support_a, delta};
  InflatedSupport<decltype(setup.support_b)> ib{setup.support_b, delta};
  gjk::Settings gs = setup.gjk_settings(l.request);
  gjk::Outcome gi = gjk::distance(ia, ib, setup.axis, gs);
  l.ans.iterations += gi.iterations;
  epa::Outcome ei = epa::penetration(ia, ib, gi.simplex, setup.scale, es);
  if (ei.status == epa::Status::Degenerate && gs.variant != gjk::Variant::Plain) {
    // Nesterov's momentum can end on a flat tetrahedron (the origin 6e-7 inside it, on a box
    // holding an ellipsoid 20 deep), from which EPA cannot start: plain GJK's tetrahedron.
    gs.variant = gjk::Variant::Plain;
    gi = gjk::distance(ia, ib, setup.axis, gs);
    l.ans.iterations += gi.iterations + ei.iterations;
    ei = epa::penetration(ia, ib, gi.simplex, setup.scale, es);
  }
  // Inflated cores are curved; for polytopes only when the cores merely touch (deeper
  // polytope pairs have the exact SAT fall-back, while a refinement stops at a local
  // minimum of a starved EPA's normal).
  polish(l, ei, ia, ib, !kPolytopePair<A, B> || l.touching);
  if (ei.status != epa::Status::Degenerate) {
    ei.depth -= Real(2) * delta;
    ei.point_a -= delta * ei.normal;
    ei.point_b += delta * ei.normal;
  }
  return ei;
}

/// EPA's answer and which EPA gave it.
struct EpaRun {
  epa::Outcome outcome;  ///< depth, normal, witnesses of the cores
  GenericStage stage;    ///< Epa or InflatedEpa
};

/// The cores overlap or touch: EPA on the cores, or on inflated cores when they only touch.
/// An EPA stopped at its cap by rounding is run again on the inflated cores, which meet
/// other slivers; the answer with the smaller error bound is kept. So is an EPA that could
/// not start from GJK's tetrahedron (Degenerate: a Nesterov run left a flat one on two
/// cones 0.29 deep, answered distance 0 before). Iterations of every run
/// count into the answer.
template <class A, class B>
EpaRun run_epa(Ladder<A, B>& l) {
  const epa::Settings es = epa_settings(l);
  if (l.touching) {
    EpaRun run{inflated_epa(l, es), GenericStage::InflatedEpa};
    l.ans.iterations += run.outcome.iterations;
    return run;
  }
  PairSetup<A, B>& setup = l.setup;
  EpaRun run{epa::penetration(setup.support_a, setup.support_b, l.core.simplex, setup.scale, es), GenericStage::Epa};
  polish(l, run.outcome, setup.support_a, setup.support_b, !kPolytopePair<A, B>);
  if (run.outcome.status == epa::Status::MaxIterations || run.outcome.status == epa::Status::Degenerate) {
    l.ans.iterations += run.outcome.iterations;
    const epa::Outcome again = inflated_epa(l, es);
    if (again.status != epa::Status::Degenerate &&
        (run.outcome.status == epa::Status::Degenerate || again.gap < run.outcome.gap))
      run = {again, GenericStage::InflatedEpa};
  }
  l.ans.iterations += run.outcome.iterations;
  return run;
}

/// How far the answer's witnesses are from point_b = point_a + signed_distance normal.
inline Real relation_gap(const LocalAnswer& ans) {
  return glm::length(ans.point_b - (ans.point_a + ans.signed_distance * ans.normal));
}

/// How far a point given in A's frame lies from B's surface (|signed distance|, B's
/// closest_point through the pair's relative pose).
template <class A, class B>
Real off_b_surface(const B& b, const PairSetup<A, B>& setup, const Vec3& p) {
  const MappedSupport<CoreSupport<B>>& to_b = setup.support_b;
  return std::abs(b.closest_point(to_b.rotation_t * (p - to_b.translation)).signed_distance);
}

/// Where the support features along EPA's normal do not meet the relation either (a small
/// cone's apex against a sliver hull whose faces are not quite normal to it): one witness
/// moved by the signed distance along the normal, kept when it lies on the other shape's
/// surface (its closest_point, within the tolerance). B's first, then A's.
template <class A, class B>
void partner_on_the_other_surface(Ladder<A, B>& l) {
  const Vec3 on_b = l.ans.point_a + l.ans.signed_distance * l.ans.normal;
  if (off_b_surface(l.b, l.setup, on_b) <= l.setup.tolerance) {
    l.ans.point_b = on_b;
    return;
  }
  const Vec3 on_a = l.ans.point_b - l.ans.signed_distance * l.ans.normal;
  if (std::abs(l.a.closest_point(on_a).signed_distance) <= l.setup.tolerance) l.ans.point_a = on_a;
}

/// EPA's witnesses off point_b = point_a + signed_distance n beyond the tolerance (its
/// nearest face's projection fell outside it on a flat contact of coplanar faces, and the
/// face's nearest point answered): the witnesses of the cores' support feature along EPA's
/// normal (epa::witnesses_along), A's kept and B's placed on the normal, when they meet the
/// line along it closer, else partner_on_the_other_surface. Seen on two cones whose bases
/// overlap face to face 2.5 deep: witnesses 1.9 apart across the normal.
template <class A, class B>
void place_witnesses_on_the_normal(Ladder<A, B>& l, const epa::Outcome& e) {
  const Real off = relation_gap(l.ans);
  if (!(off > l.setup.tolerance)) return;
  const epa::Refinement w = epa::witnesses_along(l.setup.support_a, l.setup.support_b, e.normal, l.setup.scale);
  l.ans.iterations += w.iterations;
  if (w.witness_gap < off) {
    l.ans.point_a = w.support_a + l.setup.radius_a * e.normal;
    l.ans.point_b = l.ans.point_a + l.ans.signed_distance * e.normal;
    return;
  }
  partner_on_the_other_surface(l);
}

/// Stage c: EPA's answer when it converged, or (curved pairs, which have no exact
/// fall-back) when it stopped at its cap with a lower bound.
template <class A, class B>
bool epa_answer(Ladder<A, B>& l, const EpaRun& run) {
  const epa::Outcome& e = run.outcome;
  if (!(e.status == epa::Status::Converged || (e.status == epa::Status::MaxIterations && !kPolytopePair<A, B>)))
    return false;
  l.ans.normal = e.normal;
  l.ans.signed_distance = -(e.depth + l.radii);  // e.depth may be slightly negative when touching
  l.ans.point_a = e.point_a + l.setup.radius_a * e.normal;
  l.ans.point_b = e.point_b - l.setup.radius_b * e.normal;
  l.ans.method = PairMethod::Epa;
  l.ans.status = e.status == epa::Status::MaxIterations
                     ? PairStatus::MaxIterations
                     : status_from_distance(l.ans.signed_distance, l.setup.tolerance);
  l.ans.stage = run.stage;
  place_witnesses_on_the_normal(l, e);
  if constexpr (kPolytopePair<A, B>) {
    // Witnesses still off the relation: EPA stopped short of the depth (float EPA on shapes of
    // very different sizes, e.g. a hull 0.1 across in a triangle 26 across). The polytopes'
    // exact SAT answers instead (stage d).
    const Real off = relation_gap(l.ans);
    if (off > l.setup.tolerance) return false;
  }
  // Touching cores whose core search found the distance exactly: that distance, EPA's normal
  // (EPA's own within sqrt(eps) of the size: its error on inflated cores, not another contact).
  if (std::isfinite(l.core_touch) && std::abs(l.core_touch - l.ans.signed_distance) <= kSqrtEpsilon * l.setup.scale) {
    l.ans.signed_distance = l.core_touch;
    l.ans.point_b = l.ans.point_a + l.core_touch * e.normal;
    if (l.ans.status != PairStatus::MaxIterations)
      l.ans.status = status_from_distance(l.ans.signed_distance, l.setup.tolerance);
  }
  return true;
}

/// Stage d: polytopes whose EPA failed or stopped at its cap: the SAT's depth. Touching
/// cores keep GJK's witness (an exact point of both), else the SAT's feature point.
template <class A, class B>
bool sat_fallback(Ladder<A, B>& l, const epa::Outcome& e) {
  if constexpr (kPolytopePair<A, B>) {
    const SatResult s = run_sat(l);
    if (!s.valid) return false;
    answer_from_sat(l, s, GenericStage::SatFallback);
    // GJK's point is on both surfaces only where the cores really touch; a simplex short of
    // a tetrahedron can also hold the origin deep inside D (a triangle 0.05 deep in a hull).
    const bool touching = l.touching && std::abs(s.signed_distance) <= l.setup.tolerance;
    const Vec3 core_a = touching ? l.core.point_a : s.point_a;
    l.ans.point_a = core_a + l.setup.radius_a * s.normal;
    l.ans.point_b = l.ans.point_a + l.ans.signed_distance * s.normal;
    l.ans.status = e.status == epa::Status::Degenerate ? PairStatus::Degenerate
                                                       : status_from_distance(l.ans.signed_distance, l.setup.tolerance);
    return true;
  } else {
    (void)l;
    (void)e;
    return false;
  }
}

/// Stage e: the cores touch (distance ~0) and D = core A - core B, holding the origin, is
/// too thin for EPA (a point against a segment, coincident segments). The depth is radii
/// plus min over n of D's support distance, 0 along D's normals at the origin: descend the
/// support function from `n` to such a normal. Answers when the support distance found
/// (an upper bound of the core depth, 0 in exact arithmetic) is within reach of 0.
template <class A, class B>
bool core_refinement(Ladder<A, B>& l, const Vec3& n) {
  PairSetup<A, B>& setup = l.setup;
  const epa::Refinement f =
      epa::refine(setup.support_a, setup.support_b, n, setup.scale, std::clamp(l.request.max_iterations, 1, 96));
  l.ans.iterations += f.iterations;
  const Real reach = std::max(setup.tolerance, kSqrtEpsilon * setup.scale);
  if (!(f.depth <= reach && f.witness_gap <= reach)) return false;
  l.ans.normal = f.normal;
  l.ans.signed_distance = -std::max(f.depth, Real(0)) - l.radii;
  l.ans.point_a = f.support_a + setup.radius_a * f.normal;
  l.ans.point_b = l.ans.point_a + l.ans.signed_distance * f.normal;
  l.ans.method = PairMethod::Epa;
  l.ans.status = status_from_distance(l.ans.signed_distance, setup.tolerance);
  l.ans.stage = GenericStage::CoreRefinement;
  return true;
}

/// Stage f: nothing else answered: GJK's core contact along `n`, status Degenerate.
template <class A, class B>
void gjk_core_contact(Ladder<A, B>& l, const Vec3& n) {
  l.ans.normal = n;
  l.ans.signed_distance = l.core.distance - l.radii;
  l.ans.point_a = l.core.point_a + l.setup.radius_a * n;
  l.ans.point_b = l.ans.point_a + l.ans.signed_distance * n;  // keeps the witness relation exact
  l.ans.method = PairMethod::Gjk;
  l.ans.status = PairStatus::Degenerate;
  l.ans.stage = GenericStage::GjkCoreContact;
}

/// The ladder's stages (see the file comment): GJK on the cores, then the stages in order
/// until one answers. A's-frame answer with the stage that gave it.
template <class A, class B>
LocalAnswer run_stages(const A& a, const B& b, PairSetup<A, B>& setup, const PairRequest& request) {
  Ladder<A, B> l(a, b, setup, request);
  widen_open_polytope_gjk(l);
  if (sat_at_gjk_cap(l) || core_closest(l) || projected_distance(l)) return l.ans;
  if ((!l.undecided && gjk_distance(l)) || sat_at_contact(l)) return l.ans;
  const EpaRun run = run_epa(l);
  if (l.undecided) {
    // EPA decides within the bounds: an answer below the proven lower bound (EPA's error on
    // the inflated cores) or above the stage's distance is not taken.
    const UndecidedGap& u = *l.undecided;
    const Real tol = l.setup.tolerance;
    const bool decided = epa_answer(l, run) && l.ans.signed_distance >= u.lower - tol &&
                         l.ans.signed_distance <= u.answer.signed_distance + tol;
    return decided ? l.ans : u.answer;
  }
  if (epa_answer(l, run) || sat_fallback(l, run.outcome)) return l.ans;
  const Vec3 n = unit_or(-l.core.v, setup.axis);
  if (!core_refinement(l, n)) gjk_core_contact(l, n);
  return l.ans;
}

/// Witnesses for a refined answer whose feature search did not meet the line along its
/// normal n: a point of one shape whose partner, moved by the signed distance sd along n,
/// lies on the other shape within sqrt(eps) of the size (closest_point). Candidates: the
/// stage's witness on A (still right when the refinement barely turned the normal), A's
/// support point along n, and B's along -n (where one side's support along n is a single
/// point, as a cone's rim point against a segment across n, and the other's a whole edge or
/// face, that point and its partner are the contact). The stage's witness when its partner
/// is within the tolerance, else the candidate whose partner lies closest to the other
/// surface, is written to `point_a`; false when none is within reach
/// (a descent stopped along a cone's rim crease had turned the normal by 2e-5: every
/// partner 1.5e-5 off; the stage's answer stands there).
template <class A, class B>
bool refined_partners(const A& a, const B& b, PairSetup<A, B>& setup, const Vec3& stage_a, Real sd, const Vec3& n,
                      Vec3& point_a) {
  const auto off_b = [&](const Vec3& on_a) { return off_b_surface(b, setup, on_a + sd * n); };
  const Real stage_off = off_b(stage_a);
  if (stage_off <= setup.tolerance) {
    point_a = stage_a;
    return true;
  }
  const Vec3 from_b = setup.support_b(-n) - (setup.radius_b + sd) * n;
  const std::array<Vec3, 3> candidates{stage_a, setup.support_a(n) + setup.radius_a * n, from_b};
  const std::array<Real, 3> off{stage_off, off_b(candidates[1]), std::abs(a.closest_point(from_b).signed_distance)};
  const auto best = static_cast<std::size_t>(std::min_element(off.begin(), off.end()) - off.begin());
  if (!(off[best] <= kSqrtEpsilon * setup.scale)) return false;
  point_a = candidates[best];
  return true;
}

/// Step 5 (a side's core curved): the answer's normal refined on D's support function
/// (epa::refine) to the precision of the arithmetic, and the signed distance taken along it,
/// -(h(n) + r_A + r_B), so that the overlap of the two shapes along the reported normal is
/// the reported depth (minus the distance) to rounding. The stages place normals from GJK's
/// v, EPA's faces, closest points or projections, which on a curved side are off by about
/// sqrt(rounding / curvature): 3e-8 rad in double, the distance then 2e-9 of the size from
/// the gap along the normal. Kept when the refinement settled near the stage's answer (see
/// below), converged or not: its support distance is a bound the stage's normal gave no
/// better (an upper bound of a depth, a lower bound of a distance), and it is the overlap
/// along the normal it reports.
template <class A, class B>
void refine_to_precision(const A& a, const B& b, PairSetup<A, B>& setup, const PairRequest& request, LocalAnswer& ans) {
  if constexpr (kCurvedCorePair<A, B>) {
    if (ans.stage == GenericStage::NotRun || ans.status == PairStatus::Degenerate ||
        ans.status == PairStatus::MaxIterations)
      return;
    const epa::Refinement f = epa::refine(setup.support_a, setup.support_b, ans.normal, setup.scale,
                                          std::clamp(request.max_iterations, 1, 96));
    ans.iterations += f.iterations;
    const Real sd = -(f.depth + setup.radius_a + setup.radius_b);
    // A polish, not another minimum: within sqrt(eps) of the size of the stage's answer.
    // Near the contact threshold, beyond half the boolean query's band of it (boolean_band:
    // intersect trusts GJK outside it, so a larger move would split the touching rule) only
    // for a gap whose refined witnesses meet the line along its normal (a point of each shape
    // with a - b = h n: the distance both ways); a refinement stopped on a kink of a box
    // against a cone's rim had moved a touching pair 1e-8 deep. Where both answers lie on
    // the same side of the threshold beyond the band, no query's decision can change, and
    // the refined answer is the overlap along its own normal (a box 0.04 deep in a cylinder:
    // EPA's lower bound 5e-11 short, the refinement, stopped on a kink, 6e-13 over).
    const Real moved = std::abs(sd - ans.signed_distance);
    const bool met = f.witness_gap <= setup.tolerance;
    const bool certified = met && sd > Real(0) && ans.signed_distance > Real(0);
    const Real reach = contact_reach(request.contact_distance, setup.tolerance);
    const Real band = boolean_band(setup.tolerance);
    const bool clear = (sd > reach + band && ans.signed_distance > reach + band) ||
                       (sd < reach - band && ans.signed_distance < reach - band);
    if (!(moved <= kSqrtEpsilon * setup.scale) || (!certified && !clear && !(moved <= Real(0.5) * band))) return;
    // The refinement's witnesses where its feature search met the line along the normal;
    // else (a cap's disc, whose rim the tangent-plane search approaches linearly) a partner
    // pair placed along the refined normal (refined_partners).
    Vec3 point_a = f.support_a + setup.radius_a * f.normal;
    if (!met && !refined_partners(a, b, setup, ans.point_a, sd, f.normal, point_a)) return;
    ans.point_a = point_a;
    ans.signed_distance = sd;
    ans.normal = f.normal;
    ans.point_b = point_a + sd * f.normal;
    ans.status = status_from_distance(sd, setup.tolerance);
  } else {
    (void)a;
    (void)b;
    (void)setup;
    (void)request;
    (void)ans;
  }
}

/// The ladder: its stages, then the refinement to precision of a curved pair's answer.
template <class A, class B>
LocalAnswer climb_ladder(const A& a, const B& b, PairSetup<A, B>& setup, const PairRequest& request) {
  LocalAnswer ans = run_stages(a, b, setup, request);
  refine_to_precision(a, b, setup, request, ans);
  return ans;
}

/// The ladder's answer; where its witnesses stay off point_b = point_a + d n beyond the
/// tolerance after a Nesterov GJK run, the ladder again from plain GJK, whose answer is kept
/// when it is closer to the relation (the momentum can leave EPA a start it converges from
/// slowly: a disc 0.1 thick pierced by a needle cone, witnesses 0.038 off after 135
/// iterations; 1e-4 off after 22 from plain GJK's simplex).
template <class A, class B>
LocalAnswer solve(const A& a, const B& b, PairSetup<A, B>& setup, const PairRequest& request) {
  const LocalAnswer first = climb_ladder(a, b, setup, request);
  if (request.gjk == gjk::Variant::Plain || !(relation_gap(first) > setup.tolerance)) return first;
  PairRequest plain = request;
  plain.gjk = gjk::Variant::Plain;
  LocalAnswer again = climb_ladder(a, b, setup, plain);
  again.iterations += first.iterations;
  return relation_gap(again) < relation_gap(first) ? again : first;
}

/// generic_distance's body: writes the world-frame answer into `r` and returns the stage
/// that gave it.
template <class A, class B>
GenericStage distance_into(const A& a, const Transform& pose_a, const B& b, const Transform& pose_b,
                           const PairRequest& request, PairCache* cache, DistanceResult& r) {
  static_assert(!std::is_same_v<A, HalfSpace> && !std::is_same_v<B, HalfSpace>,
                "half-space pairs are served by their closed-form routines");
  if (!poses_in_range(pose_a, pose_b)) {
    r = invalid_distance();
    return GenericStage::NotRun;
  }
  PairSetup<A, B> setup(a, pose_a, b, pose_b, request, cache);
  const LocalAnswer ans = solve(a, b, setup, request);
  setup.store(cache, ans.normal);
  if (cache && ans.sat_used) cache->sat_feature = ans.sat_feature;
  r.signed_distance = ans.signed_distance;
  r.point_a = pose_a.apply(ans.point_a);
  r.point_b = pose_a.apply(ans.point_b);
  r.normal = pose_a.apply_vector(ans.normal);
  r.status = ans.status;
  r.method = ans.method;
  r.iterations = ans.iterations;
  r.tolerance = setup.tolerance;
  return ans.stage;
}

}  // namespace generic_detail

/// Signed distance of any convex pair by GJK / EPA / SAT (see the file comment). A and B in
/// their local frames with world poses; results in the world frame (contact.hpp). Callable on
/// pairs that also have a closed-form routine (tests compare the two).
template <class A, class B>
DistanceResult generic_distance(const A& a, const Transform& pose_a, const B& b, const Transform& pose_b,
                                const PairRequest& request, PairCache* cache) {
  DistanceResult r;
  generic_detail::distance_into(a, pose_a, b, pose_b, request, cache, r);
  return r;
}

/// A generic distance with the stage of the ladder that gave it.
struct StagedDistance {
  DistanceResult result;                      ///< as generic_distance returns it
  GenericStage stage = GenericStage::NotRun;  ///< the stage that answered
};

/// generic_distance with the stage of the ladder that answered (tests, diagnostics).
template <class A, class B>
StagedDistance generic_distance_staged(const A& a, const Transform& pose_a, const B& b, const Transform& pose_b,
                                       const PairRequest& request, PairCache* cache) {
  StagedDistance staged;
  staged.stage = generic_detail::distance_into(a, pose_a, b, pose_b, request, cache, staged.result);
  return staged;
}

/// True when A and B are in contact under the touching rule (contact.hpp: within
/// max(request.contact_distance, tolerance)): GJK in boolean mode against the reach widened
/// by a rounding band (boolean_band), stopping at the first separating axis or the first
/// proof of contact. An overlap counts as proven when the origin lies deeper than the band
/// inside GJK's final tetrahedron (enclosed_depth); a core distance in the band, or an
/// overlap that shallow, is decided by the distance query itself, so that intersect and
/// distance never disagree.
template <class A, class B>
bool generic_intersect(const A& a, const Transform& pose_a, const B& b, const Transform& pose_b,
                       const PairRequest& request, PairCache* cache) {
  static_assert(!std::is_same_v<A, HalfSpace> && !std::is_same_v<B, HalfSpace>,
                "half-space pairs are served by their closed-form routines");
  if (!poses_in_range(pose_a, pose_b)) return false;
  generic_detail::PairSetup<A, B> setup(a, pose_a, b, pose_b, request, cache);
  gjk::Settings s = setup.gjk_settings(request);
  const Real reach = setup.radius_a + setup.radius_b + contact_reach(request.contact_distance, setup.tolerance);
  const Real band = generic_detail::boolean_band(setup.tolerance);
  s.margin = reach + band;
  const gjk::Outcome g = gjk::distance(setup.support_a, setup.support_b, setup.axis, s);
  if (cache) {
    // A proven separating axis is the best start for the next, coherent query.
    const Vec3 n = g.status == gjk::Status::EarlyExit ? generic_detail::unit_or(g.separating_axis, -g.v)
                                                      : generic_detail::unit_or(-g.v, setup.axis);
    setup.store(cache, n);
  }
  if (g.status == gjk::Status::EarlyExit) return false;
  if (g.status == gjk::Status::Overlapping) {
    if (generic_detail::enclosed_depth(g.simplex) > band) return true;
  } else if (g.status != gjk::Status::MaxIterations && g.distance < reach - band) {
    return true;
  }
  return in_contact(generic_distance(a, pose_a, b, pose_b, request, nullptr), request);
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
