// time_of_impact on the shared W6 workload (ccd_pairs.txt, 10,000 moving pairs of spheres,
// boxes and hulls) beside the peers' continuous queries: Bullet's btContinuousConvexCollision
// and FCL's continuousCollide (conservative advancement, InterpMotion, GJK from libccd and
// FCL's own), with the conversions of support/ccd_peers.hpp.
//
// Asserted (what must hold of Proxima): every answer is consistent (a value, no failure,
// 0 <= t_lower <= t_upper <= 1, a Hit at a finite toi = t_upper in [0, 1] with its distance
// within the tolerance, Separated at 1, iterations within the cap; no InitiallyOverlapping, as
// the file's pairs are disjoint at t = 0). With FCL, an independent double-precision distance
// checks each Hit at t_upper, and arbitrates the peers' disagreements: no peer may find the
// shapes touching at a time Proxima certified apart.
// Recorded, not asserted: each peer's disagreements with Proxima's certified bracket (misses,
// false hits, times off by more than 1e-3), printed and attached as test properties; a
// peer's wrong answer is not a failure of Proxima's.
#include <gtest/gtest.h>

#include <proxima/ccd/time_of_impact.hpp>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "support/ccd_peers.hpp"
#include "support/random.hpp"
#include "support/workloads.hpp"

