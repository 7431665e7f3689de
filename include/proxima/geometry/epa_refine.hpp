#pragma once
/// @file epa_refine.hpp
/// Refinement of a penetration normal on the support function of D = A - B. The depth of
/// overlapping convex sets is the minimum over unit n of h(n) = n . s_D(n) (the distance from
/// the origin to D's boundary; van den Bergen, Collision Detection in Interactive 3D
/// Environments, 2004), a smooth function of n where D is strictly convex: its gradient on
/// the sphere is the part of s_D(n) across n and its Hessian the support map's Jacobian
/// minus h(n). EPA (epa.hpp) converges only linearly on curved supports; a few Newton steps
/// on h from EPA's normal reach the precision's accuracy.
///
/// Steps:
///   1. at the current n: a tangent basis (Duff et al., "Building an orthonormal basis,
///      revisited", JCGT 2017), the gradient of h, and its Hessian by forward differences of
///      the support (two more support queries); a gradient within rounding is a minimum;
///   2. a trust-region step (Nocedal, Wright, Numerical Optimization, 2006, ch. 4): the
///      Newton step on the Hessian shifted to positive definite (Levenberg-Marquardt),
///      clipped to the radius; after a failed Newton step, a plain gradient step;
///   3. keep the trial normal when it lowers h beyond rounding (then widen the radius), or,
///      within rounding of h, when it halves h's slope (near the minimum h's change is lost
///      to rounding before the normal is exact); else try the gradient, then shrink the
///      radius; stop at a slope within rounding, at a Newton step that predicts no gain and
///      cuts no slope, or when no step within reach can gain more than a settle threshold (a
///      kink of h, where D has an edge or a ruled side). A Newton step near the minimum that
///      fails both tests has its Hessian estimated again with differences 16 times closer
///      (down to eta / 256: the differences had crossed a crease);
///   3a. a descent that stops with the slope above rounding looks for the slope's zero along
///      the gradient's great circle (slope_search: regula falsi on the slope, which needs no
///      difference of h), and goes on from there;
///   3b. where it settled on a crease of h (D's support along n an edge of direction e that
///      the line along n misses: the descent's steps across the crease zigzag and shrink to
///      the settle threshold short of the minimum), the minimum along the crease: on the
///      great circle of normals across e, h is smooth and its slope is the tangent's dot
///      with D's support; doubling steps bracket the slope's sign change and bisection
///      closes it; then the descent goes on (at most four such rounds). Seen on a small
///      tetrahedron inside a sphere of radius 17: settled 0.0056 deeper than the minimum.
///      Also after a descent that ran out of steps zigzagging along a crease, the edge then
///      looked for with a wider tip (a segment in a sphere of radius 20: stopped 3.3e-8 off
///      the crease, beyond sqrt(eps)), and failing that across the crease, by the jump of a
///      side's support between normals tipped 1e-3 both ways (a tetrahedron 0.5 across in an
///      ellipsoid of radius 13.7: the minimum 4 degrees along the crease, the descent 0.0014
///      above it after 96 steps in double; in float settled by rounding 8e-4 above it, its
///      witnesses 0.075 off the line along n);
///   3c. where one side's support along the settled n is a face (three of its feature points
///      not collinear: a box's face, a cylinder's cap), that face's normal from those points,
///      the exact minimum of that kink of h, when h there is no higher (snap_to_face);
///   4. witnesses: where D's support along n is a face or an edge, a small GJK in the plane
///      across n (Gilbert, Johnson, Keerthi, IEEE J. Robotics and Automation 1988) over
///      supports tipped by sqrt(eps) finds the feature's point nearest the line along n; its
///      convex weights give points of A and B, moved to obey support_a - support_b = depth n.
/// No kept step raises h beyond rounding, so the answer is an upper bound of the depth no
/// worse than the start. Header-only, templated on the support functors: no virtual call, no
/// allocation, never NaN (a start of zero length uses +z). O(max_steps x 3 support queries).

#include <proxima/core/math.hpp>
#include <proxima/core/tolerance.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>

