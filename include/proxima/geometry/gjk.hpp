#pragma once
/// @file gjk.hpp
/// GJK distance between two convex sets given by support functions expressed in one common
/// frame (in the narrow phase: A's local frame, with B's support mapped into it once per pair).
///
/// Steps (Gilbert, Johnson, Keerthi, IEEE J. Robotics and Automation 1988):
///   1. w0 = s_A(d) - s_B(-d) for an initial direction d (warm-start axis or a guess);
///      -d.w0/|d| is already a lower bound of the distance (boolean mode may stop here);
///   2. repeat: w = s_A(-v) - s_B(v) for the current closest point v of the Minkowski
///      difference D = A - B; stop when the duality gap |v|^2 - v.w is small (relative or
///      absolute), when w adds nothing, when |v| stops decreasing, or at the cap;
///   3. add w to the simplex and reduce it to the smallest sub-simplex holding the point of
///      its hull nearest the origin, by signed volumes (Montanari, Petrinic, Barbieri,
///      "Improving the GJK algorithm for faster and more reliable distance queries between
///      convex objects", ACM TOG 2017): barycentric coordinates are ratios of signed
///      volumes / areas / lengths over the largest projection, so no tiny determinant is
///      ever divided by; a degenerate simplex falls back to its faces; the weights are the
///      signed measures over their own sum, so they sum to 1 to rounding on slivers too;
///   4. a full tetrahedron holding the origin means the sets overlap (EPA takes over).
/// The Nesterov variant (Montaut, Le Lidec, Petrik, Sivic, Carpentier, "Collision detection
/// accelerated: an optimization perspective", RSS 2022) queries the support along the
/// heading d = delta d_last + (1 - delta) y, y = delta v + (1 - delta) w_last,
/// delta = (k+1)/(k+3); when the gap test passes or the support repeats under momentum, it
/// drops momentum and continues as plain GJK (their restart rule), so its answer is the
/// plain one's. It also drops momentum that does not halve the gap |v| - lower within
/// kMomentumWindow steps: on overlapping sets the gap is |v| itself, and momentum was seen
/// creeping towards the origin by 1 % a step to the cap (two concentric ellipsoids answered
/// 0.006 apart at 128 iterations where plain GJK encloses the origin in 4).
///
/// Witnesses: the barycentric coordinates of v over the simplex applied to the support points
/// of A and of B that made each vertex. Everything is header-only and templated on the two
/// support functors: no virtual call, no allocation, no exception, never NaN.
///
/// Precision: the support points are Real, but in distance mode the simplex arithmetic (the
/// vertices w = a - b, v, the sub-simplex solves, the duality gap) runs in `Wide` = double.
/// v is a combination of vertices as far from the origin as the sets are large, so in float
/// its direction carries an error of about eps |w| / |v|: near contact (|v| under a
/// thousandth of the size) the support along -v then jumps between the ends of a ruled side
/// (a cylinder's or cone's generator), the simplex turns into a sliver and the iteration
/// stalls up to 1e-4 of the size above the distance. In Wide the direction follows the exact
/// points and GJK converges to the rounding of the supports, as the double build does (where
/// Real is Wide and nothing changes). Boolean mode (margin >= 0) stays in Real: its answer
/// is a comparison with the margin, and it is the broad phase's hot path (in Wide it cost 8 %
/// more instructions on the W2 hulls). So do polytope pairs when the caller says so
/// (Settings::wide; 6 % on the W2 hull distances): a finite vertex set ends the iteration on
/// a repeated vertex. Running distance mode in Real while |v| > |w| / 64 and in Wide below
/// was tried: the float phase still stalled (errors to 5e-5) and built other start
/// simplices for EPA, where the curved-shape witness cases failed again.

#include <proxima/core/math.hpp>
#include <proxima/core/tolerance.hpp>
#include <proxima/geometry/gjk_variant.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <type_traits>