namespace proxima {
namespace test_ccd_peers {

namespace pb = bench;

/// The W6 cases and Proxima's answers, loaded once. Null with `problem` empty when the
/// shared workload is absent (skip), with `problem` set when it is there but unusable (fail).
struct W6 {
  std::vector<pb::CcdCase> cases;
  pb::CcdHulls hulls;
  std::vector<ToiResult> results;
};

const W6* load(std::string& problem) {
  static W6 w;
  static bool tried = false;
  static const W6* loaded = nullptr;
  static std::string why;
  if (!tried) {
    tried = true;
    const std::string dir = pb::workload_dir();
    if (std::filesystem::exists(pb::workload_path(dir, "ccd_pairs.txt"))) {
      auto workload = pb::read_ccd_workload(dir);
      auto hulls = workload ? pb::build_ccd_hulls(workload->hulls) : Result<pb::CcdHulls>(workload.error());
      if (!workload) {
        why = workload.error().what();
      } else if (!hulls) {
        why = hulls.error().what();
      } else {
        w.cases = workload->pairs.cases;
        w.hulls = std::move(*hulls);
        auto shapes = pb::proxima_ccd_cases(w.cases, w.hulls);
        if (!shapes) {
          why = shapes.error().what();
        } else {
          for (std::size_t k = 0; k < w.cases.size() && why.empty(); ++k) {
            auto r = time_of_impact(shapes->a[k], shapes->ma[k], shapes->b[k], shapes->mb[k]);
            if (!r) {
              why = "case " + std::to_string(k) + ": " + r.error().what();
            } else {
              w.results.push_back(*r);
            }
          }
          if (why.empty()) loaded = &w;
        }
      }
    }
  }
  problem = why;
  return loaded;
}

#define PROXIMA_CCD_LOAD(w)                                                                            \
  std::string problem;                                                                                 \
  const W6* w = load(problem);                                                                         \
  if (w == nullptr && !problem.empty()) FAIL() << problem;                                             \
  if (w == nullptr) GTEST_SKIP() << "no shared W6 workload (ccd_pairs.txt) in " << pb::workload_dir(); \
  do {                                                                                                 \
  } while (false)

TEST(CcdPeers, ProximaAnswersAreConsistent) {
  PROXIMA_CCD_LOAD(w);
  const ToiOptions options;
  int hits = 0, separated = 0;
  double iterations = 0;
  for (std::size_t k = 0; k < w->results.size(); ++k) {
    const ToiResult& r = w->results[k];
    SCOPED_TRACE("case " + std::to_string(k) + " status " + to_string(r.status));
    ASSERT_TRUE(r.status == CcdStatus::Hit || r.status == CcdStatus::Separated || r.status == CcdStatus::MaxIterations);
    EXPECT_LE(Real(0), r.t_lower);
    EXPECT_LE(r.t_lower, r.t_upper);
    EXPECT_LE(r.t_upper, Real(1));
    EXPECT_GE(r.iterations, 1);
    EXPECT_LE(r.iterations, options.max_iterations);
    iterations += r.iterations;
    if (r.status == CcdStatus::Hit) {
      ++hits;
      EXPECT_TRUE(std::isfinite(r.toi));
      EXPECT_EQ(r.toi, r.t_upper);
      EXPECT_GE(r.toi, Real(0));
      EXPECT_LE(r.toi, Real(1));
      const double tol = pb::ccd_effective_tolerance(w->cases[k], w->hulls, 1e-4);
      EXPECT_LE(static_cast<double>(r.distance), tol * (1 + 1e-3));  // the scale rounds differently in Real
      EXPECT_NEAR(glm::length(r.normal), Real(1), Real(1e-4));
    } else if (r.status == CcdStatus::Separated) {
      ++separated;
      EXPECT_EQ(r.toi, Real(1));
      EXPECT_EQ(r.t_lower, Real(1));
    }
  }
  const double mean = iterations / static_cast<double>(w->results.size());
  std::printf("[ W6 ] Proxima: %d hits, %d separated, %zu bracketed, %.3f distance queries per case\n", hits, separated,
              w->results.size() - static_cast<std::size_t>(hits + separated), mean);
  RecordProperty("proxima_hits", hits);
  RecordProperty("proxima_separated", separated);
}

#if PROXIMA_HAVE_BULLET || PROXIMA_HAVE_FCL
/// Runs one peer over every case, prints and records its disagreements with Proxima, and
/// (with FCL) fails when the independent distance shows a disagreement is Proxima's error.
void compare_peer(const W6& w, const std::string& name, const std::function<pb::PeerToi(std::size_t)>& query) {
  pb::PeerTally all, exact;
  std::uint64_t off_early = 0, off_late = 0, early_within_skin = 0, early_apart = 0, misses_touching = 0;
  [[maybe_unused]] std::uint64_t refuted = 0;
  std::vector<std::string> examples;
#if PROXIMA_HAVE_FCL
  const pb::FclCcdCases fcl(w.cases, w.hulls);
#endif
  for (std::size_t k = 0; k < w.cases.size(); ++k) {
    pb::PeerToi a;
    {
      test::ScopedNoFpTraps no_traps;  // the peers' GJK may divide by zero on degenerate simplices
      a = query(k);
    }
    const ToiResult& r = w.results[k];
    const pb::PeerVerdict v = pb::judge_peer(r, a);
    all.add(a, v);
    if (pb::bullet_model_exact(w.cases[k])) exact.add(a, v);
    const bool early =
        v == pb::PeerVerdict::FalseHit || (v == pb::PeerVerdict::Off && a.toi < static_cast<double>(r.t_lower));
    if (v == pb::PeerVerdict::Off) ++(early ? off_early : off_late);
#if PROXIMA_HAVE_FCL
    if (v == pb::PeerVerdict::Miss) {
      // A miss of a real contact, or of a graze within the tolerance: the shapes touch when the
      // distance reaches 0 within 0.02 after Proxima's time (41 samples).
      test::ScopedNoFpTraps no_traps;
      for (int j = 0; j <= 40; ++j) {
        if (fcl.distance_at(k, std::min(1.0, static_cast<double>(r.t_upper) + 0.0005 * j)) <= 0) {
          ++misses_touching;
          break;
        }
      }
    }
    if (early) {
      test::ScopedNoFpTraps no_traps;
      const double d = fcl.distance_at(k, a.toi);
      if (d <= 0) {
        ++refuted;
        if (examples.size() < 5) {
          examples.push_back("case " + std::to_string(k) + ": " + name + " hit at " + std::to_string(a.toi) +
                             " (distance " + std::to_string(d) + "), Proxima " + to_string(r.status) + " t_lower " +
                             std::to_string(r.t_lower));
        }
      } else if (d <= 1.1e-3) {
        ++early_within_skin;
      } else {
        ++early_apart;
      }
    }
#endif
  }
  std::printf(
      "[ W6 ] %-16s hits %5llu  misses %4llu  false hits %4llu  off by > 1e-3 %5llu (early %llu, late %llu)  wrong "
      "%5llu"
      "  (arcs <= 45 deg: %llu of %llu cases)  undecided %llu\n",
      name.c_str(), static_cast<unsigned long long>(all.hits), static_cast<unsigned long long>(all.misses),
      static_cast<unsigned long long>(all.false_hits), static_cast<unsigned long long>(all.off),
      static_cast<unsigned long long>(off_early), static_cast<unsigned long long>(off_late),
      static_cast<unsigned long long>(all.wrong()), static_cast<unsigned long long>(exact.wrong()),
      static_cast<unsigned long long>(exact.agree + exact.wrong() + exact.undecided),
      static_cast<unsigned long long>(all.undecided));
#if PROXIMA_HAVE_FCL
  std::printf(
      "[ W6 ] %-16s misses: %llu of real contacts (the shapes touch within 0.02 after Proxima's time); false or early "
      "hits: %llu where the shapes are still apart by <= 1.1e-3 at the peer's time, %llu farther apart, %llu touching "
      "(Proxima refuted)\n",
      name.c_str(), static_cast<unsigned long long>(misses_touching),
      static_cast<unsigned long long>(early_within_skin), static_cast<unsigned long long>(early_apart),
      static_cast<unsigned long long>(refuted));
#endif
  ::testing::Test::RecordProperty(name + "_misses", static_cast<int>(all.misses));
  ::testing::Test::RecordProperty(name + "_false_hits", static_cast<int>(all.false_hits));
  ::testing::Test::RecordProperty(name + "_off", static_cast<int>(all.off));
#if PROXIMA_HAVE_FCL
  EXPECT_EQ(refuted, 0u) << "the shapes touch where Proxima certified them apart, e.g. "
                         << (examples.empty() ? std::string() : examples.front());
#endif
}
#endif

TEST(CcdPeers, BulletConservativeAdvancement) {
#if PROXIMA_HAVE_BULLET
  PROXIMA_CCD_LOAD(w);
  const pb::BulletCcdCases bullet(w->cases, w->hulls);
  compare_peer(*w, "bullet_ca",
               [&](std::size_t k) { return bullet.query(k, pb::BulletCast::ConservativeAdvancement); });
#else
  GTEST_SKIP() << "Bullet not found";
#endif
}

TEST(CcdPeers, FclConservativeAdvancement) {
#if PROXIMA_HAVE_FCL
  PROXIMA_CCD_LOAD(w);
  const pb::FclCcdCases fcl(w->cases, w->hulls);
  compare_peer(*w, "fcl_ca_libccd", [&](std::size_t k) { return fcl.query(k, fcl::GST_LIBCCD); });
  compare_peer(*w, "fcl_ca_indep", [&](std::size_t k) { return fcl.query(k, fcl::GST_INDEP); });
#else
  GTEST_SKIP() << "FCL not found";
#endif
}

TEST(CcdPeers, ProximaHitsConfirmedIndependently) {
#if PROXIMA_HAVE_FCL
  PROXIMA_CCD_LOAD(w);
  const pb::FclCcdCases fcl(w->cases, w->hulls);
  test::ScopedNoFpTraps no_traps;
  const pb::ProximaCheck check = pb::check_proxima(w->cases, w->hulls, w->results, fcl, 0);
  std::printf(
      "[ W6 ] Proxima hits checked with FCL's double distance: %llu, not within the tolerance: %llu "
      "(largest excess %.3g)\n",
      static_cast<unsigned long long>(check.hits_checked), static_cast<unsigned long long>(check.hits_not_confirmed),
      check.worst_hit_excess);
  EXPECT_EQ(check.hits_not_confirmed, 0u);
#else
  GTEST_SKIP() << "FCL not found: no independent distance";
#endif
}

}  // namespace test_ccd_peers
}  // namespace proxima
