// The W9 2D shape pairs (the 20,000 pairs of polygons2d_pairs.txt) through Proxima's 2D
// narrow phase and Box2D 2.4 in the same run, shapes built before the timed loops:
//   D2Pairs/Distance/<set>/proxima   d2::distance (signed distance and witnesses);
//   D2Pairs/Distance/<set>/box2d     b2Distance on prebuilt proxies (exact radii,
//                                    useRadii = true), a fresh b2SimplexCache per call;
//   D2Pairs/Manifold/<set>/proxima   d2::collide with the contact distance of Box2D's skins;
//   D2Pairs/Manifold/<set>/box2d     the matching b2Collide* function on Box2D's shapes
//                                    (support/box2d_peers.hpp: polygons and edges with the
//                                    b2_polygonRadius skin).
// Sets: All (every pair for distance; for manifolds, the pairs Box2D has a function for,
// every pair but segment/capsule against segment/capsule) and PolygonPolygon (polygon or
// box on both sides). Each reports the time per query (per_query) and a count of the
// answers (overlaps or manifold points) so that the two sides can be compared.
#include <benchmark/benchmark.h>

#include <proxima/d2/narrowphase.hpp>

#include <cstdint>
#include <string>
#include <vector>

#include "bench_main.hpp"
#include "support/polygons2d_workloads.hpp"

#if PROXIMA_HAVE_BOX2D
#include "support/box2d_peers.hpp"
#endif

