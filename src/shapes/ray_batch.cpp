/// @file ray_batch.cpp
/// raycast_batch: splits the rays into equal contiguous ranges, one per thread (the calling
/// thread takes the first), each thread writing only its own slice of the output, so the
/// result is independent of the thread count and of scheduling.

#include <proxima/shapes/ray_batch.hpp>

#include <algorithm>
#include <string>
#include <thread>
#include <vector>

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
                                  const RayBatchOptions& options) {
  if (hits.size() < rays.size())
    return make_error(ErrorCode::InvalidArgument, "hits",
                      "room for " + std::to_string(hits.size()) + " results, " + std::to_string(rays.size()) + " rays");
  const std::size_t n = rays.size();
  std::size_t threads = options.threads != 0 ? options.threads : std::max(1u, std::thread::hardware_concurrency());
  const std::size_t per_thread = std::max<std::size_t>(1, options.min_rays_per_thread);
  threads = std::max<std::size_t>(1, std::min(threads, n / per_thread));
  if (threads <= 1) return cast_range(mesh, rays, hits, options.culling, 0, n);

  std::vector<std::size_t> counts(threads, 0);
  std::vector<std::thread> workers;
  workers.reserve(threads - 1);
  auto range_begin = [&](std::size_t k) { return n * k / threads; };
  for (std::size_t k = 1; k < threads; ++k) {
    workers.emplace_back(
        [&, k] { counts[k] = cast_range(mesh, rays, hits, options.culling, range_begin(k), range_begin(k + 1)); });
  }
  counts[0] = cast_range(mesh, rays, hits, options.culling, 0, range_begin(1));
  for (std::thread& w : workers) w.join();
  std::size_t total = 0;
  for (std::size_t c : counts) total += c;
  return total;
}

}  // namespace proxima
