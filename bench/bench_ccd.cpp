// Continuous collision on W6 (ccd_pairs.txt, 10,000 cases: spheres, boxes and 32-point hulls
// moving with rotation; 35 % small spheres tunnelling through thin plates): Proxima's certified
// time_of_impact against the peers' conservative advancement, in one run.
//
//   CCD/TOI/...     the cases as written (linear and angular motion):
//     proxima         proxima::time_of_impact, default options (tolerance 1e-4)
//     bullet_ca       Bullet btContinuousConvexCollision (Mirtich's conservative advancement
//                     over GJK; btSphereShape, btBoxShape and btConvexHullShape with margin 0,
//                     btGjkEpaPenetrationDepthSolver); Bullet derives the linear and angular
//                     velocity over dt = 1 from the two poses and moves the bodies with
//                     btTransformUtil::integrateTransform
//     fcl_ca_libccd   FCL fcl::continuousCollide, CCDC_CONSERVATIVE_ADVANCEMENT, CCDM_LINEAR
//     fcl_ca_indep      (fcl::InterpMotion), GST_LIBCCD or GST_INDEP
//   CCD/Linear/...  the same cases with the rotations removed (each body keeps its start
//                   orientation; the file has no case where both bodies only translate):
//     proxima_toi     proxima::time_of_impact on the translations
//     proxima_shape_cast  proxima::shape_cast of A along its displacement relative to B
//   CCD/SafeStep/...  proxima::safe_time_step_from_distance (kernel) and safe_time_step (pair
//                   form: one distance query) at the W6 start poses and velocities
//     bullet_subsimplex, bullet_gjk_cast   Bullet's linear casts btSubsimplexConvexCast and
//                     btGjkConvexCast
//
// Every library is checked against Proxima's certified bracket [t_lower, t_upper] (computed
// before timing): `misses` (Proxima Hit, the peer no hit), `false_hits` (Proxima certified
// Separated, the peer a hit), `off` (both hit, the peer's time outside
// [t_lower - 1e-3, t_upper + 1e-3]), `wrong` (their sum), `undecided` (Proxima stopped with a
// bracket only). `wrong_arcs_le_45deg` counts the wrong answers among the cases on which
// Bullet's integrateTransform follows the W6 motion (every non-sphere body turns by at most
// pi/4; see support/ccd_peers.hpp). With FCL present, Proxima's own answers are checked with
// an independent double-precision distance (FCL's GJK, tolerance 1e-9): `check_wrong` on the
// Proxima rows (a Hit farther apart than its tolerance at t_upper, or a contact at one of 16
// sampled times in [0, t_lower]) and `refutes_proxima` on the peer rows (a false hit or an
// early hit at whose time the shapes do touch, which would make the peer right and Proxima
// wrong). Shapes and motions are converted to each library's types before timing.
#include <benchmark/benchmark.h>

#include <proxima/ccd/safe_step.hpp>
#include <proxima/ccd/shape_cast.hpp>
#include <proxima/ccd/time_of_impact.hpp>
#include <proxima/narrowphase/narrowphase.hpp>

#include <cstdint>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "bench_main.hpp"
#include "support/ccd_peers.hpp"
#include "support/workloads.hpp"