namespace proxima::epa {

/// What epa::refine found.
struct Refinement {
  bool improved = false;                   ///< a normal with a smaller support distance than the start was found
  bool converged = false;                  ///< the last Newton step changed the support distance by rounding only
  Real depth = Real(0);                    ///< support distance of D along `normal`: an upper bound of the depth
  Vec3 normal{Real(0), Real(0), Real(1)};  ///< unit, from A to B
  Vec3 support_a{Real(0)};                 ///< witness on A: support points of A along normal (tipped), combined
  Vec3 support_b{Real(0)};     ///< witness on B: the same for B along -normal; support_a - support_b = depth normal
  Vec3 tangential{Real(0)};    ///< D's support along normal minus depth * normal: 0 at a smooth minimum
  Real witness_gap = Real(0);  ///< distance of the combined witnesses from the exact relation before it was enforced
  int iterations = 0;          ///< support-pair queries made
};

namespace refine_detail {

/// v scaled to unit length (v non-zero).
inline Vec3 unit(const Vec3& v) { return v / std::sqrt(glm::dot(v, v)); }

/// v scaled to unit length, or +z when v is zero or not finite.
inline Vec3 unit_or_z(const Vec3& v) {
  const Real l2 = glm::dot(v, v);
  return l2 > Real(0) && std::isfinite(l2) ? v / std::sqrt(l2) : Vec3(Real(0), Real(0), Real(1));
}

/// Two unit vectors that complete unit n to an orthonormal basis (Duff et al. 2017).
struct TangentBasis {
  Vec3 t1;  ///< first tangent
  Vec3 t2;  ///< second tangent
};

/// The tangent basis of unit n, continuous except across n.z = 0 from below.
inline TangentBasis tangent_basis(const Vec3& n) {
  const Real sign = std::copysign(Real(1), n.z);
  const Real q = Real(-1) / (sign + n.z);
  const Real m = n.x * n.y * q;
  return {Vec3(Real(1) + sign * n.x * n.x * q, sign * m, -sign * n.x), Vec3(m, sign + n.y * n.y * q, -n.y)};
}

/// A normal with D's support along it: the point of the descent.
struct SupportSample {
  Vec3 n;  ///< unit normal
  Vec3 a;  ///< support point of A along n
  Vec3 b;  ///< support point of B along -n
  Vec3 p;  ///< a - b: D's support along n
  Real h;  ///< n . p: the support distance
};

/// D's support along unit n.
template <class SupportA, class SupportB>
SupportSample sample(SupportA& support_a, SupportB& support_b, const Vec3& n) {
  const Vec3 a = support_a(n);
  const Vec3 b = support_b(-n);
  const Vec3 p = a - b;
  return {n, a, b, p, glm::dot(n, p)};
}

/// Quadratic model of h at a sample, in the tangent plane (coordinates along t1, t2).
struct TangentModel {
  TangentBasis basis{Vec3(Real(0)), Vec3(Real(0))};  ///< the plane's axes
  Real g1 = Real(0);                                 ///< gradient along t1
  Real g2 = Real(0);                                 ///< gradient along t2
  Real h11 = Real(0);                                ///< Hessian
  Real h12 = Real(0);                                ///< ...
  Real h22 = Real(0);                                ///< ...
};

/// The tolerances of one refinement, proportional to the size of the problem.
struct RefineTolerances {
  Real scale;   ///< size of the problem (> 0)
  Real eta;     ///< forward-difference step (radians): truncation ~eta against rounding ~eps/eta
  Real flat;    ///< a change of h within rounding
  Real settle;  ///< least gain worth a step: below it, a shrinking radius stops
};

/// The tolerances for a problem of size `length_scale`.
inline RefineTolerances refine_tolerances(Real length_scale) {
  const Real scale = std::max(length_scale, std::numeric_limits<Real>::min());
  return {scale, Real(4) * std::cbrt(kEpsilon), Real(8) * kEpsilon * scale,
          std::sqrt(kEpsilon) * std::sqrt(std::sqrt(kEpsilon)) * scale};
}

/// Step 1a: tangent basis and gradient of h at `at`.
inline TangentModel gradient_at(const SupportSample& at) {
  TangentModel m;
  m.basis = tangent_basis(at.n);
  m.g1 = glm::dot(m.basis.t1, at.p);
  m.g2 = glm::dot(m.basis.t2, at.p);
  return m;
}

/// Step 1b: the Hessian of h at `at` by forward differences along the tangents (two support
/// pairs, counted in `queries`).
template <class SupportA, class SupportB>
void estimate_hessian(SupportA& support_a, SupportB& support_b, const SupportSample& at, Real eta, TangentModel& m,
                      int& queries) {
  const Vec3& t1 = m.basis.t1;
  const Vec3& t2 = m.basis.t2;
  const Vec3 n1 = unit(at.n + eta * t1);
  const Vec3 n2 = unit(at.n + eta * t2);
  const Vec3 p1 = support_a(n1) - support_b(-n1);
  const Vec3 p2 = support_a(n2) - support_b(-n2);
  queries += 2;
  m.h11 = glm::dot(t1, p1 - at.p) / eta - at.h;
  m.h22 = glm::dot(t2, p2 - at.p) / eta - at.h;
  m.h12 = Real(0.5) * (glm::dot(t2, p1 - at.p) + glm::dot(t1, p2 - at.p)) / eta;
}

/// A step in the tangent plane.
struct TangentStep {
  Real d1;            ///< along t1 (radians)
  Real d2;            ///< along t2
  Real len;           ///< its length
  bool newton_exact;  ///< a full Newton step on a positive definite Hessian predicting no gain beyond rounding
};

/// Step 2: the Newton step of the model on its Hessian shifted to positive definite
/// (Levenberg-Marquardt), clipped to `radius`; a gradient step of length `radius` when
/// `steepest` or when the Newton step is zero or not finite.
inline TangentStep trust_region_step(const TangentModel& m, Real radius, bool steepest, Real flat) {
  const Real tr = Real(0.5) * (m.h11 + m.h22);
  const Real disc = std::sqrt(Real(0.25) * (m.h11 - m.h22) * (m.h11 - m.h22) + m.h12 * m.h12);
  const Real lambda_min = tr - disc;
  const Real floor = Real(1e-3) * std::max(std::abs(tr) + disc, flat);
  const Real mu = lambda_min < floor ? floor - lambda_min : Real(0);
  const Real k11 = m.h11 + mu;
  const Real k22 = m.h22 + mu;
  const Real det = k11 * k22 - m.h12 * m.h12;
  TangentStep s{Real(0), Real(0), Real(0), false};
  if (det > Real(0) && std::isfinite(det)) {
    s.d1 = -(k22 * m.g1 - m.h12 * m.g2) / det;
    s.d2 = -(k11 * m.g2 - m.h12 * m.g1) / det;
  }
  const Real gl = std::sqrt(m.g1 * m.g1 + m.g2 * m.g2);
  s.len = std::sqrt(s.d1 * s.d1 + s.d2 * s.d2);
  s.newton_exact = mu == Real(0) && s.len <= radius && Real(-0.5) * (m.g1 * s.d1 + m.g2 * s.d2) <= flat;
  if (steepest || !(s.len > Real(0)) || !std::isfinite(s.len)) {
    s.d1 = -m.g1 / gl * radius;
    s.d2 = -m.g2 / gl * radius;
    s.len = radius;
  } else if (s.len > radius) {
    s.d1 *= radius / s.len;
    s.d2 *= radius / s.len;
    s.len = radius;
  }
  return s;
}

/// State of the trust-region descent.
struct Descent {
  SupportSample at;          ///< the best normal so far
  TangentModel model;        ///< the model at `at` (valid when `fresh`)
  Real radius = Real(0.25);  ///< trust radius (radians)
  bool fresh = false;        ///< the model belongs to `at`
  Real eta = Real(0);        ///< the Hessian's difference step (radians; RefineTolerances::eta, or closer)
  bool steepest = false;     ///< the next trial is a gradient step (the Newton one failed)
  bool converged = false;    ///< stopped at a minimum (within rounding) or a settled kink
  int queries = 0;           ///< support-pair queries made
};

/// h's gradient at a sample: the part of D's support across the normal.
inline Vec3 across(const SupportSample& s) { return s.p - s.h * s.n; }

/// The length of h's gradient at a sample.
inline Real slope(const SupportSample& s) {
  const Vec3 g = across(s);
  return std::sqrt(glm::dot(g, g));
}

/// Step 3: takes the trial sample when it lowers h beyond rounding (a flat stretch of h
/// stays put), else falls back from Newton to gradient to a smaller radius. True when the
/// descent is done.
inline bool accept_or_shrink(Descent& d, const SupportSample& trial, const TangentStep& step,
                             const RefineTolerances& tol) {
  if (trial.h < d.at.h - tol.flat) {
    d.at = trial;
    d.fresh = false;
    d.steepest = false;
    d.eta = tol.eta;
    d.radius = std::min(Real(0.5), std::max(d.radius, Real(2) * step.len));
    return false;
  }
  // Near a smooth minimum h changes by rounding only (its error there is quadratic in the
  // normal's), while its slope still shows how far off the normal is: a step within rounding
  // of h that halves the slope is kept (in float the Hessian by differences over 0.02 rad is
  // good to about 40 %, and Newton's steps cut the slope by about 2.4). Stopping on h alone
  // left normals about sqrt(flat / curvature) off (3e-8 rad in double, 7e-4 in float).
  if (trial.h <= d.at.h + tol.flat && slope(trial) < Real(0.5) * slope(d.at)) {
    d.at = trial;
    d.fresh = false;
    d.steepest = false;
    d.eta = tol.eta;
    return false;
  }
  if ((step.newton_exact || trial.h <= d.at.h + tol.flat) && !d.steepest) {
    // A Newton step near the minimum (a full step predicting no gain, or one that left h
    // within rounding) that neither lowers h nor halves the slope: the Hessian's differences
    // may have crossed a crease within eta of the sample (a box edge 0.02 rad from a float
    // sample: the model 150 times too stiff along it; a cylinder's rim in an ellipsoid: the
    // model indefinite, its steps raising the slope ninefold, and the descent settled with
    // the normal 3.8e-5 rad off); again with the differences 16 times closer, down to
    // eta / 256.
    if (d.eta > tol.eta * Real(1.0 / 256.0)) {
      d.eta *= Real(1.0 / 16.0);
      d.fresh = false;
      return false;
    }
    if (step.newton_exact) {
      d.converged = true;
      return true;
    }
  }
  if (!d.steepest) {
    d.steepest = true;  // at a kink of h the Newton model misleads: try the plain gradient
    return false;
  }
  d.steepest = false;
  d.radius = Real(0.25) * step.len;
  if (d.radius * tol.scale <= tol.settle) {  // no step within reach can gain more than `settle`
    d.converged = true;
    return true;
  }
  return false;
}

/// Step 3a: the descent stopped with h's slope still above rounding, where h's change over
/// the remaining distance is below it (in float a normal 7e-4 rad off changes h by 2 ulps)
/// and the Newton model could not tell (its Hessian by differences crossed a crease): the
/// zero of the slope along the great circle downhill from the sample, n(th) = cos th n +
/// sin th u, whose slope is (cos th u - sin th n) . s_D(n(th)) and needs no difference of
/// h. Doubling steps from `theta0` bracket the zero, regula falsi (Illinois) closes it, at
/// most `budget` support pairs. Takes the probe of least slope when it halves the sample's
/// and h does not rise beyond rounding (at a kink of h the slope jumps and is not halved).
template <class SupportA, class SupportB>
bool slope_search(SupportA& support_a, SupportB& support_b, Descent& d, Real theta0, const RefineTolerances& tol,
                  int budget) {
  const Vec3 n = d.at.n;
  const Real g = slope(d.at);
  if (!(g > Real(0)) || !std::isfinite(g)) return false;
  const Vec3 u = -across(d.at) / g;
  auto probe = [&](Real th) {
    ++d.queries;
    return sample(support_a, support_b, unit(std::cos(th) * n + std::sin(th) * u));
  };
  auto slope_along = [&](Real th, const SupportSample& x) {
    return glm::dot(std::cos(th) * u - std::sin(th) * n, x.p);
  };
  SupportSample best = d.at;
  auto consider = [&](const SupportSample& x) {
    if (x.h <= d.at.h + tol.flat && slope(x) < slope(best)) best = x;
  };
  Real lo = Real(0);
  Real s_lo = -g;
  Real hi = std::clamp(theta0, kEpsilon, Real(0.125));
  Real s_hi = Real(0);
  for (;; hi *= Real(2)) {
    if (budget-- <= 0 || hi > Real(0.5)) return false;
    const SupportSample x = probe(hi);
    consider(x);
    s_hi = slope_along(hi, x);
    if (!(s_hi < Real(0))) break;
    lo = hi;
    s_lo = s_hi;
  }
  int side = 0;
  while (budget-- > 0 && (hi - lo) * tol.scale > tol.flat) {
    Real th = (lo * s_hi - hi * s_lo) / (s_hi - s_lo);
    if (!(th > lo && th < hi)) th = Real(0.5) * (lo + hi);
    const SupportSample x = probe(th);
    consider(x);
    const Real st = slope_along(th, x);
    if (st < Real(0)) {
      lo = th;
      s_lo = st;
      if (side < 0) s_hi *= Real(0.5);
      side = -1;
    } else {
      hi = th;
      s_hi = st;
      if (side > 0) s_lo *= Real(0.5);
      side = 1;
    }
    if (std::abs(st) <= tol.flat) break;
  }
  if (!(slope(best) < Real(0.5) * g)) return false;
  d.at = best;
  d.fresh = false;
  d.eta = tol.eta;
  d.steepest = false;
  d.converged = false;
  d.radius = Real(0.25);
  return true;
}

/// Steps 1-3: the trust-region Newton descent of h from `start`, at most `max_steps` trials.
template <class SupportA, class SupportB>
Descent descend(SupportA& support_a, SupportB& support_b, const SupportSample& start, const RefineTolerances& tol,
                int max_steps) {
  Descent d;
  d.at = start;
  d.queries = 1;
  d.eta = tol.eta;
  int searches = 4;
  for (int step = 0; step < max_steps; ++step) {
    if (!d.fresh) {
      d.model = gradient_at(d.at);
      if (std::sqrt(d.model.g1 * d.model.g1 + d.model.g2 * d.model.g2) <= tol.flat) {
        d.converged = true;
        break;
      }
      estimate_hessian(support_a, support_b, d.at, d.eta, d.model, d.queries);
      d.fresh = true;
    }
    const TangentStep s = trust_region_step(d.model, d.radius, d.steepest, tol.flat);
    const Vec3 n_try = unit(d.at.n + s.d1 * d.model.basis.t1 + s.d2 * d.model.basis.t2);
    const SupportSample trial = sample(support_a, support_b, n_try);
    ++d.queries;
    if (!accept_or_shrink(d, trial, s, tol)) continue;
    // Stopped with the slope above rounding: its zero along the gradient, then on.
    const Real g = slope(d.at);
    if (g > tol.flat && searches-- > 0 && slope_search(support_a, support_b, d, g / tol.scale, tol, 32)) continue;
    break;
  }
  return d;
}

/// Up to three kept support pairs plus one new one, with their coordinates (u, v) in the
/// plane across n and their convex weights.
struct TangentPoints {
  std::array<Vec3, 4> pa{};   ///< support points of A
  std::array<Vec3, 4> pb{};   ///< support points of B
  std::array<Real, 4> u{};    ///< coordinate of pa - pb along t1
  std::array<Real, 4> v{};    ///< ... along t2
  std::array<Real, 4> lam{};  ///< weights of the kept points (sum 1)
  int count = 0;              ///< kept points
};

/// The best candidate so far of nearest_hull_weights: weights over the points and the
/// squared norm of the point they make.
struct NearestCandidate {
  std::array<Real, 4> weights{};                       ///< convex weights
  Real norm2 = std::numeric_limits<Real>::infinity();  ///< |sum weights x (u, v)|^2

