#pragma once
/// @file ray_batch.hpp
/// Batched ray casts: many rays against one TriangleMesh in one call, split over threads.
/// Each ray's answer is TriangleMesh::raycast's, so the output is identical whatever the
/// thread count (deterministic, equal to a serial loop).

#include <proxima/core/result.hpp>
#include <proxima/geometry/ray.hpp>
#include <proxima/shapes/triangle_mesh.hpp>

#include <cstddef>
#include <span>

namespace proxima {

/// One ray of a batch: the ray (mesh frame) and its largest parameter.
struct BatchRay {
  Ray ray;                ///< origin and direction, local frame of the mesh
  Real max_t = kRealMax;  ///< hits with t in [0, max_t] count
};

/// How raycast_batch runs.
struct RayBatchOptions {
  FaceCulling culling = FaceCulling::None;  ///< as in TriangleMesh::raycast
  /// Worker threads: 0 means std::thread::hardware_concurrency(); 1 runs on the calling
  /// thread only. The result does not depend on it.
  unsigned threads = 0;
  /// Fewer rays than this per thread use fewer threads (thread start-up costs ~10 us).
  std::size_t min_rays_per_thread = 256;
};

/// Closest hit of every ray: hits[i] is TriangleMesh::raycast(rays[i].ray, rays[i].max_t,
/// culling), or a RayHit with sub.triangle == kNoIndex (and t = 0) for a miss. Returns the
/// number of rays that hit. Errors: InvalidArgument ("hits") when hits is shorter than rays.
/// O(R log n / threads); the calling thread works as one of the threads; no allocation
/// besides the std::thread objects.
Result<std::size_t> raycast_batch(const TriangleMesh& mesh, std::span<const BatchRay> rays, std::span<RayHit> hits,
                                  const RayBatchOptions& options = {});

}  // namespace proxima