namespace proxima::gjk {

/// The scalar of the simplex arithmetic (see the file comment): double in both builds.
using Wide = double;
/// A 3-vector of Wide.
using WideVec3 = glm::vec<3, Wide, glm::defaultp>;

/// A vertex of the Minkowski difference D = A - B with the support points that made it; `T`
/// is the scalar of w (Real for the simplex handed to EPA, Wide inside GJK).
template <class T>
struct BasicVertex {
  glm::vec<3, T, glm::defaultp> w{T(0)};  ///< a - b
  Vec3 a{Real(0)};                        ///< support point of A
  Vec3 b{Real(0)};                        ///< support point of B
};

/// Up to four vertices of D with the barycentric coordinates of the current closest point.
template <class T>
struct BasicSimplex {
  std::array<BasicVertex<T>, 4> v{};                ///< vertices, newest first
  std::array<T, 4> lambda{T(1), T(0), T(0), T(0)};  ///< weights (sum 1)
  int size = 0;                                     ///< number of vertices (0..4)
};

/// A vertex of D in Real (the form EPA takes).
using Vertex = BasicVertex<Real>;
/// GJK's final simplex in Real (the form EPA takes).
using Simplex = BasicSimplex<Real>;
/// The simplex GJK iterates on.
using WideSimplex = BasicSimplex<Wide>;

/// How GJK stopped.
enum class Status : std::uint8_t {
  Separated,      ///< converged: the sets are apart by `distance` (within the tolerances)
  Overlapping,    ///< the origin is in D (within the overlap tolerance): distance 0
  MaxIterations,  ///< iteration cap: `distance` is an upper bound, witnesses exact for it
  EarlyExit,      ///< boolean mode: a separating axis proves distance > margin
};

/// Options of one GJK run.
struct Settings {
  int max_iterations = 128;                 ///< iteration cap
  Real abs_tolerance = Real(0);             ///< stop when upper - lower distance bound <= this (length)
  Real rel_tolerance = Real(4) * kEpsilon;  ///< ... or <= this times the distance
  /// Boolean mode: when >= 0, stop as soon as distance > margin is proven (EarlyExit) or
  /// distance <= margin is proven (Overlapping-or-Separated with distance <= margin).
  Real margin = Real(-1);
  Variant variant = Variant::Plain;  ///< plain or Nesterov-accelerated iteration (gjk_variant.hpp)
  /// Distance mode: the simplex arithmetic in Wide (see the file comment). Off, it runs in
  /// Real, which suffices for polytopes: their finite vertex sets end the iteration on a
  /// repeated vertex, where a curved side offers a new point along every rounded direction.
  bool wide = true;
};

/// What gjk::distance found: how it stopped, the distance, witnesses and final simplex.
struct Outcome {
  Status status = Status::Separated;  ///< how the iteration stopped (the meaning of the fields below)
  Real distance = Real(0);            ///< |v|: distance between the sets (0 when overlapping)
  Vec3 v{Real(0)};                    ///< closest point of D to the origin: point_a - point_b
  Vec3 point_a{Real(0)};              ///< witness on A (common frame)
  Vec3 point_b{Real(0)};              ///< witness on B (common frame)
  Simplex simplex;                    ///< final simplex (EPA starts from it)
  Real lower_bound = Real(0);         ///< proven lower bound on the distance
  /// EarlyExit: the direction u (A to B, not unit) whose supporting plane of D proves the
  /// distance above the margin (support of D along u below -margin |u|); zero otherwise.
  Vec3 separating_axis{Real(0)};
  int iterations = 0;  ///< iterations of the main loop (at most Settings::max_iterations)
};

namespace detail {

/// Iterations over which Nesterov's momentum must halve the duality gap to be kept.
inline constexpr int kMomentumWindow = 8;

template <class T>
bool same_sign(T a, T b) {
  return (a > T(0) && b > T(0)) || (a < T(0) && b < T(0));
}

/// Closest point of segment (s[0], s[1]) to the origin, by the signed-length rule. Writes
/// the kept vertices (in order) into out and their weights; returns |v|^2.
template <class T>
T solve_1d(const BasicVertex<T>& s0, const BasicVertex<T>& s1, BasicSimplex<T>& out) {
  using V3 = glm::vec<3, T, glm::defaultp>;
  const V3 t = s1.w - s0.w;
  const T tt = glm::dot(t, t);
  if (!(tt > T(0))) {
    out.v[0] = s0;
    out.lambda[0] = T(1);
    out.size = 1;
    return glm::dot(s0.w, s0.w);
  }
  // Projection of the origin on the line, then 1-D barycentrics along the largest axis.
  const V3 p0 = s0.w - t * (glm::dot(s0.w, t) / tt);
  int axis = 0;
  if (std::abs(t.y) > std::abs(t[axis])) axis = 1;
  if (std::abs(t.z) > std::abs(t[axis])) axis = 2;
  const T mu = s0.w[axis] - s1.w[axis];
  const T c0 = p0[axis] - s1.w[axis];  // weight of s0 times mu
  const T c1 = s0.w[axis] - p0[axis];  // weight of s1 times mu
  if (same_sign(mu, c0) && same_sign(mu, c1)) {
    // Divided by their own sum (mu in exact arithmetic), so that the weights sum to 1 to
    // rounding: v is then a convex combination of the vertices, |v| a true upper bound.
    const T sum = c0 + c1;
    out.v[0] = s0;
    out.v[1] = s1;
    out.lambda[0] = c0 / sum;
    out.lambda[1] = c1 / sum;
    out.size = 2;
    const V3 v = out.lambda[0] * s0.w + out.lambda[1] * s1.w;
    return glm::dot(v, v);
  }
  // The origin's projection lies beyond one end: the nearer end is the answer.
  const T d0 = glm::dot(s0.w, s0.w);
  const T d1 = glm::dot(s1.w, s1.w);
  const BasicVertex<T>& best = d0 <= d1 ? s0 : s1;
  out.v[0] = best;
  out.lambda[0] = T(1);
  out.size = 1;
  return std::min(d0, d1);
}

/// Closest point of triangle (s0, s1, s2) to the origin by signed areas.
template <class T>
T solve_2d(const BasicVertex<T>& s0, const BasicVertex<T>& s1, const BasicVertex<T>& s2, BasicSimplex<T>& out) {
  using V3 = glm::vec<3, T, glm::defaultp>;
  constexpr T kEps = std::numeric_limits<T>::epsilon();
  const V3 n = glm::cross(s1.w - s0.w, s2.w - s0.w);
  const T nn = glm::dot(n, n);
  const T e2 = std::max(
      {glm::dot(s1.w - s0.w, s1.w - s0.w), glm::dot(s2.w - s0.w, s2.w - s0.w), glm::dot(s2.w - s1.w, s2.w - s1.w)});
  bool inside_possible = nn > kEps * kEps * e2 * e2 && nn > T(0);
  if (inside_possible) {
    const V3 p0 = n * (glm::dot(s0.w, n) / nn);
    int i = 0;
    if (std::abs(n.y) > std::abs(n[i])) i = 1;
    if (std::abs(n.z) > std::abs(n[i])) i = 2;
    const int j = (i + 1) % 3;
    const int k = (i + 2) % 3;
    const T mu = n[i];
    // Signed areas of the sub-triangles opposite each vertex, projected on the (j, k) plane:
    // area(a, b, c) = (b_j - a_j)(c_k - a_k) - (b_k - a_k)(c_j - a_j), written out because
    // GCC does not always inline a helper here (measured: 9.6e6 more instructions on W2).
    const V3& w0 = s0.w;
    const V3& w1 = s1.w;
    const V3& w2 = s2.w;
    const T c0 = (w1[j] - p0[j]) * (w2[k] - p0[k]) - (w1[k] - p0[k]) * (w2[j] - p0[j]);
    const T c1 = (p0[j] - w0[j]) * (w2[k] - w0[k]) - (p0[k] - w0[k]) * (w2[j] - w0[j]);
    const T c2 = (w1[j] - w0[j]) * (p0[k] - w0[k]) - (w1[k] - w0[k]) * (p0[j] - w0[j]);
    const bool in0 = same_sign(mu, c0);
    const bool in1 = same_sign(mu, c1);
    const bool in2 = same_sign(mu, c2);
    if (in0 && in1 && in2) {
      // Divided by their own sum, not by mu: on a sliver (two vertices close together) the
      // areas about p0 and the cross product round differently, and weights over mu were
      // seen to sum to 1 - 7e-10, putting v off the simplex and |v| below the distance.
      const T sum = c0 + c1 + c2;
      out.v[0] = s0;
      out.v[1] = s1;
      out.v[2] = s2;
      out.lambda[0] = c0 / sum;
      out.lambda[1] = c1 / sum;
      out.lambda[2] = c2 / sum;
      out.size = 3;
      const V3 v = out.lambda[0] * s0.w + out.lambda[1] * s1.w + out.lambda[2] * s2.w;
      return glm::dot(v, v);
    }
    T best = std::numeric_limits<T>::infinity();
    BasicSimplex<T> tmp;
    if (!in0) {
      const T d = solve_1d(s1, s2, tmp);
      if (d < best) best = d, out = tmp;
    }
    if (!in1) {
      const T d = solve_1d(s0, s2, tmp);
      if (d < best) best = d, out = tmp;
    }
    if (!in2) {
      const T d = solve_1d(s0, s1, tmp);
      if (d < best) best = d, out = tmp;
    }
    return best;
  }
  // Degenerate (collinear) triangle: the nearest of its edges.
  T best = std::numeric_limits<T>::infinity();
  BasicSimplex<T> tmp;
  T d = solve_1d(s0, s1, tmp);
  if (d < best) best = d, out = tmp;
  d = solve_1d(s0, s2, tmp);
  if (d < best) best = d, out = tmp;
  d = solve_1d(s1, s2, tmp);
  if (d < best) best = d, out = tmp;
  return best;
}

/// Closest point of tetrahedron (s0..s3) to the origin by signed volumes. Returns |v|^2; a
/// result of size 4 means the origin is inside.
template <class T>
T solve_3d(const BasicVertex<T>& s0, const BasicVertex<T>& s1, const BasicVertex<T>& s2, const BasicVertex<T>& s3,
           BasicSimplex<T>& out) {
  using V3 = glm::vec<3, T, glm::defaultp>;
  constexpr T kEps = std::numeric_limits<T>::epsilon();
  const auto vol = [](const V3& a, const V3& b, const V3& c, const V3& d) {
    return glm::dot(b - a, glm::cross(c - a, d - a));
  };
  const V3 o(T(0));
  const T c0 = vol(o, s1.w, s2.w, s3.w);
  const T c1 = vol(s0.w, o, s2.w, s3.w);
  const T c2 = vol(s0.w, s1.w, o, s3.w);
  const T c3 = vol(s0.w, s1.w, s2.w, o);
  const T det = c0 + c1 + c2 + c3;
  const T e = std::max({glm::length(s1.w - s0.w), glm::length(s2.w - s0.w), glm::length(s3.w - s0.w)});
  const bool proper = std::abs(det) > T(8) * kEps * e * e * e && det != T(0);
  const bool in0 = proper && same_sign(det, c0);
  const bool in1 = proper && same_sign(det, c1);
  const bool in2 = proper && same_sign(det, c2);
  const bool in3 = proper && same_sign(det, c3);
  if (in0 && in1 && in2 && in3) {
    out.v = {s0, s1, s2, s3};
    out.lambda = {c0 / det, c1 / det, c2 / det, c3 / det};
    out.size = 4;
    return T(0);
  }
  T best = std::numeric_limits<T>::infinity();
  BasicSimplex<T> tmp;
  if (!in0) {
    const T d = solve_2d(s1, s2, s3, tmp);
    if (d < best) best = d, out = tmp;
  }
  if (!in1) {
    const T d = solve_2d(s0, s2, s3, tmp);
    if (d < best) best = d, out = tmp;
  }
  if (!in2) {
    const T d = solve_2d(s0, s1, s3, tmp);
    if (d < best) best = d, out = tmp;
  }
  if (!in3) {
    const T d = solve_2d(s0, s1, s2, tmp);
    if (d < best) best = d, out = tmp;
  }
  return best;
}

/// Reduces `s` (newest vertex first) to the sub-simplex nearest the origin; returns |v|^2.
template <class T>
T reduce(BasicSimplex<T>& s) {
  BasicSimplex<T> out;
  T d = T(0);
  switch (s.size) {
    case 1: s.lambda[0] = T(1); return glm::dot(s.v[0].w, s.v[0].w);
    case 2: d = solve_1d(s.v[0], s.v[1], out); break;
    case 3: d = solve_2d(s.v[0], s.v[1], s.v[2], out); break;
    default: d = solve_3d(s.v[0], s.v[1], s.v[2], s.v[3], out); break;
  }
  s = out;
  return d;
}

}  // namespace detail

/// The point of the simplex weighted by its barycentric coordinates (component `which`:
/// 0 = w, 1 = a, 2 = b), in the simplex's scalar.
template <class T>
glm::vec<3, T, glm::defaultp> combine(const BasicSimplex<T>& s, int which) {
  glm::vec<3, T, glm::defaultp> r(T(0));
  for (int i = 0; i < s.size; ++i) {
    const glm::vec<3, T, glm::defaultp> p =
        which == 0 ? s.v[i].w : glm::vec<3, T, glm::defaultp>(which == 1 ? s.v[i].a : s.v[i].b);
    r += s.lambda[i] * p;
  }
  return r;
}

/// The simplex in Real (w rounded: a - b as Real arithmetic gives it).
template <class T>
Simplex narrowed(const BasicSimplex<T>& s) {
  Simplex r;
  r.size = s.size;
  for (std::size_t i = 0; i < 4; ++i) {
    r.v[i].w = Vec3(s.v[i].w);
    r.v[i].a = s.v[i].a;
    r.v[i].b = s.v[i].b;
    r.lambda[i] = Real(s.lambda[i]);
  }
  return r;
}

namespace detail {

/// Steps 1-4 in scalar T, and the answer in Real. One function with the state in locals,
/// as GCC keeps it in registers (split over a state struct, the boolean queries cost 5 %
/// more instructions).
template <class T, class SupportA, class SupportB>
Outcome run(SupportA& support_a, SupportB& support_b, const Vec3& initial_direction, const Settings& settings) {
  using V3 = glm::vec<3, T, glm::defaultp>;
  const auto make_vertex = [&](const V3& d) {  // support of D = A - B in direction d
    BasicVertex<T> x;
    const Vec3 dr(d);
    x.a = support_a(dr);
    x.b = support_b(-dr);
    x.w = V3(x.a) - V3(x.b);  // in Wide: exact, the difference of two Reals
    return x;
  };
  // The supports' own rounding (Real) sets the noise level.
  const T eps = T(kEpsilon);
  const T margin = T(settings.margin);
  Outcome r;
  V3 d0(initial_direction);
  if (!(glm::dot(d0, d0) > T(0))) d0 = V3(T(1), T(0), T(0));
  // In Real the simplex is built in place in the answer, as before; in Wide, beside it.
  BasicSimplex<T> wide_simplex;
  BasicSimplex<T>& s = [&]() -> BasicSimplex<T>& {
    if constexpr (std::is_same_v<T, Real>)
      return r.simplex;
    else
      return wide_simplex;
  }();
  s.v[0] = make_vertex(d0);
  s.lambda[0] = T(1);
  s.size = 1;
  V3 v = s.v[0].w;
  T vv = glm::dot(v, v);
  T scale2 = vv;  // largest |w|^2 seen: the noise level of the dot products
  // The first vertex is the support of D along d0: its plane bounds the distance below
  // already, so a good axis (the cached separating axis of a coherent pair, or the line
  // between the centres) ends a boolean query after one pair of support calls.
  T lower = std::max(-glm::dot(d0, s.v[0].w) / std::sqrt(glm::dot(d0, d0)), T(0));
  if (margin >= T(0) && lower > margin) {
    r.status = Status::EarlyExit;
    if constexpr (!std::is_same_v<T, Real>) r.simplex = narrowed(s);
    r.v = Vec3(v);
    r.distance = Real(std::sqrt(vv));
    r.point_a = s.v[0].a;
    r.point_b = s.v[0].b;
    r.lower_bound = std::min(Real(lower), r.distance);
    r.separating_axis = Vec3(d0);
    return r;
  }
  Status status = Status::MaxIterations;
  BasicVertex<T> last = s.v[0];
  bool momentum = settings.variant == Variant::Nesterov;
  V3 heading = v;       // the momentum's accumulated search direction
  T checkpoint = T(0);  // the gap |v| - lower when the momentum's window began
  V3 separating(T(0));
  int k = 0;
  for (; k < settings.max_iterations; ++k) {
    // Overlap: v is at the origin within the rounding of the vertices.
    if (vv <= T(64) * eps * eps * scale2 || !(vv > T(0))) {
      status = Status::Overlapping;
      break;
    }
    if (margin >= T(0) && vv <= margin * margin) {
      status = Status::Separated;  // distance <= margin proven by the upper bound |v|
      break;
    }
    V3 dir = v;
    if (momentum) {
      const T delta = T(k + 1) / T(k + 3);
      const V3 y = delta * v + (T(1) - delta) * last.w;
      heading = k == 0 ? y : delta * heading + (T(1) - delta) * y;
      dir = heading;
    }
    if (!(glm::dot(dir, dir) > T(0))) dir = v;
    const BasicVertex<T> w = make_vertex(-dir);
    const T vw = glm::dot(v, w.w);
    scale2 = std::max(scale2, glm::dot(w.w, w.w));
    const T vn = std::sqrt(vv);
    // Lower bound from the supporting plane of D along v (valid only for dir = v; with
    // momentum, any direction gives a valid bound dir.w/|dir|).
    const T dn = std::sqrt(glm::dot(dir, dir));
    const T lb = glm::dot(dir, w.w) / dn;
    if (lb > lower) lower = lb;
    if (margin >= T(0) && lower > margin) {
      status = Status::EarlyExit;
      separating = -dir;
      break;
    }
    // Duality gap of v: |v| - v.w/|v| (only meaningful with the support at -v).
    const T gap_tol = std::max(T(settings.abs_tolerance), T(settings.rel_tolerance) * vn);
    const T noise = T(8) * eps * std::sqrt(scale2);
    bool repeated = false;
    for (int i = 0; i < s.size; ++i)
      if (s.v[i].w == w.w) repeated = true;
    if (momentum) {
      const T gap_m = vn - lower;
      // Momentum must halve the gap every kMomentumWindow steps: on overlapping sets (lower
      // stays 0) it can creep towards the origin by a percent a step for ever.
      bool stalled = false;
      if (k % kMomentumWindow == 0) {
        stalled = k > 0 && gap_m > T(0.5) * checkpoint;
        checkpoint = gap_m;
      }
      if (repeated || stalled || gap_m <= std::max(gap_tol, noise)) {
        momentum = false;  // restart: finish with plain steps and the true duality gap
        continue;
      }
    } else {
      if (vn - vw / vn <= std::max(gap_tol, noise) || repeated) {
        status = Status::Separated;
        break;
      }
    }
    last = w;
    const BasicSimplex<T> previous = s;
    // Newest first.
    for (int i = s.size; i > 0; --i) s.v[i] = s.v[i - 1];
    s.v[0] = w;
    ++s.size;
    const T nvv = reduce(s);
    if (s.size == 4) {
      vv = T(0);
      v = V3(T(0));
      status = Status::Overlapping;
      ++k;
      break;
    }
    if (!(nvv < vv)) {
      // No progress (rounding): keep the previous simplex, whose v is as good.
      if (!momentum) {
        s = previous;
        status = Status::Separated;
        ++k;
        break;
      }
      momentum = false;
    }
    vv = nvv;
    v = combine(s, 0);
  }
  r.iterations = k;
  r.status = status;
  if constexpr (!std::is_same_v<T, Real>) r.simplex = narrowed(s);
  if (status == Status::EarlyExit) r.separating_axis = Vec3(separating);
  if (status == Status::Overlapping) {
    r.distance = Real(0);
    r.v = Vec3(Real(0));
    r.point_a = Vec3(combine(s, 1));
    r.point_b = Vec3(combine(s, 2));
    r.lower_bound = Real(0);
    return r;
  }
  const V3 vf = combine(s, 0);
  r.v = Vec3(vf);
  r.distance = Real(std::sqrt(glm::dot(vf, vf)));
  r.point_a = Vec3(combine(s, 1));
  r.point_b = Vec3(combine(s, 2));
  r.lower_bound = std::min(Real(std::max(lower, T(0))), r.distance);
  return r;
}

}  // namespace detail

/// Distance between convex sets A and B given their support functors in a common frame:
/// `support_a(d)` and `support_b(d)` return a farthest point in direction d (any non-zero
/// vector, not necessarily unit). `initial_direction` is a guess of the direction from A to
/// B (any non-zero vector; the warm-start axis). O(iterations x support cost).
template <class SupportA, class SupportB>
Outcome distance(SupportA& support_a, SupportB& support_b, const Vec3& initial_direction, const Settings& settings) {
  // Boolean mode decides distance <= margin within the tolerance: Real suffices, and it is
  // the hot path of the broad phase's pairs. Distances run in Wide unless the caller knows
  // both sets are polytopes (see the file comment).
  if (settings.margin >= Real(0) || !settings.wide)
    return detail::run<Real>(support_a, support_b, initial_direction, settings);
  return detail::run<Wide>(support_a, support_b, initial_direction, settings);
}

}  // namespace proxima::gjk
