// The memory-bound floor of the W7 primitive workloads (sphere_pairs.txt,
// capsule_pairs.txt): the count * repeat = 1,000,000 query records are materialised in
// proxima::Real and streamed from memory.
//   1. ReadBandwidth: sum every number of the records (the cost of touching the data);
//   2. SpherePairs: the cheapest exact test, |c1 - c2|^2 <= (r1 + r2)^2, hits counted;
//   3. CapsulePairs: the segment-segment distance of geometry/closest_points.hpp
//      (Ericson, Real-Time Collision Detection, 5.1.9) compared with (ra + rb)^2, and
//      the same with a plain inlined clamped closed form (non-robust) for comparison.
// Each reports ns per query (per_query), the hits of one pass, and the hits computed
// in double from the file's values (hits_double) for comparison.
#include <benchmark/benchmark.h>

#include <proxima/geometry/closest_points.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "bench_main.hpp"
#include "support/workloads.hpp"

namespace {

using proxima::Real;
using proxima::Vec3;
namespace pb = proxima::bench;

/// One sphere query in the benchmark's own representation (32 bytes in float).
struct SphereRecord {
  Vec3 c1;
  Real r1;
  Vec3 c2;
  Real r2;
};

/// One capsule query (56 bytes in float).
struct CapsuleRecord {
  Vec3 a0;
  Vec3 a1;
  Real ra;
  Vec3 b0;
  Vec3 b1;
  Real rb;
};

std::vector<SphereRecord> g_spheres;
std::vector<CapsuleRecord> g_capsules;
std::uint64_t g_sphere_hits_double = 0;
std::uint64_t g_capsule_hits_double = 0;

/// Sum of `count` Reals starting at `data`, with 8 independent accumulators so the loop
/// is bound by memory, not by the latency of one addition chain.
Real sum_all(const Real* data, std::size_t count) {
  std::array<Real, 8> acc{};
  std::size_t i = 0;
  for (; i + 8 <= count; i += 8) {
    for (int k = 0; k < 8; ++k) acc[k] += data[i + k];
  }
  for (; i < count; ++i) acc[0] += data[i];
  Real s = 0;
  for (const Real a : acc) s += a;
  return s;
}

template <class Record>
void read_bandwidth(benchmark::State& state, const std::vector<Record>* records) {
  static_assert(sizeof(Record) % sizeof(Real) == 0);
  const auto* data = reinterpret_cast<const Real*>(records->data());
  const std::size_t count = records->size() * (sizeof(Record) / sizeof(Real));
  for (auto _ : state) {
    Real s = sum_all(data, count);
    benchmark::DoNotOptimize(s);
  }
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations()) *
                          static_cast<std::int64_t>(records->size() * sizeof(Record)));
  state.counters["per_query"] = pb::time_per_item(records->size());
}

void sphere_pairs(benchmark::State& state) {
  std::uint64_t hits = 0;
  for (auto _ : state) {
    hits = 0;
    for (const SphereRecord& q : g_spheres) {
      const Vec3 d = q.c1 - q.c2;
      const Real r = q.r1 + q.r2;
      hits += glm::dot(d, d) <= r * r ? 1u : 0u;
    }
    benchmark::DoNotOptimize(hits);
  }
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations()) *
                          static_cast<std::int64_t>(g_spheres.size() * sizeof(SphereRecord)));
  state.counters["per_query"] = pb::time_per_item(g_spheres.size());
  state.counters["hits"] = static_cast<double>(hits);
  state.counters["hits_double"] = static_cast<double>(g_sphere_hits_double);
}

/// Squared distance of segments p0p1 and q0q1 by the plain clamped closed form (Ericson,
/// 5.1.9) inlined in Real: the speed a minimal non-robust version reaches, for comparison
/// with the library's robust one (which also handles huge coordinates and parallel
/// segments to rounding). Needs segments of non-zero length, as W7 has (>= 0.2).
Real plain_segment_distance_squared(const Vec3& p0, const Vec3& p1, const Vec3& q0, const Vec3& q1) {
  const Vec3 d1 = p1 - p0, d2 = q1 - q0, r = p0 - q0;
  const Real a = glm::dot(d1, d1), e = glm::dot(d2, d2), f = glm::dot(d2, r);
  const Real c = glm::dot(d1, r), b = glm::dot(d1, d2);
  const Real denom = a * e - b * b;
  Real s = denom > Real(0) ? std::clamp((b * f - c * e) / denom, Real(0), Real(1)) : Real(0);
  Real t = (b * s + f) / e;
  if (t < Real(0)) {
    t = Real(0);
    s = std::clamp(-c / a, Real(0), Real(1));
  } else if (t > Real(1)) {
    t = Real(1);
    s = std::clamp((b - c) / a, Real(0), Real(1));
  }
  const Vec3 d = (p0 + d1 * s) - (q0 + d2 * t);
  return glm::dot(d, d);
}