  /// Keeps `l` when its point is nearer the origin than the best so far.
  void consider(const TangentPoints& t, const std::array<Real, 4>& l) {
    Real x = Real(0);
    Real y = Real(0);
    for (std::size_t c = 0; c < 4; ++c) {
      x += l[c] * t.u[c];
      y += l[c] * t.v[c];
    }
    const Real nn = x * x + y * y;
    if (nn < norm2) {
      norm2 = nn;
      weights = l;
    }
  }
};

/// Segment (i, j): the weights of its point nearest the origin when that point lies strictly
/// inside it.
inline void consider_segment(const TangentPoints& t, std::size_t i, std::size_t j, NearestCandidate& best) {
  const auto& u = t.u;
  const auto& v = t.v;
  const Real eu = u[j] - u[i];
  const Real ev = v[j] - v[i];
  const Real ee = eu * eu + ev * ev;
  if (!(ee > Real(0))) return;
  const Real s = -(u[i] * eu + v[i] * ev) / ee;
  if (!(s > Real(0) && s < Real(1))) return;
  std::array<Real, 4> w{};
  w[i] = Real(1) - s;
  w[j] = s;
  best.consider(t, w);
}

/// Triangle (i, j, k): the barycentric weights of the origin when it lies inside.
inline void consider_triangle(const TangentPoints& t, std::size_t i, std::size_t j, std::size_t k,
                              NearestCandidate& best) {
  const auto& u = t.u;
  const auto& v = t.v;
  const Real den = (u[j] - u[i]) * (v[k] - v[i]) - (v[j] - v[i]) * (u[k] - u[i]);
  if (!(std::abs(den) > Real(0))) return;
  const Real li = (u[j] * v[k] - v[j] * u[k]) / den;
  const Real lj = (u[k] * v[i] - v[k] * u[i]) / den;
  const Real lk = Real(1) - li - lj;
  if (!(li >= Real(0) && lj >= Real(0) && lk >= Real(0))) return;
  std::array<Real, 4> w{};
  w[i] = li;
  w[j] = lj;
  w[k] = lk;
  best.consider(t, w);
}

/// Weights (over the first `total` points) of the point of their convex hull nearest the
/// origin of the (u, v) plane: the best of every vertex, segment and triangle.
inline std::array<Real, 4> nearest_hull_weights(const TangentPoints& t, int total) {
  NearestCandidate best;
  const auto n = static_cast<std::size_t>(total);
  for (std::size_t i = 0; i < n; ++i) {
    std::array<Real, 4> vertex{};
    vertex[i] = Real(1);
    best.consider(t, vertex);
    for (std::size_t j = i + 1; j < n; ++j) {
      consider_segment(t, i, j, best);
      for (std::size_t k = j + 1; k < n; ++k) consider_triangle(t, i, j, k, best);
    }
  }
  return best.weights;
}

/// Keeps the points of positive weight (packed to the front, at most three) and returns
/// their weighted coordinates in mu, mv.
inline void keep_weighted(TangentPoints& t, const std::array<Real, 4>& best, int total, Real& mu, Real& mv) {
  t.count = 0;
  mu = Real(0);
  mv = Real(0);
  for (std::size_t c = 0; c < static_cast<std::size_t>(total); ++c) {
    if (!(best[c] > Real(0))) continue;
    const auto o = static_cast<std::size_t>(t.count++);
    t.pa[o] = t.pa[c];
    t.pb[o] = t.pb[c];
    t.u[o] = t.u[c];
    t.v[o] = t.v[c];
    t.lam[o] = best[c];
    mu += best[c] * t.u[c];
    mv += best[c] * t.v[c];
  }
  for (auto c = static_cast<std::size_t>(t.count); c < 4; ++c) t.lam[c] = Real(0);
}

/// Step 4a: D's support feature along `at.n` (a face or edge of D: a cylinder's cap or side
/// against a point) as convex weights over support pairs. The feature's own support in a
/// tangent direction e is D's support along n tipped by sqrt(eps) towards e, so a small GJK
/// in the tangent plane (at most 16 support pairs, counted in `queries`) finds the feature's
/// point nearest the line along n. `tip` (radians) may be wider, to reach a crease the
/// normal lies beyond sqrt(eps) of.
template <class SupportA, class SupportB>
TangentPoints feature_points(SupportA& support_a, SupportB& support_b, const SupportSample& at, Real scale,
                             int& queries, Real tip = std::sqrt(kEpsilon)) {
  const Vec3& n = at.n;
  const TangentBasis tb = tangent_basis(n);
  TangentPoints t;
  t.pa[0] = at.a;
  t.pb[0] = at.b;
  t.u[0] = glm::dot(tb.t1, at.p);
  t.v[0] = glm::dot(tb.t2, at.p);
  t.lam[0] = Real(1);
  t.count = 1;
  Real mu = t.u[0];
  Real mv = t.v[0];
  const Real close = Real(4) * kEpsilon * scale;
  for (int it = 0; it < 16; ++it) {
    const Real mm = mu * mu + mv * mv;
    if (std::sqrt(mm) <= close) break;
    const Real ml = std::sqrt(mm);
    const Vec3 d = unit(n - tip * (mu / ml * tb.t1 + mv / ml * tb.t2));
    const Vec3 na = support_a(d);
    const Vec3 nb = support_b(-d);
    ++queries;
    const Vec3 w = na - nb;
    const Real nu = glm::dot(tb.t1, w);
    const Real nv = glm::dot(tb.t2, w);
    if (mm - (mu * nu + mv * nv) <= close * ml) break;  // no progress towards the line
    const auto k = static_cast<std::size_t>(t.count);
    t.pa[k] = na;
    t.pb[k] = nb;
    t.u[k] = nu;
    t.v[k] = nv;
    const int total = t.count + 1;
    keep_weighted(t, nearest_hull_weights(t, total), total, mu, mv);
    if (t.count >= 3) break;  // the origin's projection is inside a triangle: done
  }
  return t;
}

/// How far the feature's point nearest the line along the sample's normal is from it (0 when
/// the line meets the feature: a smooth minimum or a resolved crease).
inline Real off_line(const TangentPoints& t) {
  Real mu = Real(0);
  Real mv = Real(0);
  for (std::size_t c = 0; c < static_cast<std::size_t>(t.count); ++c) {
    mu += t.lam[c] * t.u[c];
    mv += t.lam[c] * t.v[c];
  }
  return std::sqrt(mu * mu + mv * mv);
}

/// The direction of D's support feature when it is an edge that the line along the sample's
/// normal misses (a ridge of h: the descent settled on its crease), else zero.
inline Vec3 missed_edge(const TangentPoints& t, Real scale) {
  if (t.count != 2) return Vec3(Real(0));
  const Real mu = t.lam[0] * t.u[0] + t.lam[1] * t.u[1];
  const Real mv = t.lam[0] * t.v[0] + t.lam[1] * t.v[1];
  if (std::sqrt(mu * mu + mv * mv) <= std::sqrt(kEpsilon) * scale) return Vec3(Real(0));
  return (t.pa[1] - t.pb[1]) - (t.pa[0] - t.pb[0]);
}

/// The direction of an edge of one side's support that a crease of h near the sample runs
/// along, found across it: the sample's normal tipped by `tip` both ways along both tangents;
/// a side whose support point jumps by more than a curved side's support moves for that tip
/// (8 tip scale) switched vertices there, and the jump is the edge. Zero when none jumps. For a
/// descent that zigzagged along a crease whose minimum lies along it, where the feature's
/// tangent-plane search tips towards the minimum, along the crease, and never crosses it.
template <class SupportA, class SupportB>
Vec3 crossed_edge(SupportA& support_a, SupportB& support_b, const SupportSample& at, Real scale, Real tip,
                  int& queries) {
  const TangentBasis tb = tangent_basis(at.n);
  const Real jump = Real(8) * tip * scale;
  Vec3 best(Real(0));
  Real best_len = jump;
  for (const Vec3& t : {tb.t1, -tb.t1, tb.t2, -tb.t2}) {
    const SupportSample x = sample(support_a, support_b, unit(at.n + tip * t));
    ++queries;
    for (const Vec3& d : {x.a - at.a, x.b - at.b}) {
      const Real len = std::sqrt(glm::dot(d, d));
      if (len > best_len) {
        best_len = len;
        best = d;
      }
    }
  }
  return best;
}

/// Step 3b: the descent settled on a ridge of h, where D's support along n is an edge of
/// direction e (two vertices tie): across it h has a crease, along it h is smooth. From n
/// moved onto the crease (e . n = 0), on the great circle of normals across e,
/// n(th) = cos th n + sin th m with m = unit(e x n), the slope of h is m(th) . s_D(n(th))
/// (both ends of the edge agree on it). Steps downhill, doubling until the slope turns or h
/// rises, then bisects the bracket to the settle threshold, at most `budget` support pairs.
/// True when it lowered h beyond rounding.
template <class SupportA, class SupportB>
bool follow_ridge(SupportA& support_a, SupportB& support_b, Descent& d, const Vec3& e, const RefineTolerances& tol,
                  int budget) {
  // The great circle through the crease itself (e . n = 0) where the normal is off it beyond
  // sqrt(eps) radians: from there the circle stays off by as much (seen 6e-4 rad in float,
  // the witnesses then 0.07 off the line).
  const Real ee = glm::dot(e, e);
  if (!(ee > Real(0)) || !std::isfinite(ee)) return false;
  const Real across = glm::dot(e, d.at.n);
  const Vec3 n = std::abs(across) > std::sqrt(kEpsilon * ee) ? unit(d.at.n - (across / ee) * e) : d.at.n;
  const Vec3 axis = glm::cross(e, n);
  const Real axis_len = std::sqrt(glm::dot(axis, axis));
  if (!(axis_len > Real(0)) || !std::isfinite(axis_len)) return false;
  Vec3 m = axis / axis_len;
  if (glm::dot(m, d.at.p) > Real(0)) m = -m;  // downhill
  auto probe = [&](Real th) {
    ++d.queries;
    return sample(support_a, support_b, unit(std::cos(th) * n + std::sin(th) * m));
  };
  auto slope = [&](Real th, const SupportSample& x) { return glm::dot(std::cos(th) * m - std::sin(th) * n, x.p); };
  const Real start_h = d.at.h;
  SupportSample best = d.at;
  Real lo = Real(0);
  Real hi = Real(0);
  for (Real th = Real(1e-3); budget > 0 && th < Real(1.5); th *= Real(2), --budget) {
    const SupportSample x = probe(th);
    if (x.h < best.h) best = x;
    hi = th;
    if (!(slope(th, x) < Real(0)) || x.h > start_h) break;
    lo = th;
  }
  while (budget-- > 0 && (hi - lo) * tol.scale > tol.settle) {
    const Real mid = Real(0.5) * (lo + hi);
    const SupportSample x = probe(mid);
    if (x.h < best.h) best = x;
    if (slope(mid, x) < Real(0) && x.h <= start_h)
      lo = mid;
    else
      hi = mid;
  }
  if (!(best.h < start_h - tol.flat)) return false;
  d.at = best;
  d.fresh = false;
  d.steepest = false;
  d.converged = false;
  d.radius = Real(0.25);
  return true;
}

/// The unit normal of the plane through three points, oriented along `towards`; zero when
/// they are (nearly) collinear.
inline Vec3 plane_normal(const Vec3& p0, const Vec3& p1, const Vec3& p2, const Vec3& towards, Real scale) {
  const Vec3 m = glm::cross(p1 - p0, p2 - p0);
  const Real mm = glm::dot(m, m);
  if (!(mm > Real(64) * kEpsilon * scale * scale * scale * scale) || !std::isfinite(mm)) return Vec3(Real(0));
  const Vec3 u = m / std::sqrt(mm);
  return glm::dot(u, towards) < Real(0) ? -u : u;
}

/// Step 3c: the descent settled at a kink of h where one side's support along n is a face (a
/// box's face, a cylinder's cap against a curved point): there the minimum is that face's
/// normal exactly, which a descent only approaches to its settle threshold (a box corner in a
/// cylinder: 4e-11 above the depth in double). The face normal from three of that side's
/// support points of the feature (a polytope's vertices, a cap's rim points: exact to
/// rounding, where D's points also carry the other side's motion over the tipped normals) is
/// taken when h there is no higher than at the sample beyond rounding.
template <class SupportA, class SupportB>
bool snap_to_face(SupportA& support_a, SupportB& support_b, Descent& d, TangentPoints& feature,
                  const RefineTolerances& tol, int& queries) {
  if (feature.count != 3) return false;
  const Vec3 na = plane_normal(feature.pa[0], feature.pa[1], feature.pa[2], d.at.n, tol.scale);
  const Vec3 nb = plane_normal(feature.pb[0], feature.pb[1], feature.pb[2], -d.at.n, tol.scale);
  bool moved = false;
  for (const Vec3& n : {na, -nb}) {
    if (!(glm::dot(n, n) > Real(0))) continue;
    const SupportSample x = sample(support_a, support_b, n);
    ++queries;
    if (!(x.h <= d.at.h + tol.flat) || (moved && !(x.h < d.at.h))) continue;
    d.at = x;
    moved = true;
  }
  if (moved) feature = feature_points(support_a, support_b, d.at, tol.scale, queries);
  return moved;
}

/// Step 4b: the witnesses: the feature points' weights (feature_points at `at`) applied to
/// A's and B's support points, moved half each to obey support_a - support_b = h n.
inline void tangent_witnesses(const TangentPoints& t, const SupportSample& at, Refinement& r) {
  Vec3 wa(Real(0));
  Vec3 wb(Real(0));
  for (std::size_t c = 0; c < static_cast<std::size_t>(t.count); ++c) {
    wa += t.lam[c] * t.pa[c];
    wb += t.lam[c] * t.pb[c];
  }
  const Vec3 residual = (wa - wb) - at.h * at.n;
  r.witness_gap = glm::length(residual);
  r.support_a = wa - Real(0.5) * residual;
  r.support_b = wb + Real(0.5) * residual;
}

}  // namespace refine_detail

/// Refines a penetration normal on the support function of D = A - B (see the file
/// comment): trust-region Newton steps from `start_normal`, at most `max_steps` trials, then
/// witnesses on D's support feature. `length_scale` (> 0) is the size of the problem, for
/// the rounding thresholds. Never NaN (a start of zero length uses +z).
template <class SupportA, class SupportB>
Refinement refine(SupportA& support_a, SupportB& support_b, const Vec3& start_normal, Real length_scale,
                  int max_steps = 96) {
  namespace rd = refine_detail;
  const rd::RefineTolerances tol = rd::refine_tolerances(length_scale);
  const rd::SupportSample start = rd::sample(support_a, support_b, rd::unit_or_z(start_normal));
  rd::Descent d = rd::descend(support_a, support_b, start, tol, max_steps);
  int queries = d.queries;
  rd::TangentPoints feature = rd::feature_points(support_a, support_b, d.at, tol.scale, queries);
  // Settled on a ridge (an edge of D the line along n misses): along the ridge, then on. A
  // descent that ran out of steps may be zigzagging along a crease beyond the tipped
  // supports' reach of it: the edge is looked for with a wider tip there.
  const Real wide_tip = std::min(Real(1e-3), Real(1024) * std::sqrt(kEpsilon));
  for (int round = 0; round < 4; ++round) {
    Vec3 e = rd::missed_edge(feature, tol.scale);
    if (!(glm::dot(e, e) > Real(0)) && !d.converged)
      e = rd::missed_edge(rd::feature_points(support_a, support_b, d.at, tol.scale, queries, wide_tip), tol.scale);
    // Settled (by rounding, in float) or out of steps with the line along n off D's support
    // feature: a crease the feature search did not see; across it, by the supports' jump.
    const bool unresolved = !d.converged || rd::off_line(feature) > std::sqrt(kEpsilon) * tol.scale;
    if (!(glm::dot(e, e) > Real(0)) && unresolved)
      e = rd::crossed_edge(support_a, support_b, d.at, tol.scale, Real(1e-3), queries);
    if (!(glm::dot(e, e) > Real(0))) break;
    d.queries = 0;
    const bool moved = rd::follow_ridge(support_a, support_b, d, e, tol, max_steps);
    queries += d.queries;
    if (!moved) break;
    d = rd::descend(support_a, support_b, d.at, tol, max_steps);
    queries += d.queries;
    feature = rd::feature_points(support_a, support_b, d.at, tol.scale, queries);
  }
  rd::snap_to_face(support_a, support_b, d, feature, tol, queries);
  Refinement r;
  r.iterations = queries;
  r.converged = d.converged;
  r.improved = d.at.h < start.h;
  r.depth = d.at.h;
  r.normal = d.at.n;
  r.tangential = rd::across(d.at);
  rd::tangent_witnesses(feature, d.at, r);
  return r;
}

/// Witnesses on D's support feature along `normal` alone (step 4 of refine, no descent):
/// points of A and B with support_a - support_b = depth normal, depth the support distance
/// along the normal, and witness_gap how far the feature's point nearest the line along the
/// normal was from it. For an answer whose own witnesses do not obey the relation (EPA's
/// nearest face left its projection outside, on a flat contact of many coplanar faces).
template <class SupportA, class SupportB>
Refinement witnesses_along(SupportA& support_a, SupportB& support_b, const Vec3& normal, Real length_scale) {
  namespace rd = refine_detail;
  const Vec3 n = rd::unit_or_z(normal);
  const rd::SupportSample at = rd::sample(support_a, support_b, n);
  Refinement r;
  r.iterations = 1;
  r.depth = at.h;
  r.normal = n;
  r.tangential = rd::across(at);
  const rd::TangentPoints feature =
      rd::feature_points(support_a, support_b, at, rd::refine_tolerances(length_scale).scale, r.iterations);
  rd::tangent_witnesses(feature, at, r);
  return r;
}

}  // namespace proxima::epa
