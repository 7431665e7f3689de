// proxima_bench_world2d: the 2D collision world's step on the W9 2D world (shared/bench
// FORMATS.md, W9 `world2d_mixed_20k.txt`: 20,000 moving circles, boxes, capsules and polygons
// and 44 static walls).
//
//   World2d/world2d_mixed_20k/<broadphase>/threads:<n>
//     one iteration = one frame of 1..F (cycling): every moving object moved to its frame-k
//     pose (W9 motion rule), then CollisionWorld::step (broad phase, narrow phase with
//     manifolds, events; continuous detection off: the W9 rule teleports objects through the
//     fold). The world is built at frame 0 before timing.
//     counters   pairs (touching pairs per frame, from the step's events)

#include <proxima/d2/collision_world.hpp>

#include <memory>
#include <string>
#include <vector>

#include "bench_main.hpp"
#include "support/world2d_workloads.hpp"

namespace pb = proxima::bench;
namespace d2 = proxima::d2;

namespace {

/// The W9 world and its objects' 2D shapes.
struct Scene {
  pb::World2d world;
  std::vector<d2::Shape> shapes;
};

void run_world2d(benchmark::State& state, const Scene* scene, const std::string& broadphase, std::size_t threads) {
  proxima::WorldSettings settings;
  settings.broadphase = broadphase;
  settings.continuous = false;
  d2::CollisionWorld world = d2::CollisionWorld::create(settings).value();
  const std::size_t n = scene->world.objects.size();
  std::vector<d2::ObjectHandle> handles;
  for (std::size_t i = 0; i < n; ++i) {
    const pb::World2dObject& o = scene->world.objects[i];
    d2::ObjectDesc desc{scene->shapes[i], pb::to_d2_pose(pb::pose2d_at_frame(scene->world, i, 0))};
    desc.kind = o.is_static ? d2::ObjectKind::Static : d2::ObjectKind::Moving;
    handles.push_back(world.add(desc).value());
  }
  proxima::ThreadPool pool(threads);
  proxima::Executor& executor = threads == 1 ? static_cast<proxima::Executor&>(proxima::serial_executor()) : pool;
  world.step(executor);
  int frame = 0;
  double pairs = 0;
  std::int64_t frames = 0;
  for (auto _ : state) {
    frame = frame % scene->world.frames + 1;
    for (std::size_t i = 0; i < n; ++i) {
      if (!scene->world.objects[i].is_static) {
        world.move(handles[i], pb::to_d2_pose(pb::pose2d_at_frame(scene->world, i, frame)));
      }
    }
    world.step(executor);
    pairs += static_cast<double>(world.events().begin.size() + world.events().persist.size());
    ++frames;
  }
  state.counters["pairs"] = frames > 0 ? pairs / static_cast<double>(frames) : 0;
}

bool register_world2d(const std::string& dir) {
  static Scene scene;
  auto read = pb::read_world2d(pb::workload_path(dir, "world2d_mixed_20k.txt"));
  if (!read) return pb::report_load_error(read.error());
  scene.world = std::move(read).value();
  for (const pb::World2dObject& o : scene.world.objects) {
    auto shape = pb::to_d2_shape(o.shape);
    if (!shape) return pb::report_load_error(shape.error());
    scene.shapes.push_back(std::move(shape).value());
  }
  for (const char* broadphase : {"tree", "sap", "grid", "mbp"}) {
    for (const std::size_t threads : {std::size_t(1), std::size_t(2)}) {
      const std::string name = "World2d/" + scene.world.name + "/" + broadphase + "/threads:" + std::to_string(threads);
      benchmark::RegisterBenchmark(name.c_str(), run_world2d, &scene, std::string(broadphase), threads)
          ->Unit(benchmark::kMillisecond)
          ->UseRealTime();
    }
  }
  return true;
}

}  // namespace

int main(int argc, char** argv) { return pb::run_benchmarks(argc, argv, register_world2d); }
