// proxima_bench_broadphase2d: every registered broad phase on the W9 2D world's rectangles
// (shared/bench FORMATS.md, W9 `world2d_mixed_20k.txt`), lifted to flat boxes (z = [0, 0]) as
// the 2D module hands them to the broad phase.
//
//   BroadPhase2d/world2d_mixed_20k/<structure>   (structures sorted by name)
//     one iteration = one frame of 1..F (F = frames= of the file, 100): update every box
//     (one batch update) and find every pair, through AnyBroadPhase (make_broadphase); the
//     structure is built at frame 0 (insert all, one find_pairs) before timing.
//     counters   pairs (per frame), check (1 when every frame's sorted pair list equals the
//                one of a sweep on x written here, 0 otherwise)
//
// Rectangles: each object's pose at frame k by the W9 motion rule (support/world2d_workloads,
// double precision), then a conservative bound of its shape: circle centre +- r; capsule2d,
// segment2d, polygon and box2d the rectangle of the transformed end points, vertices or
// corners grown by the radius; rounded outwards to proxima::Real. All are precomputed before
// timing. The pairs are those of the rectangles (not of the shapes): MANIFEST.txt's shape
// pair counts are lower.

#include <proxima/broadphase/any_broadphase.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include "bench_main.hpp"
#include "support/world2d_workloads.hpp"
#include "support/world_workloads.hpp"

namespace pb = proxima::bench;
using proxima::Aabb;
using proxima::ProxyPair;
using proxima::ProxyUpdate;
using proxima::Real;
using proxima::Vec3;