template <Real (*DistanceSquared)(const Vec3&, const Vec3&, const Vec3&, const Vec3&)>
void capsule_pairs(benchmark::State& state) {
  std::uint64_t hits = 0;
  for (auto _ : state) {
    hits = 0;
    for (const CapsuleRecord& q : g_capsules) {
      const Real r = q.ra + q.rb;
      hits += DistanceSquared(q.a0, q.a1, q.b0, q.b1) <= r * r ? 1u : 0u;
    }
    benchmark::DoNotOptimize(hits);
  }
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations()) *
                          static_cast<std::int64_t>(g_capsules.size() * sizeof(CapsuleRecord)));
  state.counters["per_query"] = pb::time_per_item(g_capsules.size());
  state.counters["hits"] = static_cast<double>(hits);
  state.counters["hits_double"] = static_cast<double>(g_capsule_hits_double);
}

Real library_segment_distance_squared(const Vec3& p0, const Vec3& p1, const Vec3& q0, const Vec3& q1) {
  return proxima::geometry::closest_points_segment_segment(p0, p1, q0, q1).distance_squared;
}

/// Segment distance in double for the reference hit count (Ericson 5.1.9, clamped).
double segment_distance_squared(const pb::Vec3d& p1, const pb::Vec3d& q1, const pb::Vec3d& p2, const pb::Vec3d& q2) {
  const glm::dvec3 a0(p1.x, p1.y, p1.z), a1(q1.x, q1.y, q1.z), b0(p2.x, p2.y, p2.z), b1(q2.x, q2.y, q2.z);
  const glm::dvec3 d1 = a1 - a0, d2 = b1 - b0, r = a0 - b0;
  const double a = glm::dot(d1, d1), e = glm::dot(d2, d2), f = glm::dot(d2, r);
  double s = 0, t = 0;
  if (a <= 1e-12 && e <= 1e-12) return glm::dot(r, r);
  if (a <= 1e-12) {
    t = std::clamp(f / e, 0.0, 1.0);
  } else {
    const double c = glm::dot(d1, r);
    if (e <= 1e-12) {
      s = std::clamp(-c / a, 0.0, 1.0);
    } else {
      const double b = glm::dot(d1, d2);
      const double denom = a * e - b * b;
      s = denom > 1e-12 ? std::clamp((b * f - c * e) / denom, 0.0, 1.0) : 0.0;
      t = (b * s + f) / e;
      if (t < 0) {
        t = 0;
        s = std::clamp(-c / a, 0.0, 1.0);
      } else if (t > 1) {
        t = 1;
        s = std::clamp((b - c) / a, 0.0, 1.0);
      }
    }
  }
  const glm::dvec3 d = (a0 + d1 * s) - (b0 + d2 * t);
  return glm::dot(d, d);
}

bool register_floor(const std::string& dir) {
  auto spheres = pb::read_sphere_pairs(pb::workload_path(dir, "sphere_pairs.txt"), pb::Materialize::No);
  if (!spheres) return pb::report_load_error(spheres.error());
  auto capsules = pb::read_capsule_pairs(pb::workload_path(dir, "capsule_pairs.txt"), pb::Materialize::No);
  if (!capsules) return pb::report_load_error(capsules.error());

  g_spheres = pb::materialize<SphereRecord>(*spheres, [](const pb::SpherePair& p) {
    return SphereRecord{pb::to_vec3(p.center1), static_cast<Real>(p.radius1), pb::to_vec3(p.center2),
                        static_cast<Real>(p.radius2)};
  });
  g_capsules = pb::materialize<CapsuleRecord>(*capsules, [](const pb::CapsulePair& p) {
    return CapsuleRecord{pb::to_vec3(p.a0), pb::to_vec3(p.a1), static_cast<Real>(p.radius_a),
                         pb::to_vec3(p.b0), pb::to_vec3(p.b1), static_cast<Real>(p.radius_b)};
  });
  for (const pb::SpherePair& p : spheres->distinct) {
    const double dx = p.center1.x - p.center2.x, dy = p.center1.y - p.center2.y, dz = p.center1.z - p.center2.z;
    const double r = p.radius1 + p.radius2;
    g_sphere_hits_double += dx * dx + dy * dy + dz * dz <= r * r ? spheres->repeat : 0;
  }
  for (const pb::CapsulePair& p : capsules->distinct) {
    const double r = p.radius_a + p.radius_b;
    g_capsule_hits_double += segment_distance_squared(p.a0, p.a1, p.b0, p.b1) <= r * r ? capsules->repeat : 0;
  }

  benchmark::RegisterBenchmark("Floor/ReadBandwidth/sphere_pairs", read_bandwidth<SphereRecord>, &g_spheres)
      ->Unit(benchmark::kMillisecond);
  benchmark::RegisterBenchmark("Floor/ReadBandwidth/capsule_pairs", read_bandwidth<CapsuleRecord>, &g_capsules)
      ->Unit(benchmark::kMillisecond);
  benchmark::RegisterBenchmark("Floor/SpherePairs", sphere_pairs)->Unit(benchmark::kMillisecond);
  benchmark::RegisterBenchmark("Floor/CapsulePairs", capsule_pairs<library_segment_distance_squared>)
      ->Unit(benchmark::kMillisecond);
  benchmark::RegisterBenchmark("Floor/CapsulePairs/plain_inline", capsule_pairs<plain_segment_distance_squared>)
      ->Unit(benchmark::kMillisecond);
  return true;
}

}  // namespace

int main(int argc, char** argv) { return pb::run_benchmarks(argc, argv, register_floor); }
