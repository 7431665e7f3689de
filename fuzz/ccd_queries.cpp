// Fuzz target: the continuous queries, time_of_impact and shape_cast, on pairs of convex
// shapes with arbitrary motions. With valid input both answer (no Error, status not Failed)
// and:
//   1. every number is finite; toi, t_lower, t_upper and a cast's t lie in [0, 1], with
//      t_lower <= t_upper; the normal is unit;
//   2. the certificate: for pairs apart by more than target + tolerance at t = 0, the shapes
//      are apart by more than the target (less the tolerance) at sampled times of
//      [0, t_lower) (closer at t = 0, the t = 0 contract answers), and at a Hit they are
//      within the target distance plus the tolerance, measured by the narrow phase;
//   3. a cast's Hit at t leaves A (moved by t * translation) within target + tolerance of B,
//      and A is not closer than the target at sampled times before t (pairs apart at t = 0).
// Tolerance: the query's own (1e-4, raised to 64 epsilon of the pair's scale) plus 1e-3
// (float) or 1e-6 (double) of the scale.
// Input: shape A, shape B, start and end poses of A and B, the options, a translation.
#include <proxima/ccd/shape_cast.hpp>
#include <proxima/ccd/time_of_impact.hpp>
#include <proxima/core/tolerance.hpp>
#include <proxima/narrowphase/narrowphase.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "fuzz_shapes.hpp"

namespace pf = proxima::fuzz;
using namespace proxima;

