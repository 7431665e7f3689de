/// @file bench_sprites.cpp
/// W9 sprite queries (shared/bench/FORMATS.md): the count * repeat = 100,000 queries of
/// sprites.txt materialised in order, timed all together, translation-only ones apart and
/// turned, scaled ones apart; each as the full answer (count and first pixel,
/// sprite_overlap) and as the boolean (sprites_overlap). Counters: time per query and the
/// sum of the counts (a checksum of the answers).

#include <proxima/d2/sprite_overlap.hpp>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "bench_main.hpp"
#include "support/sprite_workloads.hpp"

namespace proxima::bench {
namespace {

/// One query with its masks resolved; `turned` selects `placement_b` over `position_b`.
struct SpriteRecord {
  const d2::SpriteMask* a;
  d2::PixelPoint position_a;
  const d2::SpriteMask* b;
  d2::PixelPoint position_b;
  bool turned;
  d2::TurnedPlacement placement_b;
};

/// Which queries a benchmark runs.
enum class Subset { All, Translation, Turned };

std::vector<SpriteRecord> materialize(const SpriteWorkload& w, Subset subset) {
  std::vector<SpriteRecord> out;
  for (std::size_t k = 0; k < w.query_count(); ++k) {
    const SpriteQuery& q = w.query(k);
    if ((subset == Subset::Translation && q.turned) || (subset == Subset::Turned && !q.turned)) continue;
    const auto placement = d2::TurnedPlacement::create({q.xb, q.yb}, q.angle_degrees, q.scale).value();
    out.push_back({&w.masks[q.mask_a], {q.xa, q.ya}, &w.masks[q.mask_b], {q.xb, q.yb}, q.turned, placement});
  }
  return out;
}

std::uint64_t count_of(const SpriteRecord& r) {
  if (r.turned) return d2::sprite_overlap(*r.a, r.position_a, *r.b, r.placement_b).count;
  return d2::sprite_overlap(*r.a, r.position_a, *r.b, r.position_b).count;
}

bool overlaps(const SpriteRecord& r) {
  if (r.turned) return d2::sprites_overlap(*r.a, r.position_a, *r.b, r.placement_b);
  return d2::sprites_overlap(*r.a, r.position_a, *r.b, r.position_b);
}

void register_subset(const char* name, std::vector<SpriteRecord> records) {
  const auto shared = std::make_shared<const std::vector<SpriteRecord>>(std::move(records));
  benchmark::RegisterBenchmark((std::string("W9_sprites/count/") + name).c_str(), [shared](benchmark::State& state) {
    std::uint64_t total = 0;
    for (auto _ : state) {
      total = 0;
      for (const SpriteRecord& r : *shared) total += count_of(r);
      benchmark::DoNotOptimize(total);
    }
    state.counters["per_query"] = time_per_item(shared->size());
    state.counters["queries"] = static_cast<double>(shared->size());
    state.counters["pixels"] = static_cast<double>(total);
  });
  benchmark::RegisterBenchmark((std::string("W9_sprites/boolean/") + name).c_str(), [shared](benchmark::State& state) {
    std::uint64_t hits = 0;
    for (auto _ : state) {
      hits = 0;
      for (const SpriteRecord& r : *shared) hits += overlaps(r) ? 1 : 0;
      benchmark::DoNotOptimize(hits);
    }
    state.counters["per_query"] = time_per_item(shared->size());
    state.counters["queries"] = static_cast<double>(shared->size());
    state.counters["overlapping"] = static_cast<double>(hits);
  });
}

}  // namespace
}  // namespace proxima::bench

int main(int argc, char** argv) {
  using namespace proxima::bench;
  return run_benchmarks(argc, argv, [](const std::string& dir) {
    static const auto workload = read_sprite_workload(workload_path(dir, "sprites.txt"));
    if (!workload) return report_load_error(workload.error());
    register_subset("all", materialize(*workload, Subset::All));
    register_subset("translation", materialize(*workload, Subset::Translation));
    register_subset("turned", materialize(*workload, Subset::Turned));
    return true;
  });
}
