// The closed-form curved pairs (sphere-cylinder, sphere-cone, sphere-ellipsoid, cylinders with
// parallel axes, coaxial cones) against the generic GJK / EPA path they replaced, on the same seeded poses:
// 4,096 pairs per shape kind (a sphere of radius 0.2..1 and a cylinder or cone of radius and
// half length 0.2..1.5, or an ellipsoid of radii 0.2..1.5, or two such cylinders, the second
// turned about its axis, B's centre within 1.8 of A's, so that about half overlap; or two cones
// on one axis, B turned about it and flipped every other pair), each query
// kind through the public entry
// (`intersect`, `distance`, `collide`: the closed form) and through narrow::generic_distance
// / generic_intersect (GJK, EPA on overlaps, its refinement). Reports ns per query and the
// share of overlapping pairs.
#include <benchmark/benchmark.h>

#include <proxima/narrowphase/narrowphase.hpp>
#include <proxima/shapes/shape.hpp>

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include "bench_main.hpp"
#include "narrowphase/generic_distance.hpp"
#include "support/random.hpp"

namespace {

using proxima::Real;
using proxima::Transform;

/// One pair of the benchmark: a sphere or cylinder (A) and the curved shape (B) with their
/// poses.
template <class A, class B>
struct CurvedPair {
  A a;
  Transform pose_a;
  B b;
  Transform pose_b;
};

/// A cylinder or cone of radius and half length 0.2..1.5.
template <class B>
B random_curved(proxima::test::Random& rng) {
  return B::create(rng.uniform(Real(0.2), Real(1.5)), rng.uniform(Real(0.2), Real(1.5))).value();
}

/// An ellipsoid of radii 0.2..1.5.
template <>
proxima::Ellipsoid random_curved<proxima::Ellipsoid>(proxima::test::Random& rng) {
  const proxima::Vec3 radii(rng.uniform(Real(0.2), Real(1.5)), rng.uniform(Real(0.2), Real(1.5)),
                            rng.uniform(Real(0.2), Real(1.5)));
  return proxima::Ellipsoid::create(radii).value();
}

template <class B>
std::vector<CurvedPair<proxima::Sphere, B>> make_pairs(std::uint64_t seed) {
  proxima::test::Random rng(seed);
  std::vector<CurvedPair<proxima::Sphere, B>> pairs;
  for (int i = 0; i < 4096; ++i) {
    const proxima::Sphere a = proxima::Sphere::create(rng.uniform(Real(0.2), Real(1))).value();
    const B b = random_curved<B>(rng);
    const Transform pa = rng.pose(Real(0.9));
    const Transform pb = rng.pose(Real(0.9));
    pairs.push_back({a, pa, b, pb});
  }
  return pairs;
}

/// 4,096 pairs of two shapes S, B placed against A by `place(rng, a, b, pose_a, i)`.
template <class S, class Place>
std::vector<CurvedPair<S, S>> make_placed_pairs(std::uint64_t seed, Place place) {
  proxima::test::Random rng(seed);
  std::vector<CurvedPair<S, S>> pairs;
  for (int i = 0; i < 4096; ++i) {
    const S a = random_curved<S>(rng);
    const S b = random_curved<S>(rng);
    const Transform pa = rng.pose(Real(0.9));
    pairs.push_back({a, pa, b, place(rng, a, b, pa, i)});
  }
  return pairs;
}

const proxima::Vec3 kAxisX(Real(1), Real(0), Real(0));
const proxima::Vec3 kAxisZ(Real(0), Real(0), Real(1));

/// Two cylinders with parallel axes: B has A's rotation turned about the axis.
std::vector<CurvedPair<proxima::Cylinder, proxima::Cylinder>> make_parallel_cylinders(std::uint64_t seed) {
  return make_placed_pairs<proxima::Cylinder>(seed, [](proxima::test::Random& rng, const proxima::Cylinder&,
                                                       const proxima::Cylinder&, const Transform& pa, int) {
    const proxima::Vec3 offset = rng.in_ball(Real(1.8));
    return Transform{pa.position + offset, pa.rotation * glm::angleAxis(rng.uniform(Real(0), Real(6.283)), kAxisZ)};
  });
}

/// Two coaxial cones: B on A's axis (1.8 reach either way), turned about it, flipped every
/// other pair.
std::vector<CurvedPair<proxima::Cone, proxima::Cone>> make_coaxial_cones(std::uint64_t seed) {
  return make_placed_pairs<proxima::Cone>(
      seed, [](proxima::test::Random& rng, const proxima::Cone& a, const proxima::Cone& b, const Transform& pa, int i) {
        proxima::Quat q = pa.rotation * glm::angleAxis(rng.uniform(Real(0), Real(6.283)), kAxisZ);
        if (i % 2 == 1) q = q * glm::angleAxis(proxima::kPi, kAxisX);
        const Real height = rng.uniform(Real(-1.8), Real(1.8)) * (a.half_length() + b.half_length());
        return Transform{pa.apply(height * kAxisZ), q};
      });
}

enum class Query { Intersect, Distance, Collide };

/// The closed form (public entry) or the generic path on every pair, in turn.
template <class A, class B>
void run(benchmark::State& state, const std::vector<CurvedPair<A, B>>& pairs, Query query, bool generic) {
  std::size_t i = 0;
  std::int64_t hits = 0;
  const proxima::PairRequest request{};
  for (auto _ : state) {
    const CurvedPair<A, B>& p = pairs[i];
    i = (i + 1) % pairs.size();
    if (query == Query::Intersect) {
      const bool hit = generic ? proxima::narrow::generic_intersect(p.a, p.pose_a, p.b, p.pose_b, request, nullptr)
                               : proxima::intersect(p.a, p.pose_a, p.b, p.pose_b, request);
      hits += hit ? 1 : 0;
    } else if (query == Query::Distance || generic) {
      const proxima::DistanceResult d =
          generic ? proxima::narrow::generic_distance(p.a, p.pose_a, p.b, p.pose_b, request, nullptr)
                  : proxima::distance(p.a, p.pose_a, p.b, p.pose_b, request);
      benchmark::DoNotOptimize(d);
      hits += d.signed_distance <= Real(0) ? 1 : 0;
    } else {
      const proxima::ContactManifold m = proxima::collide(p.a, p.pose_a, p.b, p.pose_b, request);
      benchmark::DoNotOptimize(m);
      hits += m.count > 0 ? 1 : 0;
    }
  }
  state.counters["hit_share"] =
      benchmark::Counter(double(hits) / double(std::max<std::int64_t>(state.iterations(), 1)));
}

template <class A, class B>
void register_kind(const std::string& name, const std::vector<CurvedPair<A, B>>& pairs) {
  const auto add = [&](const std::string& label, Query q, bool generic) {
    benchmark::RegisterBenchmark(("Curved/" + name + "/" + label).c_str(),
                                 [q, generic, &pairs](benchmark::State& s) { run(s, pairs, q, generic); });
  };
  add("Intersect/closed_form", Query::Intersect, false);
  add("Intersect/gjk", Query::Intersect, true);
  add("Distance/closed_form", Query::Distance, false);
  add("Distance/gjk_epa", Query::Distance, true);
  add("Collide/closed_form", Query::Collide, false);
}

bool register_curved(const std::string& /*dir*/) {
  static const auto cylinders = make_pairs<proxima::Cylinder>(901);
  static const auto cones = make_pairs<proxima::Cone>(902);
  static const auto ellipsoids = make_pairs<proxima::Ellipsoid>(903);
  static const auto parallel = make_parallel_cylinders(904);
  static const auto coaxial = make_coaxial_cones(905);
  register_kind("SphereCylinder", cylinders);
  register_kind("SphereCone", cones);
  register_kind("SphereEllipsoid", ellipsoids);
  register_kind("ParallelCylinders", parallel);
  register_kind("CoaxialCones", coaxial);
  return true;
}

}  // namespace

int main(int argc, char** argv) { return proxima::bench::run_benchmarks(argc, argv, register_curved); }