namespace {

namespace pb = proxima::bench;
using proxima::CcdStatus;
using proxima::ToiResult;

constexpr int kCheckSamples = 16;

/// One set of cases (the W6 cases, or the same with the rotations removed), in every
/// library's types, with Proxima's answers as the reference.
struct CaseSet {
  std::vector<pb::CcdCase> cases;
  std::optional<pb::ProximaCcdCases> proxima;
  std::vector<ToiResult> reference;  // Proxima, default options
  std::vector<char> bullet_exact;    // Bullet's motion is W6's on the whole step
  double mean_iterations = 0;
  std::uint64_t check_wrong = 0;
  bool checked = false;
#if PROXIMA_HAVE_BULLET
  std::unique_ptr<pb::BulletCcdCases> bullet;
#endif
#if PROXIMA_HAVE_FCL
  std::unique_ptr<pb::FclCcdCases> fcl;
#endif
};

pb::CcdHulls g_hulls;
CaseSet g_rotating;  // W6 as written
CaseSet g_linear;    // rotations removed

bool prepare(CaseSet& set, std::vector<pb::CcdCase> cases, const char* name) {
  set.cases = std::move(cases);
  auto p = pb::proxima_ccd_cases(set.cases, g_hulls);
  if (!p) return pb::report_load_error(p.error());
  set.proxima = std::move(*p);
  const proxima::ToiOptions options;
  std::uint64_t iterations = 0, hits = 0, separated = 0, other = 0;
  for (std::size_t k = 0; k < set.cases.size(); ++k) {
    auto r =
        proxima::time_of_impact(set.proxima->a[k], set.proxima->ma[k], set.proxima->b[k], set.proxima->mb[k], options);
    if (!r) return pb::report_load_error(r.error());
    set.reference.push_back(*r);
    iterations += static_cast<std::uint64_t>(r->iterations);
    hits += r->status == CcdStatus::Hit ? 1u : 0u;
    separated += r->status == CcdStatus::Separated ? 1u : 0u;
    other += r->status != CcdStatus::Hit && r->status != CcdStatus::Separated ? 1u : 0u;
    set.bullet_exact.push_back(pb::bullet_model_exact(set.cases[k]) ? 1 : 0);
  }
  set.mean_iterations = static_cast<double>(iterations) / static_cast<double>(set.cases.size());
#if PROXIMA_HAVE_BULLET
  set.bullet = std::make_unique<pb::BulletCcdCases>(set.cases, g_hulls);
#endif
#if PROXIMA_HAVE_FCL
  set.fcl = std::make_unique<pb::FclCcdCases>(set.cases, g_hulls);
  const pb::ProximaCheck check = pb::check_proxima(set.cases, g_hulls, set.reference, *set.fcl, kCheckSamples);
  set.check_wrong = check.wrong();
  set.checked = true;
  std::fprintf(
      stderr,
      "%s: Proxima hit %llu, separated %llu, other %llu, mean iterations %.3f; independent check: %llu hits "
      "(%llu not confirmed, worst excess over the tolerance %.3g), %llu sampled times (%llu in contact)\n",
      name, static_cast<unsigned long long>(hits), static_cast<unsigned long long>(separated),
      static_cast<unsigned long long>(other), set.mean_iterations, static_cast<unsigned long long>(check.hits_checked),
      static_cast<unsigned long long>(check.hits_not_confirmed), check.worst_hit_excess,
      static_cast<unsigned long long>(check.samples), static_cast<unsigned long long>(check.samples_in_contact));
#else
  std::fprintf(stderr, "%s: Proxima hit %llu, separated %llu, other %llu, mean iterations %.3f (no FCL: unchecked)\n",
               name, static_cast<unsigned long long>(hits), static_cast<unsigned long long>(separated),
               static_cast<unsigned long long>(other), set.mean_iterations);
#endif
  return true;
}

// -------------------------------------------------------------------------------------
// Proxima
// -------------------------------------------------------------------------------------

void proxima_toi(benchmark::State& state, const CaseSet* set) {
  const pb::ProximaCcdCases& p = *set->proxima;
  const std::size_t n = set->cases.size();
  const proxima::ToiOptions options;  // tolerance 1e-4, target 0
  std::uint64_t hits = 0, separated = 0, undecided = 0, iterations = 0;
  for (auto _ : state) {
    hits = separated = undecided = iterations = 0;
    for (std::size_t k = 0; k < n; ++k) {
      const auto r = proxima::time_of_impact(p.a[k], p.ma[k], p.b[k], p.mb[k], options);
      if (!r) {
        ++undecided;
        continue;
      }
      hits += r->status == CcdStatus::Hit ? 1u : 0u;
      separated += r->status == CcdStatus::Separated ? 1u : 0u;
      undecided += r->status == CcdStatus::MaxIterations || r->status == CcdStatus::Failed ? 1u : 0u;
      iterations += static_cast<std::uint64_t>(r->iterations);
    }
    benchmark::DoNotOptimize(hits);
    benchmark::DoNotOptimize(iterations);
  }
  state.counters["per_query"] = pb::time_per_item(n);
  state.counters["hits"] = static_cast<double>(hits);
  state.counters["separated"] = static_cast<double>(separated);
  state.counters["undecided"] = static_cast<double>(undecided);
  state.counters["iterations"] = static_cast<double>(iterations) / static_cast<double>(n);
  if (set->checked) state.counters["check_wrong"] = static_cast<double>(set->check_wrong);
}

// Proxima's linear shape cast on the rotation-free set: A cast along its displacement
// relative to B, B still at its start pose (the same query as the time of impact of two
// translations).
void proxima_cast(benchmark::State& state, const CaseSet* set) {
  const pb::ProximaCcdCases& p = *set->proxima;
  const std::size_t n = set->cases.size();
  std::uint64_t hits = 0, iterations = 0;
  for (auto _ : state) {
    hits = iterations = 0;
    for (std::size_t k = 0; k < n; ++k) {
      const proxima::Vec3 s = p.ma[k].displacement() - p.mb[k].displacement();
      const auto r = proxima::shape_cast(p.a[k], p.ma[k].start, s, p.b[k], p.mb[k].start);
      if (!r) continue;
      hits += r->status == CcdStatus::Hit ? 1u : 0u;
      iterations += static_cast<std::uint64_t>(r->iterations);
    }
    benchmark::DoNotOptimize(hits);
  }
  state.counters["per_query"] = pb::time_per_item(n);
  state.counters["hits"] = static_cast<double>(hits);
  state.counters["iterations"] = static_cast<double>(iterations) / static_cast<double>(n);
}

// Safe time steps on W6's start poses: the kernel alone (the gap along the normal already
// known, as a world that keeps its pairs' distances has it) and the pair form (one narrow-phase
// distance query), with each body's linear and angular velocity over the step. `kind`: 0 the
// kernel over every case, 1 the pair form over the sphere-sphere cases, 2 over every case.
void proxima_safe_step(benchmark::State& state, const CaseSet* set, int kind) {
  const pb::ProximaCcdCases& p = *set->proxima;
  std::vector<proxima::MovingBody> a, b;
  std::vector<proxima::Real> gaps;
  std::vector<proxima::Vec3> normals;
  for (std::size_t k = 0; k < set->cases.size(); ++k) {
    const bool spheres =
        std::holds_alternative<proxima::Sphere>(p.a[k]) && std::holds_alternative<proxima::Sphere>(p.b[k]);
    if (kind == 1 && !spheres) continue;
    a.push_back({p.a[k], p.ma[k].start, p.ma[k].displacement(), p.ma[k].angular_velocity()});
    b.push_back({p.b[k], p.mb[k].start, p.mb[k].displacement(), p.mb[k].angular_velocity()});
    const proxima::DistanceResult d = proxima::distance(p.a[k], p.ma[k].start, p.b[k], p.mb[k].start);
    gaps.push_back(d.signed_distance);
    normals.push_back(d.normal);
  }
  const std::size_t n = a.size();
  double sum = 0;
  for (auto _ : state) {
    sum = 0;
    for (std::size_t k = 0; k < n; ++k) {
      const proxima::Real dt = kind == 0 ? proxima::safe_time_step_from_distance(
                                               gaps[k], normals[k], a[k].linear, a[k].angular, proxima::Real(1),
                                               b[k].linear, b[k].angular, proxima::Real(1), proxima::Real(0))
                                         : *proxima::safe_time_step(a[k], b[k]);
      sum += dt < proxima::Real(1e30) ? double(dt) : 0.0;
    }
    benchmark::DoNotOptimize(sum);
  }
  state.counters["per_query"] = pb::time_per_item(n);
  state.counters["pairs"] = static_cast<double>(n);
}

// -------------------------------------------------------------------------------------
// The peers: timing, then one untimed pass judged against Proxima's bracket
// -------------------------------------------------------------------------------------

template <class Query>
void peer_toi(benchmark::State& state, const CaseSet* set, Query query) {
  const std::size_t n = set->cases.size();
  std::uint64_t hits = 0;
  double sum = 0;
  for (auto _ : state) {
    hits = 0;
    sum = 0;
    for (std::size_t k = 0; k < n; ++k) {
      const pb::PeerToi a = query(k);
      hits += a.hit ? 1u : 0u;
      sum += a.toi;
    }
    benchmark::DoNotOptimize(hits);
    benchmark::DoNotOptimize(sum);
  }
  pb::PeerTally all, exact;
  std::uint64_t refutes = 0;
  for (std::size_t k = 0; k < n; ++k) {
    const pb::PeerToi a = query(k);
    const ToiResult& r = set->reference[k];
    const pb::PeerVerdict v = pb::judge_peer(r, a);
    all.add(a, v);
    if (set->bullet_exact[k] != 0) exact.add(a, v);
#if PROXIMA_HAVE_FCL
    const bool early =
        v == pb::PeerVerdict::FalseHit || (v == pb::PeerVerdict::Off && a.toi < static_cast<double>(r.t_lower));
    if (early && set->fcl->distance_at(k, a.toi) <= 0) ++refutes;
#endif
  }
  state.counters["per_query"] = pb::time_per_item(n);
  state.counters["hits"] = static_cast<double>(all.hits);
  state.counters["misses"] = static_cast<double>(all.misses);
  state.counters["false_hits"] = static_cast<double>(all.false_hits);
  state.counters["off"] = static_cast<double>(all.off);
  state.counters["wrong"] = static_cast<double>(all.wrong());
  state.counters["undecided"] = static_cast<double>(all.undecided);
  state.counters["wrong_arcs_le_45deg"] = static_cast<double>(exact.wrong());
#if PROXIMA_HAVE_FCL
  state.counters["refutes_proxima"] = static_cast<double>(refutes);
#endif
}

#if PROXIMA_HAVE_BULLET
void bullet_toi(benchmark::State& state, const CaseSet* set, pb::BulletCast method) {
  const pb::BulletCcdCases& b = *set->bullet;
  peer_toi(state, set, [&](std::size_t k) { return b.query(k, method); });
}
#endif

#if PROXIMA_HAVE_FCL
void fcl_toi(benchmark::State& state, const CaseSet* set, fcl::GJKSolverType solver) {
  const pb::FclCcdCases& f = *set->fcl;
  peer_toi(state, set, [&](std::size_t k) { return f.query(k, solver); });
}
#endif

// -------------------------------------------------------------------------------------
// Registration
// -------------------------------------------------------------------------------------

template <class... Args>
void add(const std::string& name, Args&&... args) {
  benchmark::RegisterBenchmark(name.c_str(), std::forward<Args>(args)...)->Unit(benchmark::kMicrosecond);
}

bool register_ccd(const std::string& dir) {
  auto workload = pb::read_ccd_workload(dir);
  if (!workload) return pb::report_load_error(workload.error());
  auto hulls = pb::build_ccd_hulls(workload->hulls);
  if (!hulls) return pb::report_load_error(hulls.error());
  g_hulls = std::move(*hulls);
  const std::vector<pb::CcdCase>& cases = workload->pairs.cases;
  std::vector<pb::CcdCase> linear;
  for (const pb::CcdCase& c : cases) linear.push_back(pb::without_rotation(c));
  if (!prepare(g_rotating, cases, "W6") || !prepare(g_linear, std::move(linear), "W6 without rotation")) return false;

  std::string peers;
#if PROXIMA_HAVE_FCL
  peers += " fcl";
#endif
#if PROXIMA_HAVE_BULLET
  peers += " bullet";
#endif
  benchmark::AddCustomContext("peers", peers.empty() ? "none" : peers.substr(1));
  std::uint64_t exact = 0;
  for (char e : g_rotating.bullet_exact) exact += e != 0 ? 1u : 0u;
  benchmark::AddCustomContext("w6_cases_arcs_le_45deg", std::to_string(exact));
  benchmark::AddCustomContext("w6_proxima_mean_iterations", std::to_string(g_rotating.mean_iterations));

  add("CCD/TOI/proxima", proxima_toi, &g_rotating);
#if PROXIMA_HAVE_BULLET
  add("CCD/TOI/bullet_ca", bullet_toi, &g_rotating, pb::BulletCast::ConservativeAdvancement);
#endif
#if PROXIMA_HAVE_FCL
  add("CCD/TOI/fcl_ca_libccd", fcl_toi, &g_rotating, fcl::GST_LIBCCD);
  add("CCD/TOI/fcl_ca_indep", fcl_toi, &g_rotating, fcl::GST_INDEP);
#endif

  add("CCD/Linear/proxima_toi", proxima_toi, &g_linear);
  add("CCD/Linear/proxima_shape_cast", proxima_cast, &g_linear);
  add("CCD/SafeStep/kernel", proxima_safe_step, &g_rotating, 0);
  add("CCD/SafeStep/pair_spheres", proxima_safe_step, &g_rotating, 1);
  add("CCD/SafeStep/pair_all", proxima_safe_step, &g_rotating, 2);
#if PROXIMA_HAVE_BULLET
  add("CCD/Linear/bullet_subsimplex", bullet_toi, &g_linear, pb::BulletCast::Subsimplex);
  add("CCD/Linear/bullet_gjk_cast", bullet_toi, &g_linear, pb::BulletCast::Gjk);
#endif
  return true;
}

}  // namespace

int main(int argc, char** argv) { return pb::run_benchmarks(argc, argv, register_ccd); }
