// Safe time steps (src/ccd/safe_step.cpp): the kernel against its formula, the certificate by
// simulation, and the API around them.
//
// The certificate: over [0, dt] two bodies moving with their constant velocities (position
// p + v t, rotation exp(w t) q about the world axis of w) stay apart by at least the target.
// Checked on seeded pairs of every convex kind (and a still or translating half-space) with
// random linear and angular velocities: the narrow phase's distance at many sub-times of
// [0, dt] and at the first touch found by a fine scan and bisection, which also gives the
// ratio dt / first touch (<= 1 by the certificate; its distribution, printed, shows how
// conservative the bound is). A pure translation along the normal is exact (ratio 1);
// moving apart gives +infinity, also when checked far ahead. The batched form equals the
// pair form and returns the least step; rotation_radius bounds every core point of each
// kind and follows its documented formula; every bad field is named.
#include <gtest/gtest.h>

#include <proxima/ccd/safe_step.hpp>
#include <proxima/core/tolerance.hpp>
#include <proxima/narrowphase/narrowphase.hpp>
#include <proxima/shapes/shape.hpp>
#include <proxima/shapes/shape_queries.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <type_traits>
#include <variant>
#include <vector>

#include "ccd/case_text.hpp"
#include "support/random.hpp"
#include "support/solid_test_meshes.hpp"
#include "sweep_size.hpp"

