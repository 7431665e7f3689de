/// @file ray_batch.cpp
/// raycast_batch. Steps:
/// 1. Check the output size.
/// 2. Cut the rays into B equal contiguous blocks: B = min(4 x the executor's concurrency,
///    R / min_rays_per_task), at least 1; one block runs inline on the caller.
/// 3. The executor runs the blocks; each block casts its rays, writes only its own slice of
///    `hits` and adds its hit count to an atomic total (a sum: independent of the order).
/// The result is therefore independent of the executor, the thread count and scheduling.

#include <proxima/shapes/ray_batch.hpp>

#include <algorithm>
#include <atomic>
#include <string>

namespace proxima {
namespace {

std::size_t cast_range(const TriangleMesh& mesh, std::span<const BatchRay> rays, std::span<RayHit> hits,
                       FaceCulling culling, std::size_t begin, std::size_t end) {
  std::size_t count = 0;
  for (std::size_t i = begin; i < end; ++i) {
    const std::optional<RayHit> hit = mesh.raycast(rays[i].ray, rays[i].max_t, culling);
    if (hit) {
      hits[i] = *hit;
      ++count;
    } else {
      hits[i] = RayHit{};
    }
  }
  return count;
}

}  // namespace

Result<std::size_t> raycast_batch(const TriangleMesh& mesh, std::span<const BatchRay> rays, std::span<RayHit> hits,
                                  Executor& executor, const RayBatchOptions& options) {
  if (hits.size() < rays.size())
    return make_error(ErrorCode::InvalidArgument, "hits",
                      "room for " + std::to_string(hits.size()) + " results, " + std::to_string(rays.size()) + " rays");
  const std::size_t n = rays.size();
  const std::size_t per_task = std::max<std::size_t>(1, options.min_rays_per_task);
  const std::size_t blocks = std::max<std::size_t>(1, std::min(4 * executor.concurrency(), n / per_task));
  if (executor.concurrency() <= 1 || blocks <= 1) return cast_range(mesh, rays, hits, options.culling, 0, n);

  std::atomic<std::size_t> total{0};
  executor.run(blocks, [&](std::size_t first, std::size_t last) {
    std::size_t count = 0;
    for (std::size_t b = first; b < last; ++b) {
      count += cast_range(mesh, rays, hits, options.culling, n * b / blocks, n * (b + 1) / blocks);
    }
    total.fetch_add(count, std::memory_order_relaxed);
  });
  return total.load();
}

Result<std::size_t> raycast_batch(const TriangleMesh& mesh, std::span<const BatchRay> rays, std::span<RayHit> hits,
                                  const RayBatchOptions& options) {
  return raycast_batch(mesh, rays, hits, serial_executor(), options);
}

}  // namespace proxima
