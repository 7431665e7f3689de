// Running Proxima's parallel work on oneTBB: an Executor adapter over tbb::parallel_for, used
// for a broad phase's pair search and a batch of mesh ray casts. The answers equal the serial
// ones, whatever the executor. A game engine's job system plugs in the same way: run(count,
// task) splits [0, count) into jobs that call task(begin, end), and waits for them.
// Built only when CMake finds oneTBB (Debian: libtbb-dev).
#include <proxima/broadphase/dynamic_aabb_tree.hpp>
#include <proxima/core/executor.hpp>
#include <proxima/shapes/ray_batch.hpp>
#include <proxima/shapes/triangle_mesh.hpp>

#include <cstdio>
#include <oneapi/tbb/blocked_range.h>
#include <oneapi/tbb/parallel_for.h>
#include <oneapi/tbb/task_arena.h>
#include <random>
#include <vector>

/// proxima::Executor on a oneTBB task arena: run() is one tbb::parallel_for over [0, count)
/// inside the arena (TBB chooses the ranges and balances them by work stealing).
class TbbExecutor final : public proxima::Executor {
 public:
  /// An arena of `threads` threads (0: TBB's default, every hardware thread).
  explicit TbbExecutor(int threads = 0) : arena_(threads > 0 ? threads : oneapi::tbb::task_arena::automatic) {
    arena_.initialize();
  }
  /// The arena's thread count.
  std::size_t concurrency() const override { return std::size_t(arena_.max_concurrency()); }
  /// task(begin, end) over TBB's ranges of [0, count); returns when all have run.
  void run(std::size_t count, proxima::RangeTask task) override {
    arena_.execute([&] {
      oneapi::tbb::parallel_for(oneapi::tbb::blocked_range<std::size_t>(0, count),
                                [&](const oneapi::tbb::blocked_range<std::size_t>& r) { task(r.begin(), r.end()); });
    });
  }

 private:
  oneapi::tbb::task_arena arena_;
};

int main() {
  using namespace proxima;
  TbbExecutor tbb_executor;  // every hardware thread

  // Broad phase: 20,000 random boxes, every overlapping pair.
  std::mt19937 rng(1);
  std::uniform_real_distribution<float> where(-100, 100), size(0.2f, 2.5f);
  DynamicAabbTree tree;
  for (ProxyId id = 0; id < 20000; ++id) {
    // One draw per statement, so that the boxes do not depend on the compiler's order of
    // evaluation of arguments.
    const float cz = where(rng);
    const float cy = where(rng);
    const float cx = where(rng);
    const Vec3 c(cx, cy, cz);
    const float hz = size(rng);
    const float hy = size(rng);
    const float hx = size(rng);
    const Vec3 h(hx, hy, hz);
    tree.insert(id, {c - h, c + h}, id % 4 == 0 ? ProxyKind::Static : ProxyKind::Moving);
  }
  std::vector<ProxyPair> serial_pairs, tbb_pairs;
  tree.find_pairs(serial_pairs);
  tree.find_pairs(tbb_pairs, tbb_executor);

  // Ray casts: a 64 x 64 height field of triangles, 10,000 rays from above.
  IndexedMesh grid;
  const int n = 64;
  for (int y = 0; y <= n; ++y) {
    for (int x = 0; x <= n; ++x) grid.vertices.push_back(Vec3(Real(x), Real(y), Real((x * 7 + y * 3) % 5) * Real(0.1)));
  }
  for (int y = 0; y < n; ++y) {
    for (int x = 0; x < n; ++x) {
      const std::uint32_t a = std::uint32_t(y * (n + 1) + x), b = a + 1, c = a + std::uint32_t(n + 1), d = c + 1;
      grid.triangles.push_back({a, b, d});
      grid.triangles.push_back({a, d, c});
    }
  }
  const TriangleMesh mesh = TriangleMesh::create(grid).value();
  std::uniform_real_distribution<float> over(0, float(n));
  std::vector<BatchRay> rays(10000);
  for (BatchRay& r : rays) {
    const float y = over(rng);
    const float x = over(rng);
    r.ray = {Vec3(x, y, Real(10)), Vec3(0, 0, -1)};
  }
  std::vector<RayHit> serial_hits(rays.size()), tbb_hits(rays.size());
  const std::size_t serial_count = raycast_batch(mesh, rays, serial_hits).value();
  const std::size_t tbb_count = raycast_batch(mesh, rays, tbb_hits, tbb_executor).value();
  bool same_hits = serial_count == tbb_count;
  for (std::size_t i = 0; i < rays.size(); ++i) {
    same_hits =
        same_hits && serial_hits[i].t == tbb_hits[i].t && serial_hits[i].sub.triangle == tbb_hits[i].sub.triangle;
  }

  const bool same_pairs = serial_pairs == tbb_pairs;
  std::printf("oneTBB executor, %zu threads: %zu pairs (%s the serial run), %zu of %zu rays hit (%s the serial run)\n",
              tbb_executor.concurrency(), tbb_pairs.size(), same_pairs ? "equal to" : "DIFFERENT from", tbb_count,
              rays.size(), same_hits ? "equal to" : "DIFFERENT from");
  return same_pairs && same_hits ? 0 : 1;
}