namespace {

namespace pb = proxima::bench;
namespace d2 = proxima::d2;
using proxima::Real;

/// The pairs of one set, in both libraries' forms.
struct PairSet {
  std::vector<pb::Polygons2dShapePair> proxima;  ///< the 2D module's shapes and poses
#if PROXIMA_HAVE_BOX2D
  std::vector<pb::Box2dShape> box2d;    ///< sides 2k and 2k + 1 of pair k
  std::vector<b2DistanceInput> inputs;  ///< proxies into `box2d` (built once it is complete)
#endif
  std::vector<Real> reach;  ///< contact distance of pair k: the sum of Box2D's skins
};

PairSet g_distance_all, g_distance_polygons, g_manifold_all, g_manifold_polygons;

bool is_polygon(const pb::Polygons2dShape& s) {
  return s.kind == pb::Polygons2dKind::Polygon || s.kind == pb::Polygons2dKind::Box;
}
bool is_edge(const pb::Polygons2dShape& s) {
  return s.kind == pb::Polygons2dKind::Segment || s.kind == pb::Polygons2dKind::Capsule;
}
Real skin(const pb::Polygons2dShape& s) { return s.kind == pb::Polygons2dKind::Circle ? Real(0) : Real(0.01); }

void add(PairSet& set, const pb::Polygons2dPair& raw, const pb::Polygons2dShapePair& shapes) {
  set.proxima.push_back(shapes);
  set.reach.push_back(skin(raw.a) + skin(raw.b));
#if PROXIMA_HAVE_BOX2D
  set.box2d.push_back(pb::make_box2d_shape(raw.a, raw.pose_a));
  set.box2d.push_back(pb::make_box2d_shape(raw.b, raw.pose_b));
#endif
}

void finish(PairSet& set) {
#if PROXIMA_HAVE_BOX2D
  for (std::size_t k = 0; k < set.proxima.size(); ++k) {
    set.inputs.push_back(pb::box2d_distance_input(set.box2d[2 * k], set.box2d[2 * k + 1]));
  }
#else
  (void)set;
#endif
}

void proxima_distance(benchmark::State& state, const PairSet* set) {
  std::uint64_t overlaps = 0;
  for (auto _ : state) {
    overlaps = 0;
    for (const pb::Polygons2dShapePair& p : set->proxima) {
      overlaps += d2::distance(p.a, p.pose_a, p.b, p.pose_b).signed_distance <= Real(0) ? 1u : 0u;
    }
    benchmark::DoNotOptimize(overlaps);
  }
  state.counters["per_query"] = pb::time_per_item(set->proxima.size());
  state.counters["overlaps"] = static_cast<double>(overlaps);
}

void proxima_manifold(benchmark::State& state, const PairSet* set) {
  std::uint64_t points = 0;
  for (auto _ : state) {
    points = 0;
    for (std::size_t k = 0; k < set->proxima.size(); ++k) {
      const pb::Polygons2dShapePair& p = set->proxima[k];
      points += std::uint64_t(d2::collide(p.a, p.pose_a, p.b, p.pose_b, set->reach[k]).count);
    }
    benchmark::DoNotOptimize(points);
  }
  state.counters["per_query"] = pb::time_per_item(set->proxima.size());
  state.counters["points"] = static_cast<double>(points);
}

#if PROXIMA_HAVE_BOX2D
void box2d_distance(benchmark::State& state, const PairSet* set) {
  std::uint64_t overlaps = 0;
  for (auto _ : state) {
    overlaps = 0;
    for (const b2DistanceInput& input : set->inputs) {
      b2SimplexCache cache;
      cache.count = 0;
      b2DistanceOutput output;
      b2Distance(&output, &cache, &input);
      overlaps += output.distance < 10.0f * b2_epsilon ? 1u : 0u;
    }
    benchmark::DoNotOptimize(overlaps);
  }
  state.counters["per_query"] = pb::time_per_item(set->inputs.size());
  state.counters["overlaps"] = static_cast<double>(overlaps);
}

void box2d_manifold(benchmark::State& state, const PairSet* set) {
  std::uint64_t points = 0;
  for (auto _ : state) {
    points = 0;
    for (std::size_t k = 0; k < set->inputs.size(); ++k) {
      const pb::Box2dShape& a = set->box2d[2 * k];
      const pb::Box2dShape& b = set->box2d[2 * k + 1];
      b2Manifold m;
      if (!pb::box2d_collide_ordered(a, b, m)) pb::box2d_collide_ordered(b, a, m);
      points += std::uint64_t(m.pointCount);
    }
    benchmark::DoNotOptimize(points);
  }
  state.counters["per_query"] = pb::time_per_item(set->inputs.size());
  state.counters["points"] = static_cast<double>(points);
}
#endif

void register_set(const std::string& name, void (*proxima)(benchmark::State&, const PairSet*),
                  [[maybe_unused]] void (*box2d)(benchmark::State&, const PairSet*), const PairSet& set) {
  benchmark::RegisterBenchmark((name + "/proxima").c_str(), proxima, &set);
#if PROXIMA_HAVE_BOX2D
  benchmark::RegisterBenchmark((name + "/box2d").c_str(), box2d, &set);
#endif
}

bool register_pairs(const std::string& dir) {
  const auto raw = pb::read_polygons2d_pairs(pb::workload_path(dir, "polygons2d_pairs.txt"));
  if (!raw) return pb::report_load_error(raw.error());
  const auto shapes = pb::to_d2_pairs(*raw);
  if (!shapes) return pb::report_load_error(shapes.error());
  for (std::size_t k = 0; k < raw->size(); ++k) {
    const pb::Polygons2dPair& r = (*raw)[k];
    const bool polygons = is_polygon(r.a) && is_polygon(r.b);
    add(g_distance_all, r, (*shapes)[k]);
    if (polygons) add(g_distance_polygons, r, (*shapes)[k]), add(g_manifold_polygons, r, (*shapes)[k]);
    if (!is_edge(r.a) || !is_edge(r.b)) add(g_manifold_all, r, (*shapes)[k]);
  }
  for (PairSet* set : {&g_distance_all, &g_distance_polygons, &g_manifold_all, &g_manifold_polygons}) finish(*set);
#if PROXIMA_HAVE_BOX2D
  const auto box2d_distance_fn = box2d_distance;
  const auto box2d_manifold_fn = box2d_manifold;
#else
  void (*box2d_distance_fn)(benchmark::State&, const PairSet*) = nullptr;
  void (*box2d_manifold_fn)(benchmark::State&, const PairSet*) = nullptr;
#endif
  register_set("D2Pairs/Distance/All", proxima_distance, box2d_distance_fn, g_distance_all);
  register_set("D2Pairs/Distance/PolygonPolygon", proxima_distance, box2d_distance_fn, g_distance_polygons);
  register_set("D2Pairs/Manifold/All", proxima_manifold, box2d_manifold_fn, g_manifold_all);
  register_set("D2Pairs/Manifold/PolygonPolygon", proxima_manifold, box2d_manifold_fn, g_manifold_polygons);
  return true;
}

}  // namespace

int main(int argc, char** argv) { return pb::run_benchmarks(argc, argv, register_pairs); }