namespace proxima {
namespace test_safe_step {

using test::num;
using test::text;

constexpr bool kFloat = sizeof(Real) == 4;
constexpr Real kInf = std::numeric_limits<Real>::infinity();
// Accuracy of the narrow phase's distance at the length scale of the sweeps (~5), and of its
// normal's direction on curved shapes (GJK converges linearly there), as a length error.
const Real kGapAccuracy = kFloat ? Real(5e-5) : Real(1e-9);
const Real kCurvedAccuracy = kFloat ? Real(5e-4) : Real(1e-6);

constexpr std::array<ShapeType, 10> kConvexKinds{
    ShapeType::Sphere,    ShapeType::Capsule,    ShapeType::Box,      ShapeType::Cylinder, ShapeType::Cone,
    ShapeType::Ellipsoid, ShapeType::ConvexHull, ShapeType::Triangle, ShapeType::Segment,  ShapeType::Point};

// A convex shape of `kind` about `size` across, its local origin off its centre now and then
// (a hull's or a triangle's points are not centred), so rotation moves it.
Shape random_convex(test::Random& rng, ShapeType kind, Real size) {
  const auto r = [&](Real lo, Real hi) { return size * rng.uniform(lo, hi); };
  switch (kind) {
    case ShapeType::Sphere: return Sphere::create(r(Real(0.3), Real(1))).value();
    case ShapeType::Capsule: return Capsule::create(r(Real(0.2), Real(0.6)), r(Real(0.2), Real(1))).value();
    case ShapeType::Box: return Box::create(size * rng.vec3(Real(0.2), Real(1))).value();
    case ShapeType::Cylinder: return Cylinder::create(r(Real(0.2), Real(1)), r(Real(0.2), Real(1))).value();
    case ShapeType::Cone: return Cone::create(r(Real(0.2), Real(1)), r(Real(0.2), Real(1))).value();
    case ShapeType::Ellipsoid: return Ellipsoid::create(size * rng.vec3(Real(0.2), Real(1))).value();
    case ShapeType::ConvexHull: {
      std::vector<Vec3> points;
      const Vec3 centre = rng.in_ball(size * Real(0.5));
      for (int i = 0; i < 14; ++i) points.push_back(centre + rng.in_ball(size));
      return ConvexHull::create(points).value();
    }
    case ShapeType::Triangle:
      for (;;) {
        auto t = Triangle::create(rng.in_ball(size), rng.in_ball(size), rng.in_ball(size));
        if (t && t->area() > Real(0.05) * size * size) return *t;
      }
    case ShapeType::Segment:
      for (;;) {
        auto s = Segment::create(rng.in_ball(size), rng.in_ball(size));
        if (s && s->length() > Real(0.2) * size) return *s;
      }
    default: return Point::create().value();
  }
}

// The true rigid motion of a body after `t` seconds: p + v t, exp(w t) q.
Transform at_time(const MovingBody& body, Real t) {
  Transform pose{body.pose.position + t * body.linear, body.pose.rotation};
  const Real speed = glm::length(body.angular);
  if (speed > Real(0)) pose.rotation = glm::normalize(glm::angleAxis(speed * t, body.angular / speed) * pose.rotation);
  return pose;
}

Real gap_at(const MovingBody& a, const MovingBody& b, Real t) {
  return distance(a.shape, at_time(a, t), b.shape, at_time(b, t)).signed_distance;
}

std::string text(const MovingBody& body) {
  const Quat& q = body.pose.rotation;
  std::string out = to_string(body.shape.type());
  for (const std::string& part : {std::string(" at "), text(body.pose.position), std::string(" q("), num(q.w),
                                  std::string(", "), num(q.x), std::string(", "), num(q.y), std::string(", "), num(q.z),
                                  std::string(") v "), text(body.linear), std::string(" w "), text(body.angular)}) {
    out += part;
  }
  return out;
}

// Wrong answers of a sweep: counted, the first few described.
struct Failures {
  int count = 0;
  std::string examples;
  void add(const std::string& what) {
    if (++count <= 4) examples += "\n  " + what;
  }
};

// ---------------------------------------------------------------------------------------
// The kernel

TEST(SafeStep, KernelMatchesItsFormula) {
  test::Random rng(2101);
  int finite = 0, infinite = 0, zero = 0;
  const int n = test::sweep_size(5000);
  for (int i = 0; i < n; ++i) {
    const Real gap = rng.uniform(Real(-1), Real(5));
    const Vec3 nrm = rng.unit_vector();
    const Vec3 va = rng.vec3(Real(-3), Real(3)), vb = rng.vec3(Real(-3), Real(3));
    const Vec3 wa = i % 3 == 0 ? Vec3(0) : rng.vec3(Real(-2), Real(2));
    const Vec3 wb = i % 4 == 0 ? Vec3(0) : rng.vec3(Real(-2), Real(2));
    const Real ra = rng.uniform(Real(0), Real(3)), rb = rng.uniform(Real(0), Real(3));
    const Real target = i % 2 == 0 ? Real(0) : rng.uniform(Real(0), Real(0.5));
    const Real dt = safe_time_step_from_distance(gap, nrm, va, wa, ra, vb, wb, rb, target);
    // The formula in double: mu = n.(v_a - v_b) + |n x w_a| r_a + |n x w_b| r_b.
    const glm::dvec3 dn(nrm), dva(va), dvb(vb), dwa(wa), dwb(wb);
    const double mu = glm::dot(dn, dva - dvb) + glm::length(glm::cross(dn, dwa)) * double(ra) +
                      glm::length(glm::cross(dn, dwb)) * double(rb);
    if (!(gap > target)) {
      ++zero;
      EXPECT_EQ(dt, Real(0)) << "case " << i;
    } else if (mu <= 0) {
      ++infinite;
      // Rounding may leave a tiny positive mu where the double one is <= 0: then a huge step.
      EXPECT_GT(dt, Real(1e3) * (gap - target)) << "case " << i << " mu " << mu;
    } else {
      ++finite;
      const double expected = (double(gap) - double(target)) / mu;
      // mu loses digits to cancellation: the error is relative to the terms' magnitude.
      const double terms = glm::length(dva - dvb) + glm::length(dwa) * double(ra) + glm::length(dwb) * double(rb);
      const double eps = kFloat ? 1e-6 : 1e-14;
      EXPECT_NEAR(double(dt), expected, expected * eps * 8 * terms / mu + 1e-30) << "case " << i;
    }
  }
  EXPECT_GT(finite, test::sweep_share(1500));
  EXPECT_GT(infinite, test::sweep_share(500));
  EXPECT_GT(zero, test::sweep_share(500));
}

TEST(SafeStep, KernelEdgeCases) {
  const Vec3 up(0, 0, 1), zero(0);
  // Closing at 2 along n over a gap of 3 less the target 1: one second.
  EXPECT_EQ(
      safe_time_step_from_distance(Real(3), up, Vec3(0, 0, 1), zero, Real(5), Vec3(0, 0, -1), zero, Real(5), Real(1)),
      Real(1));
  // Gap at (or below) the target: 0.
  EXPECT_EQ(safe_time_step_from_distance(Real(1), up, up, zero, Real(1), zero, zero, Real(1), Real(1)), Real(0));
  EXPECT_EQ(safe_time_step_from_distance(Real(-1), up, up, zero, Real(1), zero, zero, Real(1), Real(0)), Real(0));
  // Moving apart or sideways, no rotation: never.
  EXPECT_EQ(safe_time_step_from_distance(Real(1), up, -up, zero, Real(1), zero, zero, Real(1), Real(0)), kInf);
  EXPECT_EQ(safe_time_step_from_distance(Real(1), up, Vec3(1, 0, 0), zero, Real(1), zero, zero, Real(1), Real(0)),
            kInf);
  // Spin about n itself moves no point along n: never.
  EXPECT_EQ(
      safe_time_step_from_distance(Real(1), up, zero, Vec3(0, 0, 7), Real(1), zero, Vec3(0, 0, -3), Real(2), Real(0)),
      kInf);
  // Spin across n: |n x w| r = 2 x 0.5 = 1 per second over a gap of 2.
  EXPECT_EQ(safe_time_step_from_distance(Real(2), up, zero, Vec3(2, 0, 0), Real(0.5), zero, zero, Real(0), Real(0)),
            Real(2));
  // Both bodies' spins add; B's linear velocity counts against A's.
  EXPECT_EQ(safe_time_step_from_distance(Real(4), up, Vec3(0, 0, 1), Vec3(0, 1, 0), Real(1), Vec3(0, 0, 1),
                                         Vec3(0, 2, 0), Real(0.5), Real(0)),
            Real(2));
  // An unbounded radius (a half-space) with its spin about n: n.v only (motion.hpp).
  EXPECT_EQ(safe_time_step_from_distance(Real(2), up, Vec3(0, 0, 1), Vec3(0, 0, 3), kInf, zero, zero, Real(0), Real(0)),
            Real(2));
  // Doubling every velocity halves the step.
  test::Random rng(2102);
  for (int i = 0; i < 200; ++i) {
    const Vec3 n = rng.unit_vector(), va = rng.vec3(-2, 2), wa = rng.vec3(-2, 2), vb = rng.vec3(-2, 2),
               wb = rng.vec3(-2, 2);
    const Real ra = rng.uniform(0, 2), rb = rng.uniform(0, 2), gap = rng.uniform(Real(0.1), 3);
    const Real once = safe_time_step_from_distance(gap, n, va, wa, ra, vb, wb, rb, Real(0));
    const Real twice =
        safe_time_step_from_distance(gap, n, Real(2) * va, Real(2) * wa, ra, Real(2) * vb, Real(2) * wb, rb, Real(0));
    if (std::isfinite(once)) {
      EXPECT_NEAR(twice, once / 2, once * Real(1e-5)) << "case " << i;
    } else {
      EXPECT_EQ(twice, kInf) << "case " << i;
    }
  }
}

// ---------------------------------------------------------------------------------------
// rotation_radius

// The documented radius: 0 for a sphere or a point, the half length of a capsule, the
// farthest vertex of a hull, the farthest corner of the local box otherwise.
Real documented_radius(const Shape& shape) {
  switch (shape_type(shape)) {
    case ShapeType::Sphere:
    case ShapeType::Point: return Real(0);
    case ShapeType::Capsule: return std::get<Capsule>(shape).half_length();
    case ShapeType::ConvexHull: {
      Real r = Real(0);
      for (const Vec3& v : std::get<ConvexHull>(shape).vertices()) r = std::max(r, glm::length(v));
      return r;
    }
    default: {
      const Aabb box = world_aabb(shape, Transform{});
      return glm::length(glm::max(glm::abs(box.min), glm::abs(box.max)));
    }
  }
}

TEST(SafeStep, RotationRadiusPerShapeKind) {
  test::Random rng(2201);
  for (const ShapeType kind : kConvexKinds) {
    for (int i = 0; i < 20; ++i) {
      const Shape shape = random_convex(rng, kind, rng.uniform(Real(0.2), Real(3)));
      const Real r = rotation_radius(shape);
      EXPECT_NEAR(r, documented_radius(shape), Real(1e-6) * std::max(Real(1), r)) << to_string(kind);
      // Every point that rotation moves (the core: the shape less its rounding ball) lies
      // within r of the origin.
      const Real core_max = std::visit(
          [&](const auto& s) {
            Real m = Real(0);
            using S = std::decay_t<decltype(s)>;
            if constexpr (ConvexShape<S> && !std::is_same_v<S, HalfSpace>) {
              for (int k = 0; k < 200; ++k) m = std::max(m, glm::length(s.core_support(rng.unit_vector())));
            }
            return m;
          },
          shape);
      EXPECT_LE(core_max, r * (Real(1) + Real(1e-5)) + Real(1e-6)) << to_string(kind);
    }
  }
  EXPECT_EQ(rotation_radius(Sphere::create(Real(2)).value()), Real(0));
  EXPECT_EQ(rotation_radius(Capsule::create(Real(2), Real(3)).value()), Real(3));
  EXPECT_NEAR(rotation_radius(Box::create(Vec3(1, 2, 2)).value()), Real(3), Real(1e-6));
  EXPECT_EQ(rotation_radius(HalfSpace::create(Vec3(0, 0, 1), Real(0)).value()), kInf);
  // Meshes and compounds: every vertex within the radius.
  const TriangleMesh torus = TriangleMesh::create(test::torus_mesh(Real(2), Real(0.5), 12, 6)).value();
  const Real rt = rotation_radius(torus);
  for (const Vec3& v : torus.vertices()) EXPECT_LE(glm::length(v), rt * (Real(1) + Real(1e-6)));
  std::vector<CompoundChild> kids;
  kids.push_back({Box::create(Vec3(0.5f)).value(), Transform{Vec3(3, 0, 0), kIdentityQuat}});
  kids.push_back({Sphere::create(Real(1)).value(), Transform{Vec3(0, -2, 0), kIdentityQuat}});
  const Compound compound = Compound::create(kids).value();
  EXPECT_GE(rotation_radius(compound), glm::length(Vec3(3.5f, 0.5f, 0.5f)) * (Real(1) - Real(1e-6)));
  EXPECT_GE(rotation_radius(compound), Real(3) * (Real(1) - Real(1e-6)));
}

// ---------------------------------------------------------------------------------------
// The certificate, by simulation

// Two shapes with their poses and velocities; the bodies view the shapes held here.
struct Pair {
  Shape a, b;
  Transform pa, pb;
  Vec3 va{0}, vb{0}, wa{0}, wb{0};
  MovingBody body_a() const { return {a, pa, va, wa}; }
  MovingBody body_b() const { return {b, pb, vb, wb}; }
};

// A seeded pair: A of `ka`, B of `kb` (or a half-space: still or translating, never
// rotating, as the header requires), 1.5 to 4 apart, with random velocities aimed roughly
// at each other.
Pair random_pair(test::Random& rng, ShapeType ka, ShapeType kb, bool rotate) {
  Pair p{random_convex(rng, ka, rng.uniform(Real(0.3), Real(1))), Point::create().value(), {}, {}};
  const Transform pa = rng.pose(Real(2));
  const Transform pb{pa.position + rng.vector_of_length(Real(1.5), Real(4)), rng.rotation()};
  const Vec3 towards = glm::normalize(pb.position - pa.position);
  if (kb == ShapeType::HalfSpace) {
    // The plane through pb facing A.
    p.b = HalfSpace::create(pb.inverse_apply_vector(-towards), Real(0)).value();
  } else {
    p.b = random_convex(rng, kb, rng.uniform(Real(0.3), Real(1)));
  }
  p.pa = pa;
  p.pb = pb;
  p.va = towards * rng.uniform(Real(0), Real(3)) + rng.in_ball(Real(1.5));
  p.vb = -towards * rng.uniform(Real(0), Real(1)) + rng.in_ball(Real(1));
  p.wa = rotate ? rng.vector_of_length(Real(0), Real(3)) : Vec3(0);
  p.wb = rotate && kb != ShapeType::HalfSpace ? rng.vector_of_length(Real(0), Real(3)) : Vec3(0);
  return p;
}

struct CertificateTally {
  int cases = 0, finite = 0, infinite = 0, zero = 0, touched = 0;
  std::vector<double> ratios;  // dt / first touch, where a touch was found
  Failures wrong;
};

// First time in (0, horizon] at which the gap reaches `target` (scan in `steps` steps, then
// bisection); +infinity when the scan finds none.
Real first_touch(const MovingBody& a, const MovingBody& b, Real target, Real horizon, int steps) {
  Real previous = Real(0);
  for (int k = 1; k <= steps; ++k) {
    const Real t = horizon * Real(k) / Real(steps);
    if (gap_at(a, b, t) <= target) {
      Real lo = previous, hi = t;
      for (int j = 0; j < 40; ++j) {
        const Real mid = Real(0.5) * (lo + hi);
        (gap_at(a, b, mid) <= target ? hi : lo) = mid;
      }
      return hi;
    }
    previous = t;
  }
  return kInf;
}

// The certificate of one pair: apart by the target over [0, dt] at `samples` sub-times, and
// dt not after the first touch found by a scan of `scan` steps.
void certify(const MovingBody& a, const MovingBody& b, Real target, int samples, int scan, CertificateTally& tally) {
  const Result<Real> step = safe_time_step(a, b, target);
  ASSERT_TRUE(step.ok()) << step.error().what();
  const Real dt = *step;
  ++tally.cases;
  const std::string label = "A " + text(a) + "; B " + text(b) + "; target " + num(target) + "; dt " + num(dt);
  const Real gap0 = gap_at(a, b, Real(0));
  if (dt == Real(0)) {
    ++tally.zero;
    // Only when already within the target (the support gap may be below the distance).
    if (gap0 > target + Real(0.05)) tally.wrong.add("dt 0 at a gap of " + num(gap0) + ": " + label);
    return;
  }
  if (!(dt > Real(0))) {
    tally.wrong.add("dt is " + num(dt) + ": " + label);
    return;
  }
  std::isfinite(dt) ? ++tally.finite : ++tally.infinite;
  // Inside [0, dt]: sub-times, denser towards dt, where a wrong step would fail first.
  const Real span = std::isfinite(dt) ? dt : Real(20);
  const Real slack = kGapAccuracy * std::max(Real(1), span * glm::length(a.linear - b.linear));
  for (int k = 1; k <= samples; ++k) {
    const Real u = Real(k) / Real(samples);
    const Real t = span * (Real(1) - (Real(1) - u) * (Real(1) - u));
    const Real g = gap_at(a, b, t);
    if (g < target - slack) {
      tally.wrong.add("gap " + num(g) + " at t = " + num(t) + " inside [0, dt]: " + label);
      return;
    }
  }
  // The true first touch, well past dt: the step must not pass it; how far short it falls.
  const Real horizon = std::isfinite(dt) ? Real(6) * dt : Real(20);
  const Real touch = first_touch(a, b, target, horizon, scan);
  if (std::isfinite(touch)) {
    ++tally.touched;
    tally.ratios.push_back(double(dt) / double(touch));
    if (dt > touch * (Real(1) + Real(1e-4)) + Real(1e-6)) {
      tally.wrong.add("dt after the first touch at " + num(touch) + ": " + label);
    }
  }
}

void print_ratios(const char* what, CertificateTally& tally) {
  std::vector<double>& r = tally.ratios;
  std::sort(r.begin(), r.end());
  const auto at = [&](double q) { return r.empty() ? 0.0 : r[std::size_t(q * double(r.size() - 1))]; };
  std::printf(
      "%s: %d pairs (%d finite steps, %d infinite, %d zero), %d touching later; dt / first touch: min %.3g, 10%% "
      "%.3g, median %.3g, 90%% %.3g, max %.3g\n",
      what, tally.cases, tally.finite, tally.infinite, tally.zero, tally.touched, at(0), at(0.1), at(0.5), at(0.9),
      at(1));
}

TEST(SafeStep, ConvexPairsStayApartOverTheStep) {
  test::Random rng(2301);
  CertificateTally translating, rotating;
  std::vector<ShapeType> kinds_b(kConvexKinds.begin(), kConvexKinds.end());
  kinds_b.push_back(ShapeType::HalfSpace);
  const int per_pair = test::sweep_size(9);
  for (const ShapeType ka : kConvexKinds) {
    for (const ShapeType kb : kinds_b) {
      for (int i = 0; i < per_pair; ++i) {
        const bool rotate = i % 3 != 0;
        const Pair p = random_pair(rng, ka, kb, rotate);
        const Real target = i % 4 == 1 ? rng.uniform(Real(0.05), Real(0.3)) : Real(0);
        SCOPED_TRACE(std::string(to_string(ka)) + " vs " + to_string(kb));
        certify(p.body_a(), p.body_b(), target, 32, 240, rotate ? rotating : translating);
      }
    }
  }
  print_ratios("safe step, translating convex pairs", translating);
  print_ratios("safe step, rotating convex pairs", rotating);
  EXPECT_EQ(translating.wrong.count, 0) << translating.wrong.examples;
  EXPECT_EQ(rotating.wrong.count, 0) << rotating.wrong.examples;
  // Not absurdly small: most steps reach a good part of the way to the first touch.
  for (CertificateTally* t : {&translating, &rotating}) {
    ASSERT_GT(t->touched, test::sweep_share(60));
    EXPECT_GT(t->ratios[t->ratios.size() / 2], 0.2) << "median of dt / first touch";
    EXPECT_GT(t->ratios.front(), 1e-3) << "least dt / first touch";
  }
}

TEST(SafeStep, TranslationAlongTheNormalIsExact) {
  test::Random rng(2302);
  Failures wrong;
  int cases = 0;
  const int n = test::sweep_size(500);
  for (int i = 0; i < n; ++i) {
    Pair p = random_pair(rng, kConvexKinds[std::size_t(i % 10)], kConvexKinds[std::size_t((i / 10) % 10)], false);
    const DistanceResult d = distance(p.a, p.pa, p.b, p.pb);
    if (!(d.signed_distance > Real(0.05))) continue;
    ++cases;
    // A moves straight along the normal, B still: the gap closes at the speed exactly.
    const Real speed = rng.uniform(Real(0.5), Real(4));
    const Real target = i % 2 == 0 ? Real(0) : d.signed_distance * rng.uniform(Real(0), Real(0.5));
    p.va = speed * d.normal;
    p.vb = Vec3(0);
    const MovingBody ba = p.body_a(), bb = p.body_b();
    const Real dt = safe_time_step(ba, bb, target).value();
    const Real expected = (d.signed_distance - target) / speed;
    if (!(std::abs(dt - expected) <= kCurvedAccuracy / speed)) {
      wrong.add("dt " + num(dt) + ", expected " + num(expected) + ": " + text(ba) + "; " + text(bb));
    }
    // And there the shapes are at the target.
    const Real g = gap_at(ba, bb, dt);
    if (!(std::abs(g - target) <= kCurvedAccuracy)) {
      wrong.add("gap " + num(g) + " at dt, target " + num(target) + ": " + text(ba) + "; " + text(bb));
    }
  }
  EXPECT_EQ(wrong.count, 0) << wrong.examples;
  EXPECT_GT(cases, test::sweep_share(300));
}

TEST(SafeStep, MovingApartIsInfinite) {
  test::Random rng(2303);
  Failures wrong;
  const int n = test::sweep_size(400);
  for (int i = 0; i < n; ++i) {
    std::vector<ShapeType> kinds_b(kConvexKinds.begin(), kConvexKinds.end());
    kinds_b.push_back(ShapeType::HalfSpace);
    Pair p = random_pair(rng, kConvexKinds[std::size_t(i % 10)], kinds_b[std::size_t((i / 10) % 11)], false);
    const DistanceResult d = distance(p.a, p.pa, p.b, p.pb);
    if (!(d.signed_distance > Real(0.01))) continue;
    // Apart along the normal, or sliding across it (the separating plane keeps them apart).
    const Vec3 side = glm::normalize(glm::cross(d.normal, rng.unit_vector()));
    const bool apart = i % 2 == 0;
    p.va = (apart ? -rng.uniform(Real(0.1), 3) * d.normal : Vec3(0)) + side * rng.uniform(0, 3);
    p.vb = (i % 3 == 0 ? rng.uniform(Real(0.1), 1) * d.normal : Vec3(0));
    const MovingBody ba = p.body_a(), bb = p.body_b();
    const Real dt = safe_time_step(ba, bb, Real(0)).value();
    const std::string label = text(ba) + "; " + text(bb);
    // Moving apart: +infinity. Sliding across the normal only (n . v is 0 up to rounding):
    // +infinity or a step far beyond any simulation's.
    if (apart || i % 3 == 0 ? dt != kInf : !(dt > Real(1e5))) wrong.add("dt " + num(dt) + ": " + label);
    // Far ahead: never closer than now.
    for (const Real t : {Real(0.1), Real(1), Real(10), Real(100)}) {
      const Real g = gap_at(ba, bb, t);
      if (g < d.signed_distance - Real(4) * kGapAccuracy * std::max(Real(1), t)) {
        wrong.add("gap " + num(g) + " at t = " + num(t) + " below the start " + num(d.signed_distance) + ": " + label);
      }
    }
  }
  EXPECT_EQ(wrong.count, 0) << wrong.examples;
}

TEST(SafeStep, WithinTheTargetIsZero) {
  test::Random rng(2304);
  int cases = 0;
  for (int i = 0; i < 300; ++i) {
    const Shape a = random_convex(rng, kConvexKinds[std::size_t(i % 7)], Real(1));
    const Shape b = random_convex(rng, kConvexKinds[std::size_t((i / 7) % 7)], Real(1));
    const MovingBody ba{a, rng.pose(Real(0.7)), rng.vec3(-1, 1), rng.vec3(-1, 1)};
    const MovingBody bb{b, rng.pose(Real(0.7)), rng.vec3(-1, 1), rng.vec3(-1, 1)};
    const Real gap = distance(a, ba.pose, b, bb.pose).signed_distance;
    // Overlapping, or apart by less than the target.
    const Real target = gap < Real(0) ? Real(0) : gap + Real(0.05);
    EXPECT_EQ(safe_time_step(ba, bb, target).value(), Real(0)) << "gap " << gap << ", target " << target;
    ++cases;
  }
  EXPECT_EQ(cases, 300);
}

// ---------------------------------------------------------------------------------------
// Non-convex bodies

// A sphere above an L of floor and wall moves parallel to the floor towards the wall: the
// nearest point (the floor) gives a normal across the motion, yet the wall comes.
IndexedMesh floor_and_wall() {
  IndexedMesh m;
  m.vertices = {{-10, -10, 0}, {10, -10, 0}, {10, 10, 0}, {-10, 10, 0},
                {3, -10, 0},   {3, 10, 0},   {3, 10, 10}, {3, -10, 10}};
  m.triangles = {{0, 1, 2}, {0, 2, 3}, {4, 6, 5}, {4, 7, 6}};
  return m;
}

Compound floor_and_wall_boxes() {
  std::vector<CompoundChild> kids;
  kids.push_back({Box::create(Vec3(10, 10, 0.5f)).value(), Transform{Vec3(0, 0, -0.5f), kIdentityQuat}});
  kids.push_back({Box::create(Vec3(0.5f, 10, 10)).value(), Transform{Vec3(3.5f, 0, 0), kIdentityQuat}});
  return Compound::create(kids).value();
}

// Regression: for meshes and compounds the step uses the directional bound along the
// current normal, which holds for two convex shapes only: here n . v = 0, so dt = +infinity,
// while the sphere reaches the wall after 2.5 s.
TEST(SafeStepRegression, NonConvexBodiesApproachingSidewaysAreNotInfinite) {
  const Sphere ball = Sphere::create(Real(0.5)).value();
  const TriangleMesh mesh = TriangleMesh::create(floor_and_wall()).value();
  const Compound boxes = floor_and_wall_boxes();
  const MovingBody a{ball, Transform{Vec3(0, 0, 1.5f), kIdentityQuat}, Vec3(1, 0, 0), Vec3(0)};
  for (const ShapeRef b : {ShapeRef(mesh), ShapeRef(boxes)}) {
    const MovingBody still{b, Transform{}, Vec3(0), Vec3(0)};
    const Real dt = safe_time_step(a, still).value();
    const Real touch = first_touch(a, still, Real(0), Real(10), 200);
    EXPECT_NEAR(touch, Real(2.5), Real(1e-3)) << to_string(b.type());
    EXPECT_LE(dt, touch) << to_string(b.type()) << ": the ball reaches the wall at " << touch;
  }
}

TEST(SafeStep, NonConvexPairsStayApartOverTheStep) {
  test::Random rng(2305);
  const TriangleMesh torus = TriangleMesh::create(test::torus_mesh(Real(1.5), Real(0.5), 16, 8)).value();
  const Compound boxes = floor_and_wall_boxes();
  CertificateTally tally;
  const int n = test::sweep_size(60);
  for (int i = 0; i < n; ++i) {
    const Shape a = random_convex(rng, kConvexKinds[std::size_t(i % 7)], rng.uniform(Real(0.2), Real(0.6)));
    MovingBody ba{a, rng.pose(Real(1)), rng.in_ball(Real(2)), i % 2 == 0 ? rng.in_ball(Real(2)) : Vec3(0)};
    MovingBody bb{torus, rng.pose(Real(0.5)), rng.in_ball(Real(0.5)), Vec3(0)};
    if (i % 3 == 2) {
      bb = MovingBody{boxes, Transform{}, Vec3(0), Vec3(0)};
      ba.pose.position = rng.vec3(Real(-3), Real(1)) + Vec3(0, 0, Real(1.5));
    } else {
      ba.pose.position = bb.pose.position + rng.vector_of_length(Real(2.5), Real(4));
    }
    certify(ba, bb, Real(0), 16, 80, tally);
  }
  print_ratios("safe step, convex against mesh or compound", tally);
  EXPECT_EQ(tally.wrong.count, 0) << tally.wrong.examples;
}

// ---------------------------------------------------------------------------------------
// The batched form and bad input

TEST(SafeStep, BatchedFormEqualsThePairFormAndReturnsTheLeast) {
  test::Random rng(2401);
  for (int round = 0; round < 30; ++round) {
    const Shape a = random_convex(rng, kConvexKinds[std::size_t(round % 10)], Real(0.6));
    const MovingBody body{a, rng.pose(Real(1)), rng.vec3(-2, 2), rng.vec3(-1, 1)};
    std::vector<Shape> shapes;
    for (int k = 0; k < 12; ++k) shapes.push_back(random_convex(rng, kConvexKinds[std::size_t(k % 10)], Real(0.6)));
    std::vector<MovingBody> others;
    for (int k = 0; k < 12; ++k) {
      others.push_back({shapes[std::size_t(k)], rng.pose(Real(5)), rng.vec3(-2, 2), rng.vec3(-1, 1)});
    }
    const Real target = round % 2 == 0 ? Real(0) : Real(0.1);
    std::vector<Real> steps(others.size(), Real(-7));
    const Result<Real> least = safe_time_steps(body, others, steps, target);
    ASSERT_TRUE(least.ok());
    Real expected = kInf;
    for (std::size_t k = 0; k < others.size(); ++k) {
      const Real pair = safe_time_step(body, others[k], target).value();
      EXPECT_EQ(steps[k], pair) << "body " << k;
      expected = std::min(expected, pair);
    }
    EXPECT_EQ(*least, expected);
  }
  // No other body: nothing limits the step.
  const Sphere ball = Sphere::create(Real(1)).value();
  const MovingBody lone{ball, Transform{}, Vec3(1, 0, 0), Vec3(0)};
  EXPECT_EQ(safe_time_steps(lone, {}, {}).value(), kInf);
}

TEST(SafeStep, EveryBadFieldIsNamed) {
  test::ScopedNoFpTraps no_traps;  // NaN inputs on purpose
  const Real nan = std::numeric_limits<Real>::quiet_NaN(), huge = kMaxCoordinate * Real(10);
  const Sphere ball = Sphere::create(Real(0.5)).value();
  const MovingBody good_a{ball, Transform{Vec3(-2, 0, 0), kIdentityQuat}, Vec3(1, 0, 0), Vec3(0, 1, 0)};
  const MovingBody good_b{ball, Transform{Vec3(2, 0, 0), kIdentityQuat}, Vec3(0), Vec3(0)};
  struct Bad {
    const char* field;
    ErrorCode code;
    MovingBody a, b;
    Real target;
  };
  std::vector<Bad> cases;
  const auto add = [&](const char* field, ErrorCode code, auto&& change) {
    Bad c{field, code, good_a, good_b, Real(0)};
    change(c);
    cases.push_back(c);
  };
  add("a.pose.position.x", ErrorCode::NotFinite, [&](Bad& c) { c.a.pose.position.x = nan; });
  add("a.pose.position.y", ErrorCode::OutOfRange, [&](Bad& c) { c.a.pose.position.y = huge; });
  add("a.pose.rotation", ErrorCode::NotFinite, [&](Bad& c) { c.a.pose.rotation.z = nan; });
  add("a.pose.rotation", ErrorCode::InvalidArgument, [&](Bad& c) { c.a.pose.rotation = Quat(0.9f, 0, 0, 0); });
  add("a.linear.z", ErrorCode::NotFinite, [&](Bad& c) { c.a.linear.z = -std::numeric_limits<Real>::infinity(); });
  add("a.angular.x", ErrorCode::NotFinite, [&](Bad& c) { c.a.angular.x = nan; });
  add("b.pose.position.z", ErrorCode::NotFinite, [&](Bad& c) { c.b.pose.position.z = nan; });
  add("b.pose.rotation", ErrorCode::InvalidArgument, [&](Bad& c) { c.b.pose.rotation = Quat(1, 1, 0, 0); });
  add("b.linear.x", ErrorCode::OutOfRange, [&](Bad& c) { c.b.linear.x = huge; });
  add("b.angular.y", ErrorCode::NotFinite, [&](Bad& c) { c.b.angular.y = nan; });
  add("target_distance", ErrorCode::Negative, [&](Bad& c) { c.target = Real(-0.1); });
  add("target_distance", ErrorCode::NotFinite, [&](Bad& c) { c.target = nan; });
  for (const Bad& c : cases) {
    const Result<Real> r = safe_time_step(c.a, c.b, c.target);
    ASSERT_FALSE(r.ok()) << c.field;
    EXPECT_EQ(r.error().field, c.field);
    EXPECT_EQ(r.error().code, c.code) << c.field << ": " << to_string(r.error().code);
  }
  // The batched form: the first bad body by its index, nothing written.
  std::vector<MovingBody> others(5, good_b);
  others[3].linear.y = nan;
  others[4].pose.position.x = nan;
  std::vector<Real> steps(others.size(), Real(-7));
  const Result<Real> batch = safe_time_steps(good_a, others, steps);
  ASSERT_FALSE(batch.ok());
  EXPECT_EQ(batch.error().field, "others[3].linear.y");
  for (const Real s : steps) EXPECT_EQ(s, Real(-7));
  MovingBody bad_a = good_a;
  bad_a.angular.z = nan;
  EXPECT_EQ(safe_time_steps(bad_a, others, steps).error().field, "a.angular.z");
  // A steps span of the wrong length.
  std::vector<Real> short_steps(2, Real(-7));
  const Result<Real> wrong_size = safe_time_steps(good_a, std::vector<MovingBody>(3, good_b), short_steps);
  ASSERT_FALSE(wrong_size.ok());
  EXPECT_EQ(wrong_size.error().field, "steps");
  EXPECT_EQ(wrong_size.error().code, ErrorCode::InvalidArgument);
  for (const Real s : short_steps) EXPECT_EQ(s, Real(-7));
  EXPECT_EQ(safe_time_steps(good_a, std::vector<MovingBody>(3, good_b), steps, Real(-1)).error().field,
            "target_distance");
}

}  // namespace test_safe_step
}  // namespace proxima