namespace {

constexpr Real kRelative = sizeof(Real) == 4 ? Real(1e-3) : Real(1e-6);

Real gap(const pf::FuzzShape& a, const Transform& pa, const pf::FuzzShape& b, const Transform& pb) {
  const Real d = distance(a.shape, pa, b.shape, pb).signed_distance;
  pf::check_finite(d, "distance at a sampled time not finite");
  return d;
}

void check_toi(const pf::FuzzShape& a, const Motion& ma, const pf::FuzzShape& b, const Motion& mb,
               const ToiOptions& options, Real tol) {
  const Result<ToiResult> r = time_of_impact(a.shape, ma, b.shape, mb, options);
  pf::check(r.ok(), "time_of_impact refused valid input");
  const ToiResult& t = r.value();
  pf::failure_context() = [&] {
    std::fprintf(stderr, "  shape types %d, %d; status %d, toi %.9g, t_lower %.9g, t_upper %.9g, iterations %d\n",
                 static_cast<int>(a.shape.index()), static_cast<int>(b.shape.index()), static_cast<int>(t.status),
                 double(t.toi), double(t.t_lower), double(t.t_upper), t.iterations);
    for (int i = 0; i <= 4; ++i) {
      const Real s = t.t_lower * static_cast<Real>(i) / Real(4) * Real(0.999);
      std::fprintf(stderr, "  t %.9g: distance %.9g (target %.9g, tolerance %.9g)\n", double(s),
                   double(distance(a.shape, ma.at(s), b.shape, mb.at(s)).signed_distance),
                   double(options.target_distance), double(tol));
    }
  };
  pf::check(t.status != CcdStatus::Failed, "time_of_impact: status Failed");
  for (Real x : {t.toi, t.t_lower, t.t_upper, t.distance, t.depth}) pf::check_finite(x, "toi: value not finite");
  for (const Vec3& v : {t.point, t.point_a, t.point_b, t.normal}) pf::check_finite(v, "toi: point not finite");
  pf::check(t.toi >= 0 && t.toi <= 1 && t.t_lower >= 0 && t.t_upper <= 1, "toi: time outside [0, 1]");
  pf::check(t.t_lower <= t.t_upper, "toi: t_lower > t_upper");
  pf::check(std::abs(glm::length(t.normal) - Real(1)) <= Real(1e-3), "toi: normal not unit");
  if (t.status == CcdStatus::Hit) {
    pf::check(gap(a, ma.at(t.toi), b, mb.at(t.toi)) <= options.target_distance + tol, "toi: Hit but apart at toi");
  }
  // The certificate holds on [0, t_lower) for pairs apart by more than target + tolerance at
  // t = 0; closer at t = 0 the t = 0 contract answers (Hit when approaching, else Separated).
  const bool apart_at_start = gap(a, ma.start, b, mb.start) > options.target_distance + tol;
  if (t.status != CcdStatus::InitiallyOverlapping && apart_at_start) {
    for (int i = 0; i <= 4; ++i) {
      const Real s = t.t_lower * static_cast<Real>(i) / Real(4) * Real(0.999);
      pf::check(gap(a, ma.at(s), b, mb.at(s)) >= options.target_distance - tol,
                "toi: closer than target before t_lower");
    }
  }
}

void check_cast(const pf::FuzzShape& a, const Transform& pa, const Vec3& translation, const pf::FuzzShape& b,
                const Transform& pb, const CastOptions& options, Real tol) {
  const Result<CastResult> r = shape_cast(a.shape, pa, translation, b.shape, pb, options);
  pf::check(r.ok(), "shape_cast refused valid input");
  const CastResult& c = r.value();
  pf::check(c.status != CcdStatus::Failed, "shape_cast: status Failed");
  for (Real x : {c.t, c.distance, c.depth}) pf::check_finite(x, "cast: value not finite");
  for (const Vec3& v : {c.point, c.point_a, c.point_b, c.normal}) pf::check_finite(v, "cast: point not finite");
  pf::check(c.t >= 0 && c.t <= 1, "cast: t outside [0, 1]");
  pf::check(std::abs(glm::length(c.normal) - Real(1)) <= Real(1e-3), "cast: normal not unit");
  const auto at = [&](Real t) { return Transform{pa.position + t * translation, pa.rotation}; };
  if (c.status == CcdStatus::Hit) {
    pf::check(gap(a, at(c.t), b, pb) <= options.target_distance + tol, "cast: Hit but apart at t");
  }
  if ((c.status == CcdStatus::Hit || c.status == CcdStatus::Separated) &&
      gap(a, pa, b, pb) > options.target_distance + tol) {
    for (int i = 0; i <= 4; ++i) {
      const Real s = c.t * static_cast<Real>(i) / Real(4) * Real(0.999);
      pf::check(gap(a, at(s), b, pb) >= options.target_distance - tol, "cast: closer than target before t");
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  pf::start_target();
  pf::ByteReader in(data, size);
  const std::optional<pf::FuzzShape> a = pf::read_convex(in);
  const std::optional<pf::FuzzShape> b = pf::read_convex(in);
  const std::optional<Transform> a0 = pf::read_pose(in);
  const std::optional<Transform> a1 = pf::read_pose(in);
  const std::optional<Transform> b0 = pf::read_pose(in);
  const std::optional<Transform> b1 = pf::read_pose(in);
  if (!a || !b || !a0 || !a1 || !b0 || !b1) return 0;
  const Real target = in.flag() ? in.in_range(0, 1) : Real(0);
  const Real tolerance = in.flag() ? Real(1e-4) : in.log_range(Real(1e-6), Real(1e-1));
  // Moving: B's motion is its start pose alone for a third of the inputs.
  const Motion ma{*a0, *a1};
  const Motion mb = in.byte() % 3 == 0 ? Motion::stationary(*b0) : Motion{*b0, *b1};
  const Real reach = glm::length(ma.displacement()) + glm::length(mb.displacement()) + a->reach + b->reach;
  const Real scale = reach + glm::length(a0->position - b0->position);
  const Real tol = std::max(tolerance, Real(64) * kEpsilon * scale) + kRelative * std::max(Real(1), scale);

  ToiOptions toi;
  toi.target_distance = target;
  toi.tolerance = tolerance;
  check_toi(*a, ma, *b, mb, toi, tol);

  CastOptions cast;
  cast.target_distance = target;
  cast.tolerance = tolerance;
  check_cast(*a, *a0, a1->position - a0->position, *b, *b0, cast, tol);
  return 0;
}