namespace {

/// The Real nearest below (down) or above (up) a double, so that the rounded interval
/// holds the exact one.
Real round_out(double v, bool up) {
  Real r = static_cast<Real>(v);
  if (up && static_cast<double>(r) < v) r = std::nextafter(r, std::numeric_limits<Real>::infinity());
  if (!up && static_cast<double>(r) > v) r = std::nextafter(r, -std::numeric_limits<Real>::infinity());
  return r;
}

/// The flat box (z = [0, 0]) bounding a W9 shape at a pose (see the file comment).
Aabb rectangle(const pb::World2dShape& shape, const pb::Pose2d& pose) {
  const double c = std::cos(pose.angle);
  const double s = std::sin(pose.angle);
  std::vector<pb::Vec2d> local = shape.points;
  if (shape.kind == pb::World2dShapeKind::Circle) local = {{0, 0}};
  if (shape.kind == pb::World2dShapeKind::Box2d) {
    const double hx = shape.half_extents.x;
    const double hy = shape.half_extents.y;
    local = {{-hx, -hy}, {hx, -hy}, {hx, hy}, {-hx, hy}};
  }
  double lo[2] = {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
  double hi[2] = {-lo[0], -lo[1]};
  for (const pb::Vec2d& l : local) {
    const double w[2] = {c * l.x - s * l.y + pose.position.x, s * l.x + c * l.y + pose.position.y};
    for (int k = 0; k < 2; ++k) {
      lo[k] = std::min(lo[k], w[k]);
      hi[k] = std::max(hi[k], w[k]);
    }
  }
  const double r = shape.radius;
  return {Vec3(round_out(lo[0] - r, false), round_out(lo[1] - r, false), 0),
          Vec3(round_out(hi[0] + r, true), round_out(hi[1] + r, true), 0)};
}

/// Every overlapping pair of `boxes` not both static, sorted: a sweep on x, independent of
/// the structures.
std::vector<ProxyPair> sweep_pairs(const std::vector<Aabb>& boxes, const pb::World2d& world) {
  std::vector<std::uint32_t> order(boxes.size());
  for (std::uint32_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(),
            [&](std::uint32_t a, std::uint32_t b) { return boxes[a].min.x < boxes[b].min.x; });
  std::vector<ProxyPair> pairs;
  for (std::size_t i = 0; i < order.size(); ++i) {
    const std::uint32_t a = order[i];
    for (std::size_t j = i + 1; j < order.size() && boxes[order[j]].min.x <= boxes[a].max.x; ++j) {
      const std::uint32_t b = order[j];
      if (world.objects[a].is_static && world.objects[b].is_static) continue;
      if (boxes[a].overlaps(boxes[b])) pairs.push_back({std::min(a, b), std::max(a, b)});
    }
  }
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

/// FNV-1a of a pair list.
std::uint64_t pair_hash(const std::vector<ProxyPair>& pairs) {
  std::uint64_t h = 1469598103934665603ull;
  for (const ProxyPair& p : pairs) {
    for (const std::uint32_t v : {p.lo, p.hi}) {
      h ^= v;
      h *= 1099511628211ull;
    }
  }
  return h;
}

/// The world's boxes at every frame, and the reference pair hash of each.
struct Frames {
  std::vector<std::vector<Aabb>> boxes;  // by frame, by object
  std::vector<std::uint64_t> reference;  // by frame
};

Frames compute_frames(const pb::World2d& world) {
  Frames f;
  for (int k = 0; k <= world.frames; ++k) {
    std::vector<Aabb> boxes(world.objects.size());
    for (std::size_t i = 0; i < boxes.size(); ++i) {
      boxes[i] = rectangle(world.objects[i].shape, pb::pose2d_at_frame(world, i, k));
    }
    f.reference.push_back(pair_hash(sweep_pairs(boxes, world)));
    f.boxes.push_back(std::move(boxes));
  }
  return f;
}

void frames_benchmark(benchmark::State& state, const pb::World2d* world, const Frames* frames, std::string name) {
  auto made = proxima::make_broadphase(name);
  if (!made) {
    state.SkipWithError(made.error().what().c_str());
    return;
  }
  proxima::AnyBroadPhase& s = **made;
  for (std::size_t i = 0; i < world->objects.size(); ++i) {
    const auto kind = world->objects[i].is_static ? proxima::ProxyKind::Static : proxima::ProxyKind::Moving;
    if (s.insert(proxima::ProxyId(i), frames->boxes[0][i], kind) != proxima::BroadPhaseStatus::Ok) {
      state.SkipWithError("a rectangle was rejected");
      return;
    }
  }
  std::vector<ProxyPair> pairs;
  s.find_pairs(pairs);
  std::vector<std::vector<ProxyUpdate>> updates(frames->boxes.size());
  for (std::size_t k = 1; k < updates.size(); ++k) {
    for (std::size_t i = 0; i < world->objects.size(); ++i) {
      if (!world->objects[i].is_static) updates[k].push_back({proxima::ProxyId(i), frames->boxes[k][i]});
    }
  }
  bool match = pair_hash(pairs) == frames->reference[0];
  std::size_t frame = 0;
  std::uint64_t total = 0;
  for (auto _ : state) {
    frame = frame % std::size_t(world->frames) + 1;
    s.update(updates[frame]);
    s.find_pairs(pairs);
    benchmark::DoNotOptimize(pairs.data());
    total += pairs.size();
    state.PauseTiming();
    match = match && pair_hash(pairs) == frames->reference[frame];
    state.ResumeTiming();
  }
  state.counters["pairs"] = benchmark::Counter(double(total), benchmark::Counter::kAvgIterations);
  state.counters["check"] = match ? 1 : 0;
}

bool register_2d(const std::string& dir) {
  static pb::World2d world;
  static Frames frames;
  auto read = pb::read_world2d(pb::workload_path(dir, "world2d_mixed_20k.txt"));
  if (!read) return pb::report_load_error(read.error());
  world = std::move(read).value();
  frames = compute_frames(world);
  std::vector<std::string_view> names = proxima::broadphase_names();
  std::sort(names.begin(), names.end());
  for (const std::string_view n : names) {
    const std::string bench_name = "BroadPhase2d/" + world.name + "/" + std::string(n);
    benchmark::RegisterBenchmark(bench_name.c_str(), frames_benchmark, &world, &frames, std::string(n))
        ->Iterations(world.frames)
        ->Unit(benchmark::kMillisecond);
  }
  return true;
}

}  // namespace

int main(int argc, char** argv) { return pb::run_benchmarks(argc, argv, register_2d); }
